#pragma once
// The sparse matrix type of the assembly (64-bit indices: several million DOF with ~100
// entries per column overflow 32-bit nonzero counts). Same alias as solver/sparse_types.hpp.
#include <Eigen/SparseCore>

#include <cstdint>

namespace ffr::preproc {
using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, std::int64_t>;
using Triplet = Eigen::Triplet<double, std::int64_t>;
}  // namespace ffr::preproc
