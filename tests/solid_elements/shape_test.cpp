// Shape functions in gmsh's node order: Kronecker property at the reference nodes (whose
// coordinates were read from gmsh 4.8, getElementProperties), partition of unity, linear
// completeness, and derivatives against central differences.
#include "support.hpp"

#include <gtest/gtest.h>

using namespace ffr::preproc;
using ffr::test::all_solid_types;

namespace {
// Interior sample points valid for every reference shape (inside the tet, hence all).
const Eigen::Vector3d kPts[] = {{0.1, 0.2, 0.3}, {0.25, 0.15, 0.05}, {0.05, 0.6, 0.2}, {0.3, 0.3, 0.3}};
}

TEST(SolidShape, KroneckerAtNodes) {
  for (ElementType t : all_solid_types()) {
    const SolidShape& s = solid_shape(t);
    ShapeValues N(s.nodes);
    ShapeGradients dN(s.nodes, 3);
    for (int a = 0; a < s.nodes; ++a) {
      Eigen::Vector3d xi = s.reference_nodes[a];
      if (t == ElementType::Pyramid5 && a == 4) xi.z() = 1 - 1e-12;  // rational basis: apex as a limit
      s.eval(xi, N, dN);
      for (int b = 0; b < s.nodes; ++b) EXPECT_NEAR(N[b], a == b ? 1.0 : 0.0, 1e-11) << name(t) << " " << a << " " << b;
    }
  }
}

TEST(SolidShape, PartitionOfUnityCompletenessAndDerivatives) {
  for (ElementType t : all_solid_types()) {
    const SolidShape& s = solid_shape(t);
    ShapeValues N(s.nodes), Np(s.nodes), Nm(s.nodes);
    ShapeGradients dN(s.nodes, 3), tmp(s.nodes, 3);
    Eigen::MatrixX3d ref(s.nodes, 3);
    for (int a = 0; a < s.nodes; ++a) ref.row(a) = s.reference_nodes[a].transpose();
    for (const auto& xi : kPts) {
      s.eval(xi, N, dN);
      EXPECT_NEAR(N.sum(), 1.0, 1e-14) << name(t);
      EXPECT_NEAR((ref.transpose() * N - xi).norm(), 0.0, 1e-14) << name(t);   // sum N_a xi_a = xi
      EXPECT_NEAR((ref.transpose() * dN - Eigen::Matrix3d::Identity()).norm(), 0.0, 1e-13) << name(t);
      const double h = 1e-6;
      for (int j = 0; j < 3; ++j) {
        Eigen::Vector3d xp = xi, xm = xi;
        xp[j] += h;
        xm[j] -= h;
        s.eval(xp, Np, tmp);
        s.eval(xm, Nm, tmp);
        EXPECT_NEAR(((Np - Nm) / (2 * h) - dN.col(j)).norm(), 0.0, 1e-8) << name(t) << " d/dxi_" << j;
      }
    }
  }
}

TEST(SolidShape, UnsupportedTypeIsRefused) {
  EXPECT_FALSE(is_solid(ElementType::Pyramid13));
  try {
    solid_shape(ElementType::Pyramid13);
    FAIL();
  } catch (const ElementError& e) {
    EXPECT_NE(std::string(e.what()).find("PYRAMID13"), std::string::npos);
  }
}
