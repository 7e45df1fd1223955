#pragma once
// A part's assembled stiffness and mass from another FE code (PartSpec::matrices), in place of
// ffr's assembly: read, checked and laid onto the model's DOFs (PART_FILE.md, "Assembled
// matrices").
//
// The model comes from the deck as for an own mesh (its elements say which nodes carry DOFs,
// its sets make the interfaces); only K and M are the file's. The inertia invariants are the
// node-based sums the assembly forms for solids (assemble.cpp, integrals.cpp): they need the
// file's M to be Ms (x) I3 on the nodes' translations, which a consistent solid mass and a
// lumped translational mass are; anything else is refused, as are rotational DOFs.
#include "ffr/preproc/assembly/assembly.hpp"
#include "ffr/preproc/model/fe_model.hpp"

#include <string>

namespace ffr::preproc::detail {

struct MatrixInput {
  Assembled fe;           ///< K, M (full symmetric storage), Ms and the rigid-body sums
  std::string mass_type;  ///< "lumped (diagonal)" or "consistent (coupled nodes)", as the file holds it
};

/// Reads part.matrices for `model` (built from the part's deck). Throws formats::FormatError
/// naming the file, the line and what was expected for: a malformed line, an index outside the
/// DOF map, a size other than the DOF map's, a DOF the deck's elements do not have (or one of
/// theirs without a row), an asymmetric matrix, a rotational DOF, a mass that is not
/// Ms (x) I3 or not positive definite.
MatrixInput read_matrix_input(const FeModel& model, const PartSpec& part);

}  // namespace ffr::preproc::detail
