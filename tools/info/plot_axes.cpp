#include "plot_axes.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace ffr::info {
namespace {

double nice_step(double range) {
  const double raw = range / 5, p = std::pow(10.0, std::floor(std::log10(raw))), r = raw / p;
  return (r < 1.5 ? 1 : r < 3.5 ? 2 : r < 7.5 ? 5 : 10) * p;
}

// Widens [lo, hi] to at least 1e-9 of its magnitude around its middle. A channel flat to its
// last bits far from zero (a coordinate a joint holds, at 1.0 +- 1 ulp) has a range below the
// spacing of doubles there: its tick step would not change a tick value it is added to, and
// its labels would all read the same.
void widen_to_resolvable(double& lo, double& hi) {
  const double least = 1e-9 * std::max(std::abs(lo), std::abs(hi));
  if (hi - lo >= least) return;
  const double mid = lo + (hi - lo) / 2;
  lo = mid - least / 2;
  hi = mid + least / 2;
}

// The tick value v printed with the significant digits that tell it from its neighbours a
// step away (at least 4), v's magnitude at most `magnitude`.
std::string label(double v, double step, double magnitude) {
  const int digits = std::clamp(static_cast<int>(std::ceil(std::log10(magnitude / step))) + 1, 4, 17);
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.*g", digits, std::abs(v) < 1e-9 * step ? 0.0 : v);
  return buf;
}

// Calls draw(v, text) for the ticks of [lo, hi] at multiples of step, counted rather than
// accumulated (a sum of steps drifts from the multiples), at most 100. Where the values need
// 6 digits or more to tell two ticks apart (a variation small against the values' magnitude),
// the labels are the difference to an offset, a tick value near the middle, which is returned
// for the axis to show ("+1000"); otherwise the labels are the values and the offset 0.
template <class Draw>
double draw_ticks(double lo, double hi, double step, Draw draw) {
  const double magnitude = std::max(std::abs(lo), std::abs(hi));
  const double offset = magnitude / step > 1e4 ? std::round((lo + (hi - lo) / 2) / step) * step : 0.0;
  const double first = std::ceil(lo / step);
  for (int k = 0; k <= 100; ++k) {
    const double v = (first + k) * step;
    if (!(v <= hi + 1e-9 * step)) break;
    draw(v, label(v - offset, step, offset != 0 ? hi - lo : magnitude));
  }
  return offset;
}

std::string offset_text(double offset, double step) {
  return offset == 0 ? std::string() : (offset > 0 ? "+" : "") + label(offset, step, std::abs(offset));
}

}  // namespace

Rgb series_colour(std::size_t k) {
  static const Rgb palette[] = {{31, 119, 180}, {214, 39, 40}, {44, 160, 44}, {255, 127, 14},
                                {148, 103, 189}, {140, 86, 75}, {227, 119, 194}, {23, 190, 207}};
  return palette[k % 8];
}

PlotArea draw_axes(Canvas& cv, PlotArea a, const std::string& title, const std::string& xlabel,
                   const std::string& ylabel) {
  const Rgb black{0, 0, 0}, grid{225, 225, 225};
  if (!std::isfinite(a.x1 - a.x0) || !std::isfinite(a.y1 - a.y0)) {
    char range[160];
    std::snprintf(range, sizeof range, "[%g, %g] x [%g, %g]", a.x0, a.x1, a.y0, a.y1);
    throw std::invalid_argument(std::string("a plot's range is not a finite number: ") + range);
  }
  if (!(a.x1 > a.x0)) a.x1 = a.x0 + 1;
  if (!(a.y1 > a.y0)) {
    const double d = std::abs(a.y0) > 0 ? 0.1 * std::abs(a.y0) : 1.0;
    a.y0 -= d;
    a.y1 += d;
  }
  widen_to_resolvable(a.x0, a.x1);
  widen_to_resolvable(a.y0, a.y1);
  const double xs = nice_step(a.x1 - a.x0), ys = nice_step(a.y1 - a.y0);
  const double x_offset = draw_ticks(a.x0, a.x1, xs, [&](double v, const std::string& t) {
    cv.line(a.X(v), a.top, a.X(v), a.bottom, grid);
    cv.text(static_cast<int>(a.X(v)) - Canvas::text_width(t) / 2, a.bottom + 10, t, black);
  });
  const double y_offset = draw_ticks(a.y0, a.y1, ys, [&](double v, const std::string& t) {
    cv.line(a.left, a.Y(v), a.right, a.Y(v), grid);
    cv.text(a.left - 10 - Canvas::text_width(t), static_cast<int>(a.Y(v)) - 7, t, black);
  });
  // The offsets as matplotlib shows them: the x axis's under its right end, the y axis's above
  // its top.
  const std::string xo = offset_text(x_offset, xs), yo = offset_text(y_offset, ys);
  cv.text(a.right - Canvas::text_width(xo), a.bottom + 32, xo, black);
  cv.text(a.left - 10 - Canvas::text_width(yo), a.top - 24, yo, black);
  cv.line(a.left, a.top, a.left, a.bottom, black, 2);
  cv.line(a.left, a.bottom, a.right, a.bottom, black, 2);
  cv.text((a.left + a.right - Canvas::text_width(title)) / 2, a.top - 35, title, black);
  cv.text((a.left + a.right - Canvas::text_width(xlabel)) / 2, a.bottom + 32, xlabel, black);
  cv.text(a.left - 80, a.top - 20, ylabel, black);
  return a;
}

// The legend name of component c of an n-component output of this type (the model file's output
// types, runtime/MODEL_FILE.md): kinetic/potential/total, x/y/z, mode numbers; [c] otherwise.
std::string component_name(const std::string& type, long c, long n) {
  static const std::map<std::string, std::vector<std::string>> names = {
      {"energy", {"kinetic", "potential", "total"}},
      {"node_position", {"x", "y", "z"}},
      {"node_deformation", {"x", "y", "z"}},
      {"node_velocity", {"x", "y", "z"}},
      {"body_angular_velocity", {"x", "y", "z"}},
      {"joint_reaction", {"Fx", "Fy", "Fz", "Mx", "My", "Mz"}}};
  if (const auto it = names.find(type); it != names.end() && static_cast<long>(it->second.size()) == n)
    return it->second[static_cast<std::size_t>(c)];
  std::string key = type == "modal_coordinates" ? "mode " : "[";
  key += std::to_string(type == "modal_coordinates" ? c + 1 : c);
  if (type != "modal_coordinates") key += ']';
  return key;
}

}  // namespace ffr::info
