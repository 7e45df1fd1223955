#pragma once
// Colouring for the lock-free scatter of the assembly.
//
// Two sets of elements that share no entity (mesh node or interface node) write disjoint
// entries of K, M and Ms. Greedy colouring gives classes of such sets, so each class can be
// scattered by several threads at once without a lock; the classes run one after another.
// Why: the scatter was serialised under one mutex, and with two threads two thirds of the
// assembly's samples of the 100k-DOF plate were in it (perf), the second thread waiting.

#include "ffr/preproc/assembly/assembly.hpp"

#include <cstddef>
#include <vector>

namespace ffr::preproc::detail {

/// Elements in blocks of neighbours, and colour classes of blocks: no two blocks of a class
/// share an entity, so the blocks of a class can be scattered by several threads at once, each
/// block by one thread in its order.
///
/// Why blocks: the elements of one colour class are spread over the whole part, so in element
/// colouring each element's scatter met columns of K and M that no recent element had touched
/// (on the 100k-DOF plate the scatter took 0.45 s of the 1.2 s assembly at one thread, mostly
/// cache misses). The elements are sorted by their lowest entity, and the entities (mesh
/// nodes) are numbered along a space-filling curve (mesh/node_order.hpp), so the elements of
/// a block are neighbours and share most of the entries they write.
struct ElementBlocks {
  std::vector<std::size_t> order;      ///< element indices, block by block
  std::vector<std::size_t> block_ptr;  ///< block b is order[block_ptr[b], block_ptr[b + 1])
  std::vector<std::vector<std::size_t>> classes;  ///< block indices of each colour class
};
ElementBlocks color_blocks(const std::vector<std::vector<Index>>& ents, Index num_entities, std::size_t block_size);

}  // namespace ffr::preproc::detail
