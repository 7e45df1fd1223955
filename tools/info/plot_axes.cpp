#include "plot_axes.hpp"

#include <cmath>
#include <cstdio>
#include <map>
#include <vector>

namespace ffr::info {
namespace {

double nice_step(double range) {
  const double raw = range / 5, p = std::pow(10.0, std::floor(std::log10(raw))), r = raw / p;
  return (r < 1.5 ? 1 : r < 3.5 ? 2 : r < 7.5 ? 5 : 10) * p;
}

std::string label(double v, double step) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", std::abs(v) < 1e-9 * step ? 0.0 : v);
  return buf;
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
  if (!(a.x1 > a.x0)) a.x1 = a.x0 + 1;
  if (!(a.y1 > a.y0)) {
    const double d = std::abs(a.y0) > 0 ? 0.1 * std::abs(a.y0) : 1.0;
    a.y0 -= d;
    a.y1 += d;
  }
  const double xs = nice_step(a.x1 - a.x0), ys = nice_step(a.y1 - a.y0);
  for (double v = std::ceil(a.x0 / xs) * xs; v <= a.x1 + 1e-9 * xs; v += xs) {
    cv.line(a.X(v), a.top, a.X(v), a.bottom, grid);
    const std::string t = label(v, xs);
    cv.text(static_cast<int>(a.X(v)) - Canvas::text_width(t) / 2, a.bottom + 10, t, black);
  }
  for (double v = std::ceil(a.y0 / ys) * ys; v <= a.y1 + 1e-9 * ys; v += ys) {
    cv.line(a.left, a.Y(v), a.right, a.Y(v), grid);
    const std::string t = label(v, ys);
    cv.text(a.left - 10 - Canvas::text_width(t), static_cast<int>(a.Y(v)) - 7, t, black);
  }
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
