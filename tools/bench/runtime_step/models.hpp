#pragma once
// Benchmark models built from synthetic SIDs (formats/synthetic.hpp) in a temporary directory.

#include "ffr/formats/synthetic.hpp"
#include "ffr/runtime/runtime.hpp"

#include <filesystem>
#include <string>

namespace bench {

/// A steel connecting rod (0.3 m, 8 x 8 mm, free-free chain of `points` masses, `modes` modes).
ffr::formats::synthetic::ChainParams rod_params(int points, int modes);

/// The chain's masses sit on its axis; a real bar of section b x h also has the rotary inertia
/// of its section (m h^2/12, m b^2/12 about the transverse axes' second moments), which keeps the
/// rotation about the bar's own axis from being massless. Added to /integrals/rrdm.
void add_section_inertia(ffr::formats::Sid& sid, double b, double h);

/// Slider-crank of the IVP Test Set geometry (crank 0.15 m, rod 0.3 m): rigid crank driven at
/// omega [rad/s], the flexible rod (SID file), rigid slider; revolute joints about z and a
/// prismatic guide (3 redundant conditions).
std::string slider_crank_json(const std::string& sid_file, double step, double end, double omega);

/// A fresh temporary directory.
std::filesystem::path temp_dir(const std::string& tag);

}  // namespace bench
