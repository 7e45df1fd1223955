#include "bdf_beam.hpp"

#include <cmath>
#include <string>

namespace ffr::preproc::detail {

namespace {

bool is_so(const std::string& s) { return s == "YES" || s == "YESA" || s == "NO"; }

}  // namespace

// The card (Quick Reference Guide, PBEAM), by field number:
//   2 PID, 3 MID, 4 A, 5 I1, 6 I2, 7 I12, 8 J, 9 NSM of end A;
//   10-17 C1 ... F2 of end A (stress recovery points; the line may be left out);
//   then per further station SO, X/XB, A, I1, I2, I12, J, NSM and, for SO = YES, C1 ... F2;
//   then K1, K2, S1, S2, NSI(A), NSI(B), CW(A), CW(B) and M1(A) ... N2(B).
// A blank value of a station is end A's (end B) or interpolated between the ends (between):
// for a constant section every given value must be end A's.
BeamProps read_pbeam(const Fields& f) {
  BeamProps bp;
  bp.A = f.real(4, "A");
  // As PBAR's: I1 bends in plane 1 (the element's x-y plane): integral of y^2 dA, ffr's Iz.
  bp.Iz = f.real(5, "I1");
  bp.Iy = f.real(6, "I2");
  bp.J = f.real_or(8, "J", 0.0);
  if (!(bp.A > 0 && bp.Iy > 0 && bp.Iz > 0 && bp.J > 0)) f.fail("fields 4-6, 8 (A, I1, I2, J): must be positive");
  f.require_zero(7, "I12: give the section in its principal axes");
  f.require_zero(9, "NSM, non-structural mass");
  std::size_t k = 10;
  if (!is_so(f.raw(10))) k = 18;  // C1 ... F2 of end A: output only
  const struct {
    std::size_t offset;
    const char* name;
    double value;
  } section[] = {{2, "A", bp.A}, {3, "I1", bp.Iz}, {4, "I2", bp.Iy}, {5, "I12", 0.0}, {6, "J", bp.J}, {7, "NSM", 0.0}};
  while (k <= f.size() && is_so(f.raw(k))) {
    const double x = f.real(k + 1, "X/XB");
    if (!(x > 0 && x <= 1)) f.fail(Fields::at(k + 1) + " (X/XB): a station lies in (0, 1]");
    for (const auto& s : section) {
      const std::size_t field = k + s.offset;
      if (f.blank(field)) continue;
      const double v = f.real(field, s.name);
      if (std::abs(v - s.value) > 1e-9 * std::abs(s.value))
        f.fail(Fields::at(field) + " (" + s.name + " at X/XB = " + f.raw(k + 1) + "): '" + f.raw(field) +
               "' differs from end A's: tapered beams are not supported (ffr's beams have one section; "
               "split the beam into properties of constant section)");
    }
    k += f.raw(k) == "YES" ? 16 : 8;  // YESA and NO leave out the line of stress points
  }
  // K1, K2: blank is 1.0 for PBEAM (unlike PBAR, where blank is rigid in shear); 0.0 rigid.
  const double k1 = f.real_or(k, "K1", 1.0), k2 = f.real_or(k + 1, "K2", 1.0);
  if (k1 < 0 || k2 < 0)
    f.fail(Fields::at(k) + ", " + Fields::at(k + 1) + " (K1, K2): must be positive, 0 (rigid in shear) or blank");
  if (k1 > 0) bp.ky = k1;
  if (k2 > 0) bp.kz = k2;
  f.require_zero(k + 2, "S1, shear relief of a tapered beam");
  f.require_zero(k + 3, "S2, shear relief of a tapered beam");
  f.require_zero(k + 4, "NSI(A), inertia of non-structural mass");
  f.require_zero(k + 5, "NSI(B), inertia of non-structural mass");
  f.require_zero(k + 6, "CW(A), warping: ffr's beams do not warp");
  f.require_zero(k + 7, "CW(B), warping: ffr's beams do not warp");
  for (std::size_t i = k + 8; i < k + 12; ++i) f.require_zero(i, "M1, M2: an offset of the non-structural mass");
  for (std::size_t i = k + 12; i < k + 16; ++i) f.require_zero(i, "N1, N2: an offset of the neutral axis");
  f.require_blank(k + 16, f.size(), "PBEAM ends with the line of M1(A) ... N2(B)");
  return bp;
}

}  // namespace ffr::preproc::detail
