#pragma once
// Sparsity pattern of the global matrices, built from element connectivity at the level of
// "entities" (mesh nodes, then interface nodes), so that every column of an entity's DOFs
// has the same sorted row set. Scattering an element matrix then needs one binary search
// per pair of entities instead of per pair of DOFs.
#include "ffr/preproc/assembly/assembly.hpp"

#include <vector>

namespace ffr::preproc::detail {

struct Pattern {
  Index num_dofs = 0, num_nodes = 0;
  std::vector<Index> ent_dof0;    ///< first DOF of each entity (-1 if it has none)
  std::vector<int> ent_ndof;      ///< DOFs of each entity
  std::vector<Index> adj_ptr;     ///< CSR: adjacent entities of each entity (sorted, self included)
  std::vector<Index> adj;
  std::vector<Index> adj_prefix;  ///< DOFs in the column before each adjacent entity
  std::vector<Index> col_ptr;     ///< CSC column starts of the DOF-level matrix
  std::vector<Index> node_col_ptr;  ///< CSC column starts of the node-level (scalar) matrix

  Index entity_of_dof(const FeModel& m, Index d) const;
  SparseMatrix make_matrix() const;       ///< zero-valued matrix with the DOF pattern
  SparseMatrix make_node_matrix() const;  ///< zero-valued num_nodes x num_nodes matrix
  /// A += Ae over the element's DOFs.
  void add(SparseMatrix& A, const std::vector<Index>& dofs, const Eigen::MatrixXd& Ae, const FeModel& m) const;
  /// Ms += the scalar part Me(3i, 3j) of a solid element's mass over its nodes.
  void add_node_scalar(SparseMatrix& Ms, const Index* nodes, int nn, const Eigen::MatrixXd& Me) const;

 private:
  Index find(Index col_entity, Index row_entity) const;  ///< position of row_entity in adj of col_entity
};

Pattern build_pattern(const FeModel& model, const std::vector<ElementRef>& refs);

}  // namespace ffr::preproc::detail
