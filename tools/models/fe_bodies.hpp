#pragma once
// Flexible bodies that keep their FE mass matrix beside their SID, for the co-rotational
// comparison (ffr::runtime::FullMass, runtime/src/bodies/body_fe_inertia.cpp): the SID's shape
// integrals and the FullMass come from the same FE model and the same modes, so the two inertia
// routes give the same motion.
//  - consistent_rod: the formats/ synthetic chain's stiffness (Euler-Bernoulli segments,
//    rotations condensed) with the consistent mass of its two-node bar elements,
//    m_e / 6 [[2, 1], [1, 2]] (x) I3, instead of the chain's lumped masses; free-free modes of
//    that pair (dense eigen-solve, so up to a few thousand DOF).
//  - solid_bar: a TET10 bar meshed and reduced by the preprocessor's library (the stages of
//    ffr-reduce), its FE mass matrix the assembled consistent one (Ms (x) I3).
#include "ffr/formats/sid.hpp"
#include "ffr/formats/synthetic.hpp"
#include "ffr/runtime/model.hpp"

#include <filesystem>
#include <memory>

namespace bench {

struct FeBody {
  ffr::formats::Sid sid;
  std::shared_ptr<const ffr::runtime::FullMass> full_mass;
  long dof = 0;  ///< translational DOF of the FE model (3 per node)
};

/// The chain of `p` with consistent bar masses; nodes and interfaces as the chain's.
FeBody consistent_rod(const ffr::formats::synthetic::ChainParams& p);

/// A steel bar along x from the origin (length, square section `side` centred on the x axis),
/// TET10 of mesh size `size`, free-free, `modes` modes, output nodes "A" (x = 0) and "B"
/// (x = length) on the axis. Reduced in `workdir`; cached there (SID and FE data) under a name
/// of the size and modes, and reused when present.
FeBody solid_bar(const std::filesystem::path& workdir, double length, double side, double size, int modes);

/// The same body with its first nq modes: the invariants' and the nodes' leading blocks, the
/// members recomputed (one reduction serves several mode counts).
FeBody first_modes(const FeBody& b, int nq);

}  // namespace bench
