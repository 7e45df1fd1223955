// Draws a Campbell diagram: one polyline per mode (ascending order at each speed), the
// once-per-revolution line f = Omega / 2pi dashed, axes with numbered ticks.
#include "ffr/formats/campbell.hpp"
#include "png.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace ffr::info {
namespace {

double nice_step(double range) {
  const double raw = range / 5, p = std::pow(10.0, std::floor(std::log10(raw))), r = raw / p;
  return (r < 1.5 ? 1 : r < 3.5 ? 2 : r < 7.5 ? 5 : 10) * p;
}

std::string label(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", std::abs(v) < 1e-12 ? 0.0 : v);
  return buf;
}

}  // namespace

Canvas plot_campbell(const formats::Campbell& c, const std::string& axis) {
  const int W = 900, H = 600, left = 90, right = 30, top = 50, bottom = 70;
  Canvas cv(W, H);
  const Rgb black{0, 0, 0}, grid{225, 225, 225}, grey{150, 150, 150};
  double x0 = *std::min_element(c.speeds_rad_s.begin(), c.speeds_rad_s.end());
  double x1 = *std::max_element(c.speeds_rad_s.begin(), c.speeds_rad_s.end());
  if (x1 <= x0) x1 = x0 + 1;
  double ymax = 0;
  for (const auto& row : c.frequency_hz)
    for (double f : row) ymax = std::max(ymax, f);
  ymax = ymax > 0 ? ymax * 1.08 : 1;
  auto X = [&](double v) { return left + (v - x0) / (x1 - x0) * (W - left - right); };
  auto Y = [&](double v) { return H - bottom - v / ymax * (H - top - bottom); };

  const double xs = nice_step(x1 - x0), ys = nice_step(ymax);
  for (double v = std::ceil(x0 / xs) * xs; v <= x1 + 1e-9 * xs; v += xs) {
    cv.line(X(v), top, X(v), H - bottom, grid);
    const std::string t = label(v);
    cv.text(static_cast<int>(X(v)) - Canvas::text_width(t) / 2, H - bottom + 10, t, black);
  }
  for (double v = 0; v <= ymax; v += ys) {
    cv.line(left, Y(v), W - right, Y(v), grid);
    const std::string t = label(v);
    cv.text(left - 10 - Canvas::text_width(t), static_cast<int>(Y(v)) - 7, t, black);
  }
  cv.line(left, top, left, H - bottom, black, 2);
  cv.line(left, H - bottom, W - right, H - bottom, black, 2);

  // Once per revolution: f = Omega / 2pi, clipped to the plot.
  const double fx1 = std::min(x1, ymax * 2 * M_PI);
  if (fx1 > std::max(x0, 0.0)) cv.line(X(std::max(x0, 0.0)), Y(std::max(x0, 0.0) / (2 * M_PI)), X(fx1), Y(fx1 / (2 * M_PI)), grey, 1, 6);

  static const Rgb palette[] = {{31, 119, 180}, {214, 39, 40}, {44, 160, 44}, {255, 127, 14},
                                {148, 103, 189}, {140, 86, 75}, {227, 119, 194}, {23, 190, 207}};
  const std::size_t nmodes = c.frequency_hz.empty() ? 0 : c.frequency_hz[0].size();
  for (std::size_t k = 0; k < nmodes; ++k) {
    const Rgb col = palette[k % 8];
    for (std::size_t s = 0; s < c.speeds_rad_s.size(); ++s) {
      const double px = X(c.speeds_rad_s[s]), py = Y(c.frequency_hz[s][k]);
      cv.fill_rect(static_cast<int>(px) - 2, static_cast<int>(py) - 2, static_cast<int>(px) + 2, static_cast<int>(py) + 2, col);
      if (s > 0) cv.line(X(c.speeds_rad_s[s - 1]), Y(c.frequency_hz[s - 1][k]), px, py, col, 2);
    }
  }
  const std::string title = "Campbell diagram, spin about " + axis;
  cv.text((W - Canvas::text_width(title)) / 2, 15, title, black);
  const std::string xl = "spin speed [rad/s]";
  cv.text((W - Canvas::text_width(xl)) / 2, H - 30, xl, black);
  cv.text(10, top - 30, "frequency [Hz]", black);
  return cv;
}

}  // namespace ffr::info
