#pragma once
// Element colouring for the lock-free scatter of the assembly.
//
// Two elements that share no entity (mesh node or interface node) write disjoint entries of K,
// M and Ms. Greedy colouring in element order gives classes of such elements, so each class can
// be scattered by several threads at once without a lock; the classes run one after another.
// Why: the scatter was serialised under one mutex, and with two threads two thirds of the
// assembly's samples of the 100k-DOF plate were in it (perf), the second thread waiting.

#include "ffr/preproc/assembly/assembly.hpp"

#include <cstddef>
#include <vector>

namespace ffr::preproc::detail {

/// Classes of element indices (into ents) with no entity in common within a class, each in
/// increasing order. ents[e] lists the entities element e writes to; num_entities bounds them.
std::vector<std::vector<std::size_t>> color_elements(const std::vector<std::vector<Index>>& ents, Index num_entities);

}  // namespace ffr::preproc::detail
