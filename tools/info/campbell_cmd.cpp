// ffr-info FILE --campbell x|y|z --speeds LIST [--json] [--png OUT]
#include "summary.hpp"

#include "ffr/cli/cli.hpp"
#include "ffr/cli/output_files.hpp"
#include "ffr/formats/campbell.hpp"
#include "ffr/formats/sid_io.hpp"
#include "png.hpp"

#include <cstdio>
#include <iostream>

namespace ffr::info {

Canvas plot_campbell(const formats::Campbell& c, const std::string& axis);  // campbell_plot.cpp

int run_campbell(const std::filesystem::path& file, const std::string& axis_name, const std::string& speeds_text,
                 bool json, const std::string& png) {
  int axis = 0;
  try {
    axis = formats::spin_axis_from_string(axis_name);
  } catch (const std::invalid_argument& e) {
    throw cli::UsageError(std::string("--campbell: ") + e.what());
  }
  const auto speeds = cli::Args::parse_list(speeds_text, "--speeds");
  if (!png.empty()) cli::check_outputs({{"--png", png}}, {{"the SID file", file}});
  const formats::Sid sid = formats::read_sid(file);
  formats::Campbell c;
  try {
    c = formats::campbell(sid, axis, speeds);
  } catch (const std::invalid_argument& e) {
    // A SID whose members give no Campbell diagram ("Me is not positive definite"): named.
    throw formats::FormatError(file.string(), "", e.what());
  }
  if (!png.empty()) write_png(plot_campbell(c, axis_name), png);

  if (json) {
    const nlohmann::ordered_json out = {{"speeds_rad_s", c.speeds_rad_s}, {"frequency_hz", c.frequency_hz}};
    std::cout << out.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
    return 0;
  }
  std::cout << file.string() << ": frequencies [Hz] spinning about " << axis_name << " through O (rotating frame)\n";
  std::printf("%14s", "speed [rad/s]");
  for (Eigen::Index k = 0; k < sid.nq(); ++k) std::printf(" %12s", ("mode " + std::to_string(k + 1)).c_str());
  std::printf("\n");
  for (std::size_t s = 0; s < c.speeds_rad_s.size(); ++s) {
    std::printf("%14.6g", c.speeds_rad_s[s]);
    for (double f : c.frequency_hz[s]) std::printf(" %12.6g", f);
    std::printf("\n");
  }
  if (!png.empty()) std::printf("diagram written to %s\n", png.c_str());
  std::fflush(stdout);
  return 0;
}

}  // namespace ffr::info
