// Draws a Campbell diagram: one polyline per mode (ascending order at each speed), the
// once-per-revolution line f = Omega / 2pi dashed, axes with numbered ticks.
#include "ffr/formats/campbell.hpp"
#include "plot_axes.hpp"

#include <algorithm>
#include <cmath>

namespace ffr::info {

Canvas plot_campbell(const formats::Campbell& c, const std::string& axis) {
  const int W = 900, H = 600;
  Canvas cv(W, H);
  const Rgb grey{150, 150, 150};
  const double x0 = *std::min_element(c.speeds_rad_s.begin(), c.speeds_rad_s.end());
  const double x1 = *std::max_element(c.speeds_rad_s.begin(), c.speeds_rad_s.end());
  double ymax = 0;
  for (const auto& row : c.frequency_hz)
    for (double f : row) ymax = std::max(ymax, f);
  ymax = ymax > 0 ? ymax * 1.08 : 1;
  const PlotArea a = draw_axes(cv, PlotArea{90, 80, W - 30, H - 70, x0, x1, 0.0, ymax},
                               "Campbell diagram, spin about " + axis, "spin speed [rad/s]", "frequency [Hz]");

  // Once per revolution: f = Omega / 2pi, clipped to the plot.
  const double fx1 = std::min(a.x1, ymax * 2 * M_PI), fx0 = std::max(a.x0, 0.0);
  if (fx1 > fx0) cv.line(a.X(fx0), a.Y(fx0 / (2 * M_PI)), a.X(fx1), a.Y(fx1 / (2 * M_PI)), grey, 1, 6);

  const std::size_t nmodes = c.frequency_hz.empty() ? 0 : c.frequency_hz[0].size();
  for (std::size_t k = 0; k < nmodes; ++k) {
    const Rgb col = series_colour(k);
    for (std::size_t s = 0; s < c.speeds_rad_s.size(); ++s) {
      const double px = a.X(c.speeds_rad_s[s]), py = a.Y(c.frequency_hz[s][k]);
      cv.fill_rect(static_cast<int>(px) - 2, static_cast<int>(py) - 2, static_cast<int>(px) + 2, static_cast<int>(py) + 2, col);
      if (s > 0) cv.line(a.X(c.speeds_rad_s[s - 1]), a.Y(c.frequency_hz[s - 1][k]), px, py, col, 2);
    }
  }
  return cv;
}

}  // namespace ffr::info
