// "roads": height profiles along a horizontal travel direction, for tyres (MODEL_FILE.md "Roads").
#include "parse.hpp"

#include <cmath>
#include <set>

namespace ffr::runtime::detail {

void parse_roads(const Field& root, ParseContext& ctx) {
  if (!root.has("roads")) return;
  Model& m = ctx.model;
  const Field list = root.at("roads");
  std::set<std::string> names;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const Field f = list.at(i);
    if (!f.is_object()) f.fail("expected an object");
    f.allow_only({"name", "direction", "s", "height", "interpolation"});
    Road r;
    r.name = f.at("name").string();
    if (r.name.empty()) f.at("name").fail("must not be empty");
    if (!names.insert(r.name).second) f.at("name").fail("duplicate road name '" + r.name + "'");
    // The height is measured against gravity, so gravity says which way is up.
    const double g = m.gravity.norm();
    if (!(g > 0)) f.fail("a road's height is measured against gravity: give a nonzero \"gravity\"");
    r.up = -m.gravity / g;
    const Field df = f.at("direction");
    const Vector3d dir = unit_axis(df);
    if (std::abs(dir.dot(r.up)) > 1e-6) df.fail("must be horizontal (normal to gravity)");
    r.direction = (dir - dir.dot(r.up) * r.up).normalized();
    const Field sf = f.at("s"), hf = f.at("height");
    const Eigen::VectorXd s = sf.vector(), h = hf.vector();
    if (s.size() < 2) sf.fail("needs at least two points");
    if (h.size() != s.size()) hf.fail("has " + std::to_string(h.size()) + " entries but s has " + std::to_string(s.size()));
    for (Eigen::Index k = 1; k < s.size(); ++k)
      if (!(s(k) > s(k - 1))) sf.fail("must be strictly increasing (entry " + std::to_string(k) + ")");
    // PCHIP by default: a continuous slope (the contact normal follows it) that never overshoots
    // the profile's points (MODEL_FILE.md "Roads"). Linear is refused: its slope jumps at every
    // point, and with it the tyre's normal and force, on which Newton cycles.
    Interpolation kind = Interpolation::Pchip;
    if (auto k = f.find("interpolation")) {
      kind = interpolation(*k);
      if (kind == Interpolation::Linear)
        k->fail("linear is not accepted for a road: its slope, and with it the tyre's contact normal and force, would jump at "
                "every point (use pchip, the default, or spline)");
    }
    r.profile = Table(s, Eigen::MatrixXd(h), kind);
    m.roads.push_back(std::move(r));
  }
}

}  // namespace ffr::runtime::detail
