#pragma once
// Nastran's PBEAM as ffr's beam section: the constant section of end A, every further station
// the same (MSC Nastran Quick Reference Guide, PBEAM). Used by the bulk-data reader.
#include "bdf_cards.hpp"
#include "ffr/preproc/part/part.hpp"

namespace ffr::preproc::detail {

/// A, I1 -> Iz, I2 -> Iy, J and the shear factors K1 -> ky, K2 -> kz of a PBEAM card (blank:
/// 1.0, Nastran's default; 0.0: shear-rigid). Refuses, naming the field: a tapered section (a
/// station whose A, I1, I2, I12 or J differs from end A's), I12, non-structural mass and its
/// inertia, shear relief, warping and offsets of the non-structural mass or the neutral axis.
BeamProps read_pbeam(const Fields& f);

}  // namespace ffr::preproc::detail
