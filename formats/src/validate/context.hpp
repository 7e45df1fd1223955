#pragma once
// Internal to validate: the natural scales of a body and the helpers that record checks.
#include "ffr/formats/validate.hpp"

#include <Eigen/Core>

#include <cmath>
#include <initializer_list>
#include <string>
#include <vector>

namespace ffr::formats::validation {

/// Natural scales: m, a length L (radius of gyration about O), a mode amplitude phi
/// (RMS displacement of the largest mode, sqrt(max Me_kk / m)), and their products for
/// zeroth-, first- and second-order members.
struct Scales {
  double m = 1, L = 1, phi = 1;
  double t1() const { return m * phi; }       // Ct, mdCM.M1, Pdm
  double r1() const { return m * phi * L; }   // Cr.M0, J.M1, Gr, Oe.M0, rPdm
  double q2() const { return m * phi * phi; } // Me, Cr.M1, Ge, Oe.M1, PPdm
  double Ke = 1;                              // largest |Ke_kk|
};
Scales natural_scales(const Sid& s);

/// "[a,b," (open, for add_matrix to complete) and "[a,b]" (closed). Built by appending: GCC 12
/// warns falsely (-Wrestrict) on "[" + std::to_string(k).
inline std::string open_index(std::initializer_list<Eigen::Index> ix, const std::string& prefix = {}) {
  std::string s = prefix;
  s += '[';
  for (auto i : ix) {
    s += std::to_string(i);
    s += ',';
  }
  return s;
}
inline std::string index(std::initializer_list<Eigen::Index> ix, const std::string& prefix = {}) {
  std::string s = open_index(ix, prefix);
  s.back() = ']';
  return s;
}

/// The largest absolute entry of a difference and where it is.
struct Worst {
  double abs = 0;
  std::string at;
  void add(double v, const std::string& where) {
    const double a = std::isfinite(v) ? std::abs(v) : INFINITY;  // a NaN is the worst entry
    if (a > abs) {
      abs = a;
      at = where;
    }
  }
  template <class M>
  void add_matrix(const M& d, const std::string& prefix) {
    for (Eigen::Index r = 0; r < d.rows(); ++r)
      for (Eigen::Index c = 0; c < d.cols(); ++c) {
        const double a = std::isfinite(d(r, c)) ? std::abs(d(r, c)) : INFINITY;
        if (a > abs) {
          abs = a;
          at = prefix;
          at += std::to_string(r);
          at += ',';
          at += std::to_string(c);
          at += ']';
        }
      }
  }
};

class Context {
 public:
  Context(const Sid& s, const ValidateOptions& o, ValidationReport& r) : sid(s), opt(o), report_(r), sc(natural_scales(s)) {}
  const Sid& sid;
  const ValidateOptions& opt;

  void record(const std::string& name, const std::string& where, const Worst& w, double scale, double tol,
              Check::Kind kind = Check::Kind::Identity) {
    Check c;
    c.kind = kind;
    c.name = name;
    c.where = where;
    c.abs = w.abs;
    c.scale = scale > 0 && std::isfinite(scale) ? scale : 1.0;
    c.rel = c.abs / c.scale;
    c.tol = tol;
    c.pass = std::isfinite(c.rel) && c.rel <= tol;
    if (!w.at.empty() && c.abs > 0) c.note = "worst at " + w.at;
    report_.checks.push_back(c);
  }
  void record_value(const std::string& name, const std::string& where, double abs, double scale, bool pass,
                    const std::string& note = {}, Check::Kind kind = Check::Kind::Identity) {
    Check c;
    c.kind = kind;
    c.name = name;
    c.where = where;
    c.abs = abs;
    c.scale = scale > 0 && std::isfinite(scale) ? scale : 1.0;
    c.rel = abs / c.scale;
    c.pass = pass && std::isfinite(c.rel);
    c.note = note;
    report_.checks.push_back(c);
  }
  void skip(const std::string& name, const std::string& where, const std::string& why) {
    Check c;
    c.name = name;
    c.where = where;
    c.applicable = false;
    c.note = why;
    report_.checks.push_back(c);
  }
  void fail(const std::string& name, const std::string& where, const std::string& why) {
    Check c;
    c.name = name;
    c.where = where;
    c.pass = false;
    c.kind = Check::Kind::Property;  // members that cannot be read together
    c.abs = c.rel = 1;
    c.note = why;
    report_.checks.push_back(c);
  }

 private:
  ValidationReport& report_;

 public:
  const Scales sc;
};

// The groups of checks (one file each).
void check_members_vs_integrals(Context& cx);
void check_identities(Context& cx);
void check_properties(Context& cx);
void check_modal(Context& cx);

}  // namespace ffr::formats::validation
