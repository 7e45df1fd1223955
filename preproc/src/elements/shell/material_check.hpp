#pragma once
// User-input checks shared by the structural kernels (shells, beams): every message names the
// element kind and the offending field, so the assembly only has to add the element tag.

#include "ffr/preproc/elements/element.hpp"

#include <Eigen/Core>

#include <cmath>
#include <sstream>
#include <string>

namespace ffr::preproc::structural {

[[noreturn]] inline void fail(const std::string& who, const std::string& what) {
  throw ElementError(who + ": " + what);
}

inline std::string num(double v) {
  std::ostringstream s;
  s.precision(6);
  s << v;
  return s.str();
}

inline void check_positive(const std::string& who, const char* field, double v) {
  if (!std::isfinite(v) || !(v > 0)) fail(who, std::string(field) + " must be > 0 (got " + num(v) + ")");
}

inline void check_non_negative(const std::string& who, const char* field, double v) {
  if (!std::isfinite(v) || v < 0) fail(who, std::string(field) + " must be >= 0 (got " + num(v) + ")");
}

inline void check_material(const std::string& who, const Material& m) {
  check_positive(who, "E", m.E);
  if (!std::isfinite(m.nu) || !(m.nu > -1.0 && m.nu < 0.5))
    fail(who, "nu must lie in (-1, 0.5) (got " + num(m.nu) + ")");
  check_non_negative(who, "rho", m.rho);
}

inline void check_finite(const std::string& who, const Eigen::MatrixXd& x, const char* what) {
  if (!x.allFinite()) fail(who, std::string(what) + " contain NaN or infinity");
}

inline Eigen::Matrix3d skew(const Eigen::Vector3d& a) {
  Eigen::Matrix3d s;
  s << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
  return s;
}

}  // namespace ffr::preproc::structural
