#pragma once
// Checks a SID against the identities of formats/SPEC.md section
// 9: members consistent with the primitive integrals, the cross-member identities, symmetry
// and definiteness, and the identities that hold only for some references or mode types.
// Returns a report; never prints and never throws on a bad body (only sizes that make the
// members unreadable give a single failed "sizes" check).

#include "ffr/formats/sid.hpp"

#include <string>
#include <vector>

namespace ffr::formats {

struct ValidateOptions {
  /// Tolerance (relative to the natural scale) of identities that hold by construction:
  /// members vs integrals, the cross-member identities, symmetry.
  double identity_rtol = 1e-9;
  /// Tolerance of identities that hold only as well as an eigen-solve converged: Me = I,
  /// Ke = diag(omega^2), free-free Ct.M0 = Cr.M0 = 0, frequencies vs Ke/Me.
  double modal_rtol = 1e-6;
};

/// One identity. `abs` is the largest violation (an entry of the difference, or a negative
/// eigenvalue, ...), `scale` the natural scale it is measured against, rel = abs / scale.
struct Check {
  /// An identity between members (or with the integrals), or a property of one member that the
  /// equations of motion rely on (the mass positive, a matrix symmetric or (semi-)definite):
  /// a body failing a property has no physical meaning, one failing an identity may still be
  /// integrated with its members as given.
  enum class Kind { Identity, Property };
  std::string name;         ///< stable identifier, e.g. "Gr + Gr^T = 2 J.M1"
  std::string where;        ///< the members involved, e.g. "/sid/Gr/M0 /sid/J/M1"
  bool applicable = true;   ///< false: does not apply to this body (see note); not a failure
  std::string note;         ///< why not applicable, or the worst entry
  double abs = 0.0;
  double scale = 1.0;
  double rel = 0.0;
  double tol = 0.0;
  bool pass = true;
  Kind kind = Kind::Identity;
};

struct ValidationReport {
  std::vector<Check> checks;
  bool ok() const;
  int failures() const;
  /// The check of that name, or nullptr.
  const Check* find(const std::string& name) const;
};

ValidationReport validate(const Sid& sid, const ValidateOptions& options = {});

}  // namespace ffr::formats
