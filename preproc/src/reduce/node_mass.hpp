#pragma once
// The block Lanczos's products with the eigen-solve's mass matrix, from the solids' scalar
// node mass Ms instead of the DOF-level M (solver/eigen_solver.hpp, EigenOptions::mass_product).
//
// Why: a solid's consistent mass is Ms_e (x) I3 (solid_element.cpp), so for a part of solids
// alone the assembled M is Ms (x) I3 entry for entry, and where the eigen-solve's matrix is a
// principal submatrix of it (held interfaces, Craig-Bampton's interior: pattern_analysis.hpp)
// M X is Ms times X's rows gathered by node. Ms has a ninth of M's entries (on the 100k-DOF
// plate of tools/bench/reduce 0.42 against 3.9 million in the upper triangles), and the
// Lanczos stage multiplies by M twice a step (46 times on that plate). The checks and the
// other backends keep using M itself: its values on K's structure, taken from the assembled M
// or, where the pipeline assembles none (AssemblyOptions::node_mass_only), from Ms
// (node_mass_values below).
#include "ffr/preproc/assembly/assembly.hpp"
#include "ffr/preproc/model/fe_model.hpp"

#include <Eigen/Core>

#include <memory>
#include <vector>

namespace ffr::preproc::detail {

class NodeMassProduct {
 public:
  /// The product for M = (Ms (x) I3)(rows, rows) (rows: full DOFs, as the analysis's), or null
  /// where the assembled M is not Ms (x) I3 on those rows: shells, beams or point masses in
  /// the part, or a row that is not one of a mesh node's three translations.
  static std::shared_ptr<const NodeMassProduct> make(const FeModel& model, const Assembled& fe,
                                                     const std::vector<Index>& rows);

  /// Y = M X (Y resized to X's shape), on up to max_threads() threads. X must not be Y. Not
  /// for concurrent calls (it keeps its buffers).
  void apply(const Eigen::MatrixXd& X, Eigen::MatrixXd& Y) const;

  Index rows() const { return static_cast<Index>(slot_.size()); }

 private:
  NodeMassProduct(const SparseMatrix& Ms, std::vector<Index> slot) : Ms_(Ms), slot_(std::move(slot)) {}
  const SparseMatrix& Ms_;
  std::vector<Index> slot_;  ///< per row of M: 3 * node + component
  mutable std::vector<double> xf_, yf_;  ///< X and Y by node: 3 p values a node, component-major
  mutable std::vector<std::vector<double>> extra_;  ///< the other threads' parts of Y
};

/// M's values on the structure of C, the upper triangle of A(rows, rows) for a matrix A of the
/// model's DOFs, where M is Ms (x) I3 on those rows (each a mesh node's translation; entries
/// of C that couple two different components get 0): the eigen-solve's mass of a part of solids
/// alone without the assembled M (AssemblyOptions::node_mass_only). The sums are Ms's, which
/// are M's bit for bit (both add the elements' m_ab in the same order). Empty where a row is
/// not a translation of a node with three DOFs.
std::vector<double> node_mass_values(const FeModel& model, const SparseMatrix& Ms, const SparseMatrix& C,
                                     const std::vector<Index>& rows);

}  // namespace ffr::preproc::detail
