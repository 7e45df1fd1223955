#pragma once
// Shape-integral invariants of a reduced body (formats/SPEC.md sections 6-8):
//  1. compute_integrals(): the primitive integrals (m, rdm, rrdm, Pdm, rPdm, PPdm) and the
//     rotary part, exact for the consistent mass: solids through the scalar mass matrix Ms
//     (their mass is Ms (x) I3 and positions are interpolated isoparametrically), shells,
//     beams and attached masses through their exact mass samples (fibres off the node move
//     with u + psi x e: Wagner & Pfeiffer's correction, docs/references.md), and mass that no material point carries
//     (a shell's drilling inertia) through its rotary part.
//  2. members_from_integrals(): every SID member of SPEC.md section 6 from those integrals.

#include "ffr/formats/sid.hpp"
#include "ffr/preproc/assembly/assembly.hpp"

namespace ffr::preproc {

/// Fills sid.refmod.mass, sid.integrals and sid.rotary for the modes Phi (full DOFs x nq).
/// `elements`: the shells, beams and masses whose samples are summed (null: all of them), for
/// a rank of a distributed reduction whose fe holds its own elements' Ms (the integrals are
/// sums over the elements, so the ranks' results add up to the whole body's).
void compute_integrals(const FeModel& model, const Assembled& fe, const Eigen::MatrixXd& Phi, formats::Sid& sid,
                       const std::vector<ElementRef>* elements = nullptr);

/// Fills mdCM, J, Ct.M0, Cr, Gr, Ge, Oe and Me from sid.refmod.mass, sid.integrals and
/// sid.rotary. The rotary part enters J.M0, Cr.M0 and Me (its higher-order terms, of the
/// size of a shell's drilling regularisation, are neglected).
void members_from_integrals(formats::Sid& sid);

}  // namespace ffr::preproc
