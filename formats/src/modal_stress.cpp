// The optional /stress group (SPEC.md section 12.1): writing, strict reading, and the
// equivalent and principal stresses of a recovered stress.
#include "ffr/formats/modal_stress.hpp"

#include "ffr/formats/h5.hpp"
#include "ffr/formats/sid.hpp"

#include <Eigen/Eigenvalues>

#include <cmath>
#include <stdexcept>

namespace ffr::formats {
namespace {
using u64 = std::uint64_t;
}

void check_modal_stress(const ModalStress& s, std::int64_t nq) {
  const auto ns = static_cast<Eigen::Index>(s.node.size());
  auto bad = [](const std::string& what) { throw std::invalid_argument("SID member stress." + what); };
  if (ns == 0) bad("node: no nodes");
  if (s.position.rows() != ns) bad("position has the wrong size");
  if (static_cast<std::int64_t>(s.modes.size()) != nq) bad("modes has the wrong size (one [Ns,6] block per mode)");
  for (const auto& m : s.modes) {
    if (m.rows() != ns) bad("modes has the wrong size");
    if (!m.allFinite()) bad("modes: a value is not finite");
  }
  if (!s.position.allFinite()) bad("position: a value is not finite");
  if (!s.layer.empty()) {
    if (static_cast<Eigen::Index>(s.layer.size()) != ns) bad("layer has the wrong size (one value per node row)");
    for (const auto l : s.layer)
      if (l < kSolid || l > kShellBottom) bad("layer: a value is not 0 (solid), 1 (top), 2 (middle) or 3 (bottom)");
    if (s.normal.rows() != ns) bad("normal has the wrong size (one row per node row)");
    if (!s.normal.allFinite()) bad("normal: a value is not finite");
  }
}

const char* layer_name(std::int64_t layer) {
  switch (layer) {
    case kSolid: return "solid";
    case kShellTop: return "top";
    case kShellMiddle: return "middle";
    case kShellBottom: return "bottom";
    default: throw std::invalid_argument("stress layer " + std::to_string(layer) + " is not 0, 1, 2 or 3");
  }
}

void write_modal_stress(h5::Writer& w, const ModalStress& s) {
  const u64 ns = s.node.size(), nq = s.modes.size();
  w.write("/stress/node", s.node.data(), {ns});
  w.write("/stress/position", s.position.data(), {ns, 3});
  std::vector<double> modes;
  modes.reserve(nq * ns * 6);
  for (const auto& m : s.modes) modes.insert(modes.end(), m.data(), m.data() + m.size());
  w.write("/stress/modes", modes.data(), {nq, ns, 6});
  if (!s.layer.empty()) {  // only with shell rows: a solid-only group is written as before
    w.write("/stress/layer", s.layer.data(), {ns});
    w.write("/stress/normal", s.normal.data(), {ns, 3});
  }
  w.attr("/stress", "selection", s.selection);
  w.attr("/stress", "recovery", s.recovery);
}

std::optional<ModalStress> read_modal_stress(const std::filesystem::path& path) {
  h5::Reader r(path);
  r.set_max_magnitude(kMaxInputMagnitude);
  if (!r.has_attr("/", "format") || r.attr_string("/", "format") != kFormatName)
    r.fail("/@format", "not a SID file");
  const auto version = r.attr_int("/", "format_version");
  if (version < 1 || version > kFormatVersion)
    r.fail("/@format_version", "unsupported format_version " + std::to_string(version));
  if (version >= 2) r.require_checksums();
  if (!r.exists("/stress")) return std::nullopt;
  const h5::Shape fs = r.shape("/refmod/frequency_hz");
  if (fs.size() != 1) r.fail("/refmod/frequency_hz", "wrong shape: expected rank 1, found " + h5::shape_string(fs));
  const u64 nq = fs[0];
  const h5::Shape ss = r.shape("/stress/node");
  if (ss.size() != 1 || ss[0] == 0) r.fail("/stress/node", "wrong shape: expected [Ns] with Ns >= 1, found " + h5::shape_string(ss));
  const u64 ns = ss[0];
  if (ns * 8 > r.file_bytes()) r.fail("/stress/node", "dataset larger than the file");
  ModalStress s;
  s.node.resize(ns);
  r.read("/stress/node", {ns}, s.node.data());
  const auto pos = r.read_array("/stress/position", {ns, 3});
  s.position = Eigen::Map<const ModalStress::RowsX3>(pos.data(), static_cast<Eigen::Index>(ns), 3);
  const auto m = r.read_array("/stress/modes", {nq, ns, 6});
  for (u64 k = 0; k < nq; ++k)
    s.modes.emplace_back(Eigen::Map<const ModalStress::RowsX6>(m.data() + k * ns * 6, static_cast<Eigen::Index>(ns), 6));
  if (r.exists("/stress/layer")) {
    s.layer.resize(ns);
    r.read("/stress/layer", {ns}, s.layer.data());
    for (const auto l : s.layer)
      if (l < kSolid || l > kShellBottom)
        r.fail("/stress/layer", "value " + std::to_string(l) + " is not 0 (solid), 1 (top), 2 (middle) or 3 (bottom)");
    const auto n = r.read_array("/stress/normal", {ns, 3});
    s.normal = Eigen::Map<const ModalStress::RowsX3>(n.data(), static_cast<Eigen::Index>(ns), 3);
  }
  s.selection = r.has_attr("/stress", "selection") ? r.attr_string("/stress", "selection") : "";
  s.recovery = r.has_attr("/stress", "recovery") ? r.attr_string("/stress", "recovery") : "";
  if (version >= 2) r.verify_content();
  return s;
}

double von_mises(const Eigen::Matrix<double, 6, 1>& s) {
  const double a = s[0] - s[1], b = s[1] - s[2], c = s[2] - s[0];
  return std::sqrt(0.5 * (a * a + b * b + c * c) + 3 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]));
}

Eigen::Vector3d principal_stresses(const Eigen::Matrix<double, 6, 1>& s) {
  Eigen::Matrix3d S;
  S << s[0], s[3], s[5], s[3], s[1], s[4], s[5], s[4], s[2];
  const Eigen::Vector3d e = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(S, Eigen::EigenvaluesOnly).eigenvalues();
  return {e[2], e[1], e[0]};
}

}  // namespace ffr::formats
