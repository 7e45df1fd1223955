#pragma once
// Sparsity pattern of the global matrices, built from element connectivity at the level of
// "entities" (mesh nodes, then interface nodes), so that every column of an entity's DOFs
// has the same sorted row set. Placing an element then needs one binary search per pair of
// its entities instead of per pair of DOFs; the placement is computed by the worker threads
// and shared by K, M and the scalar mass Ms, so the serial scatter is only additions.
#include "ffr/preproc/assembly/assembly.hpp"

#include <vector>

namespace ffr::preproc::detail {

/// Where an element's matrices go: its distinct entities (in first-seen order), per element
/// DOF the entity (local index), the offset in it and the start of its global column, and per
/// pair of local entities (column-major) the position in Pattern::adj.
struct Placement {
  std::vector<Index> ents;
  std::vector<int> ent_of;
  std::vector<Index> off, col0;
  std::vector<Index> slot;
};

struct Pattern {
  Index num_dofs = 0, num_nodes = 0;
  std::vector<Index> ent_dof0;    ///< first DOF of each entity (-1 if it has none)
  std::vector<int> ent_ndof;      ///< DOFs of each entity
  std::vector<Index> adj_ptr;     ///< CSR: adjacent entities of each entity (sorted, self included)
  std::vector<Index> adj;
  std::vector<Index> adj_prefix;  ///< DOFs in the column before each adjacent entity
  std::vector<Index> col_ptr;     ///< CSC column starts of the DOF-level matrix
  std::vector<Index> node_col_ptr;  ///< CSC column starts of the node-level (scalar) matrix's upper triangle

  Index entity_of_dof(const FeModel& m, Index d) const;
  /// A = the matrix with the DOF pattern, every stored value `value` (0 for K and M before the
  /// scatter, 1 for a structure alone), filled by up to `threads` threads. Filled in place:
  /// Eigen 3.4's SparseMatrix has no move assignment, so `out.K = make()` copied K and M whole
  /// (245 MB of fresh pages on the 100k plate).
  void make_matrix(SparseMatrix& A, unsigned threads = 1, double value = 0.0) const;
  void make_node_matrix(SparseMatrix& A) const;  ///< zero-valued num_nodes x num_nodes upper triangle
  /// The placement of an element with these global DOFs.
  Placement place(const std::vector<Index>& dofs, const FeModel& m) const;
  /// A += Ae over the element's DOFs.
  void add(SparseMatrix& A, const Placement& p, const Eigen::MatrixXd& Ae) const;
  /// Ms += the scalar part Me(3a, 3b) of a solid element's mass (three DOFs per node, its
  /// entities are its mesh nodes), upper triangle (node a <= node b).
  void add_node_scalar(SparseMatrix& Ms, const Placement& p, const Eigen::MatrixXd& Me) const;

 private:
  Index find(Index col_entity, Index row_entity) const;  ///< position of row_entity in adj of col_entity
};

Pattern build_pattern(const FeModel& model, const std::vector<ElementRef>& refs);

}  // namespace ffr::preproc::detail
