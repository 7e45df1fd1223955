// validate(): runs every group of checks on a body whose sizes are consistent.
#include "context.hpp"

#include "ffr/formats/sid_io.hpp"

#include <algorithm>
#include <stdexcept>

namespace ffr::formats {

bool ValidationReport::ok() const { return failures() == 0; }

int ValidationReport::failures() const {
  return static_cast<int>(std::count_if(checks.begin(), checks.end(), [](const Check& c) { return c.applicable && !c.pass; }));
}

const Check* ValidationReport::find(const std::string& name) const {
  for (const auto& c : checks)
    if (c.name == name) return &c;
  return nullptr;
}

namespace validation {

Scales natural_scales(const Sid& s) {
  Scales sc;
  const double m = s.refmod.mass;
  sc.m = m > 0 && std::isfinite(m) ? m : 1.0;
  const double trJ = s.J.M0.trace();
  sc.L = trJ > 0 && std::isfinite(trJ) ? std::sqrt(trJ / (2 * sc.m)) : 1.0;
  double me = 0, ke = 0;
  for (Eigen::Index k = 0; k < s.Me.rows(); ++k) me = std::max(me, std::abs(s.Me(k, k)));
  for (Eigen::Index k = 0; k < s.Ke.rows(); ++k) ke = std::max(ke, std::abs(s.Ke(k, k)));
  sc.phi = me > 0 && std::isfinite(me) ? std::sqrt(me / sc.m) : 1.0;
  sc.Ke = ke > 0 && std::isfinite(ke) ? ke : 1.0;
  return sc;
}

}  // namespace validation

ValidationReport validate(const Sid& sid, const ValidateOptions& options) {
  ValidationReport report;
  validation::Context cx(sid, options, report);
  try {
    check_sizes(sid);
  } catch (const std::invalid_argument& e) {
    cx.fail("sizes consistent with nq and the nodes", "", e.what());
    return report;
  }
  validation::check_properties(cx);
  validation::check_members_vs_integrals(cx);
  validation::check_identities(cx);
  validation::check_modal(cx);
  return report;
}

}  // namespace ffr::formats
