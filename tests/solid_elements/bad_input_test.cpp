// Bad input is refused with ElementError and a message that says what is wrong.
#include "support.hpp"

#include <gtest/gtest.h>

using namespace ffr::preproc;
using namespace ffr::test;

namespace {
const Material kOk{70e9, 0.33, 2700};

std::string error_of(ElementType t, const Eigen::MatrixX3d& xe, const Material& m) {
  try {
    solid_element(t, xe, m);
  } catch (const ElementError& e) {
    return e.what();
  }
  return "no error";
}
bool has(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }
}  // namespace

TEST(SolidBadInput, Material) {
  const Eigen::MatrixX3d xe = straight_element(ElementType::Tet4, reference_corners(ElementType::Tet4));
  std::string m = error_of(ElementType::Tet4, xe, {70e9, 0.5, 2700});
  EXPECT_TRUE(has(m, "Poisson's ratio nu = 0.5") && has(m, "incompressible")) << m;
  m = error_of(ElementType::Tet4, xe, {70e9, -1.0, 2700});
  EXPECT_TRUE(has(m, "nu = -1")) << m;
  m = error_of(ElementType::Tet4, xe, {-1e9, 0.3, 2700});
  EXPECT_TRUE(has(m, "Young's modulus E = -1e+09")) << m;
  m = error_of(ElementType::Tet4, xe, {0.0, 0.3, 2700});
  EXPECT_TRUE(has(m, "Young's modulus")) << m;
  m = error_of(ElementType::Tet4, xe, {70e9, 0.3, -1});
  EXPECT_TRUE(has(m, "density rho = -1")) << m;
  m = error_of(ElementType::Tet4, xe, {std::nan(""), 0.3, 1});
  EXPECT_TRUE(has(m, "Young's modulus")) << m;
  EXPECT_EQ(error_of(ElementType::Tet4, xe, {70e9, 0.3, 0.0}), "no error");  // massless is allowed
}

TEST(SolidBadInput, InvertedElements) {
  for (ElementType t : all_solid_types()) {
    Eigen::MatrixX3d xe = straight_element(t, projective_corners(t));
    xe.col(0) *= -1;  // mirror: same shape, reversed orientation
    const std::string m = error_of(t, xe, kOk);
    EXPECT_TRUE(has(m, std::string(name(t)) + " element is inverted")) << m;
    EXPECT_TRUE(has(m, "node order is reversed")) << m;
  }
}

TEST(SolidBadInput, CollapsedElements) {
  for (ElementType t : all_solid_types()) {
    Eigen::MatrixX3d c = projective_corners(t);
    c.row(1) = c.row(0);  // two corners coincide
    const std::string m = error_of(t, straight_element(t, c), kOk);
    EXPECT_TRUE(has(m, std::string(name(t)) + " element is degenerate")) << m;
    EXPECT_TRUE(has(m, "coincident")) << m;
  }
  // A flat tet (all four corners in a plane).
  Eigen::MatrixX3d flat(4, 3);
  flat << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0.3, 0.3, 0;
  EXPECT_TRUE(has(error_of(ElementType::Tet4, flat, kOk), "degenerate"));
}

TEST(SolidBadInput, TangledAndMisplacedMidsideNode) {
  // HEX8 with one corner pushed through the opposite face: detJ changes sign.
  Eigen::MatrixX3d c = reference_corners(ElementType::Hex8);
  c.row(6) = Eigen::RowVector3d(-0.8, -0.8, -0.8);
  std::string m = error_of(ElementType::Hex8, c, kOk);
  EXPECT_TRUE(has(m, "changes sign")) << m;
  // TET10 with a midside node moved past the far corner.
  Eigen::MatrixX3d xe = straight_element(ElementType::Tet10, reference_corners(ElementType::Tet10));
  xe.row(4) = Eigen::RowVector3d(1.2, 0, 0);
  m = error_of(ElementType::Tet10, xe, kOk);
  EXPECT_TRUE(has(m, "TET10 element is distorted") && has(m, "midside")) << m;
}

TEST(SolidBadInput, ShapeOfInputs) {
  const Eigen::MatrixX3d xe = reference_corners(ElementType::Hex8);
  EXPECT_TRUE(has(error_of(ElementType::Hex20, xe, kOk), "HEX20 element needs 20 nodes, got 8"));
  Eigen::MatrixX3d bad = xe;
  bad(2, 1) = std::numeric_limits<double>::infinity();
  EXPECT_TRUE(has(error_of(ElementType::Hex8, bad, kOk), "non-finite"));
  EXPECT_TRUE(has(error_of(ElementType::Quad4, xe, kOk), "unsupported solid element type QUAD4"));
  try {
    solid_stress(ElementType::Hex8, xe, kOk, Eigen::VectorXd::Zero(5));
    FAIL();
  } catch (const ElementError& e) {
    EXPECT_TRUE(has(e.what(), "expected 24")) << e.what();
  }
  try {
    solid_geometric_stiffness(ElementType::Hex8, xe, Eigen::Matrix<double, 6, Eigen::Dynamic>::Zero(6, 3));
    FAIL();
  } catch (const ElementError& e) {
    EXPECT_TRUE(has(e.what(), "stress given at 3 points, the element has 8")) << e.what();
  }
}
