#pragma once
// An ancf beam's frame, held at the global frame by its block of twelve linear rows
// (Body::held_frame, FORMULATION.md 15), is known while driven bodies are eliminated, like a
// driven body's pose: r0 = 0, A = I, at rest. Its twelve coordinates are then not unknowns of the
// step (set_unknowns, drive_bodies) and its block is not among the active rows (finalize). Why:
// the frame couples with every nodal coordinate in the mass matrix, so among the unknowns it
// made the tangent of the otherwise banded beam dense, and its LU with it. A plate keeps its
// frame among the unknowns: its edge supports are further rows of the same block.
#include "ffr/runtime/model.hpp"

namespace ffr::runtime::detail {

inline bool frame_known(const Model& model, const Body& b) { return b.beam != nullptr && model.settings.eliminate_driven; }

/// The first of a body's frame coordinates [first, 12) that are known, not integrated: 0 for a
/// known frame (above), 3 for a locked one (Body::frame_locked: its rotation), 12 for none.
inline int first_known_frame_coord(const Model& model, const Body& b) {
  return frame_known(model, b) ? 0 : b.frame_locked ? 3 : 12;
}

}  // namespace ffr::runtime::detail
