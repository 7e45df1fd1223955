#pragma once
// Axes shared by ffr-info's plots: a rectangle of the canvas mapped to data ranges, with a grid,
// numbered ticks at "nice" steps, a title and axis labels.
#include "png.hpp"

#include <string>

namespace ffr::info {

struct PlotArea {
  int left, top, right, bottom;  ///< pixel rectangle of the data area
  double x0, x1, y0, y1;         ///< data ranges mapped onto it
  double X(double v) const { return left + (v - x0) / (x1 - x0) * (right - left); }
  double Y(double v) const { return bottom - (v - y0) / (y1 - y0) * (bottom - top); }
};

/// Draws the grid, ticks, frame and labels of `area` (ranges widened when empty).
PlotArea draw_axes(Canvas& cv, PlotArea area, const std::string& title, const std::string& xlabel,
                   const std::string& ylabel);

/// The legend name of component c of an n-component output of the model file's output `type`:
/// kinetic/potential/total (energy), x/y/z (positions, deformations, velocities), Fx..Mz (joint
/// reactions), "mode k" (modal coordinates, k from 1); [c] for other types.
std::string component_name(const std::string& type, long c, long n);

/// The eight line colours of the plots (matplotlib's "tab10" order).
Rgb series_colour(std::size_t k);

}  // namespace ffr::info
