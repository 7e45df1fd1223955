// The reduced matrices against the assembled ones: Ke = Phi^T K Phi and Me = Phi^T M Phi with K
// and M straight from the assembly, for every method. The eigen-solve shifts K to K - sigma M
// in K's own storage for the factorization and restores it afterwards (reduction.cpp); a K left
// shifted would make Ke = Lambda - sigma I (the test fails then for free and clamped).
#include "ffr/preproc/assembly/assembly.hpp"
#include "ffr/preproc/model/fe_model.hpp"
#include "ffr/preproc/reduce/reduction.hpp"
#include "support.hpp"

#include <gtest/gtest.h>

using namespace ffr;

TEST(Reduction, ReducedMatricesAreThoseOfTheAssembledOnes) {
  test::HexGrid grid(12, 4, 3);
  const auto model = preproc::build_model(grid.mesh, grid.part);
  const preproc::Assembled fe = preproc::assemble(model);
  using Method = preproc::ReductionSpec::Method;
  for (const Method m : {Method::Free, Method::Clamped, Method::CraigBampton}) {
    preproc::ReductionSpec spec;
    spec.method = m;
    spec.interface = "L";
    spec.interfaces = {"L", "R"};
    spec.frame = "L";
    spec.modes = 6;
    SCOPED_TRACE(static_cast<int>(m));
    const auto r = preproc::reduce(model, fe, spec);
    const Eigen::MatrixXd Ke = r.Phi.transpose() * (fe.K * r.Phi);
    const Eigen::MatrixXd Me = r.Phi.transpose() * (fe.M * r.Phi);
    EXPECT_LT((r.Ke - Ke).norm(), 1e-11 * Ke.norm());
    EXPECT_LT((r.Me - Me).norm(), 1e-11 * Me.norm());
    if (m != Method::CraigBampton) {  // eigenmodes: Ke = Lambda, mass-normalized
      EXPECT_LT((Ke.diagonal() - r.lambda).norm(), 1e-11 * r.lambda.norm());
      EXPECT_LT((Me - Eigen::MatrixXd::Identity(6, 6)).norm(), 1e-11);
    }
  }
}

// A K that does not share M's structure (here an explicitly stored zero coupling two interior
// nodes that no element joins) takes the other path: K - sigma M as a matrix of its own. The
// modes are those of the same K without the zero, to the rounding of a different factor.
TEST(Reduction, StiffnessOfAnotherStructureThanTheMassGivesTheSameModes) {
  test::HexGrid grid(12, 4, 3);
  const auto model = preproc::build_model(grid.mesh, grid.part);
  const preproc::Assembled fe = preproc::assemble(model);
  preproc::Assembled other = preproc::assemble(model);
  const auto id = [](int i, int j, int k) { return (k * 5 + j) * 13 + i; };  // HexGrid(12, 4, 3)
  const preproc::Index a = model.dof(id(2, 1, 1), 0), b = model.dof(id(10, 3, 2), 1);
  preproc::SparseMatrix Z(fe.K.rows(), fe.K.cols());
  Z.insert(a, b) = 0.0;
  Z.insert(b, a) = 0.0;
  other.K = preproc::SparseMatrix(fe.K + Z);
  ASSERT_EQ(other.K.nonZeros(), fe.K.nonZeros() + 2);
  for (const auto method : {preproc::ReductionSpec::Method::Free, preproc::ReductionSpec::Method::Clamped}) {
    preproc::ReductionSpec spec;
    spec.method = method;
    spec.interface = "L";
    spec.modes = 6;
    SCOPED_TRACE(static_cast<int>(method));
    const auto same = preproc::reduce(model, fe, spec);
    const auto r = preproc::reduce(model, other, spec);
    EXPECT_EQ(r.factor.nnz_A, same.factor.nnz_A + 1);  // the zero reached the factorized matrix
    EXPECT_LT((r.lambda - same.lambda).norm(), 1e-10 * same.lambda.norm());
    const Eigen::MatrixXd Ke = r.Phi.transpose() * (fe.K * r.Phi);
    EXPECT_LT((r.Ke - Ke).norm(), 1e-11 * Ke.norm());
  }
}
