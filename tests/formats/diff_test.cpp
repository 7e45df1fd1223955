// diff(): a mode's sign and a rotation inside a repeated eigenvalue are not differences;
// everything else is, and is named. transform_modes() is checked against the direct point
// sums of the synthetic generator applied to the rotated shapes (an independent oracle).
#include "ffr/formats/diff.hpp"
#include "ffr/formats/sid_io.hpp"
#include "ffr/formats/synthetic.hpp"
#include "ffr/formats/validate.hpp"

#include <gtest/gtest.h>

#include <Eigen/QR>

#include <filesystem>
#include <random>
#include <sstream>

using namespace ffr::formats;
using namespace ffr::formats::synthetic;
using Eigen::MatrixXd;

namespace {

// Clamped chain with a symmetric section: bending modes come in exactly repeated pairs.
Sid symmetric_chain() {
  ChainParams p;
  p.points = 15;
  p.clamped = true;
  p.EIy = p.EIz = 2.0;
  p.modes = 6;  // three bending pairs (EA is high: the first axial mode is far above)
  p.stiffening = true;
  p.damping_ratio = 0.01;
  return spring_chain(p).sid;
}

MatrixXd random_orthogonal(int n, std::mt19937& rng) {
  std::normal_distribution<double> g;
  const MatrixXd A = MatrixXd::NullaryExpr(n, n, [&] { return g(rng); });
  return Eigen::HouseholderQR<MatrixXd>(A).householderQ() * MatrixXd::Identity(n, n);
}

std::string dump(const DiffReport& r) {
  std::ostringstream o;
  for (const auto& x : r.structural) o << "  " << x << "\n";
  for (const auto& d : r.worst) o << "  " << d.dataset << d.index << " rel " << d.rel << "\n";
  return o.str();
}

}  // namespace

TEST(Diff, IdenticalBodiesAreEquivalent) {
  const Sid a = symmetric_chain();
  const DiffReport r = diff(a, a);
  EXPECT_TRUE(r.equivalent) << dump(r);
  EXPECT_GT(r.datasets_compared, 30);
}

TEST(Diff, SignFlipsAreNotDifferences) {
  const Sid a = symmetric_chain();
  ASSERT_NEAR(a.refmod.frequency_hz[0], a.refmod.frequency_hz[1], 1e-9 * a.refmod.frequency_hz[0]);
  Eigen::VectorXd s = Eigen::VectorXd::Ones(6);
  s[0] = s[3] = s[4] = -1;
  const Sid b = transform_modes(a, s.asDiagonal());
  const DiffReport plain = diff(a, b, [] { DiffOptions o; o.align = false; return o; }());
  EXPECT_FALSE(plain.equivalent) << "the flip must be visible without alignment";
  const DiffReport r = diff(a, b);
  EXPECT_TRUE(r.equivalent) << dump(r);
}

TEST(Diff, RotationsInsideRepeatedEigenvaluesAreNotDifferences) {
  const Sid a = symmetric_chain();
  std::mt19937 rng(5);
  MatrixXd T = MatrixXd::Zero(6, 6);
  for (int g = 0; g < 3; ++g) T.block(2 * g, 2 * g, 2, 2) = random_orthogonal(2, rng);  // includes reflections
  const Sid b = transform_modes(a, T);
  // Through the file, as ffr-diff sees it.
  const auto path = std::filesystem::temp_directory_path() / ("ffr_diff_rot_" + std::to_string(::getpid()) + ".sid.h5");
  write_sid(b, path);
  const Sid br = read_sid(path);
  std::filesystem::remove(path);
  const DiffReport r = diff(a, br);
  EXPECT_TRUE(r.equivalent) << dump(r);
  EXPECT_EQ(r.alignment.groups.size(), 3u);
  EXPECT_FALSE(r.alignment.rotated_groups.empty());
}

TEST(Diff, RotationAcrossDistinctFrequenciesIsADifference) {
  const Sid a = symmetric_chain();
  MatrixXd T = MatrixXd::Identity(6, 6);
  const double c = std::cos(0.3), s = std::sin(0.3);
  T(1, 1) = c, T(1, 2) = -s, T(2, 1) = s, T(2, 2) = c;  // mixes the first and second pairs
  const DiffReport r = diff(a, transform_modes(a, T));
  EXPECT_FALSE(r.equivalent);
}

TEST(Diff, RescaledModeIsADifference) {
  const Sid a = symmetric_chain();
  Eigen::VectorXd s = Eigen::VectorXd::Ones(6);
  s[2] = 1.01;
  const DiffReport r = diff(a, transform_modes(a, s.asDiagonal()));
  EXPECT_FALSE(r.equivalent);
}

TEST(Diff, ARealPerturbationIsReportedWithItsDataset) {
  const Sid a = symmetric_chain();
  Sid b = a;
  b.Gr[1](0, 2) += 1e-4 * (std::abs(b.Gr[1](0, 2)) + 1);
  const DiffReport r = diff(a, b);
  ASSERT_FALSE(r.equivalent);
  ASSERT_FALSE(r.worst.empty());
  EXPECT_EQ(r.worst[0].dataset, "/sid/Gr/M0");
  EXPECT_EQ(r.worst[0].index, "[1,0,2]");
  EXPECT_EQ(r.datasets_different, 1);
  DiffOptions loose;
  loose.rtol = 1e-2;
  EXPECT_TRUE(diff(a, b, loose).equivalent);

  Sid m = a;
  m.refmod.mass *= 1.001;
  const DiffReport rm = diff(a, m);
  ASSERT_FALSE(rm.equivalent);
  EXPECT_EQ(rm.worst[0].dataset, "/refmod/mass");
}

TEST(Diff, NodesAreMatchedByNameAndMissingOnesAreStructural) {
  const Sid a = symmetric_chain();
  Sid b = a;
  std::swap(b.nodes[0], b.nodes[1]);
  for (auto& i : b.interfaces) i.node = 1 - i.node;
  EXPECT_TRUE(diff(a, b).equivalent) << dump(diff(a, b));
  b.nodes[0].name = "C";  // node B missing, C extra: alignment uses the common node only
  b.interfaces[1].node = 0;  // keeps the interfaces valid
  const DiffReport r = diff(a, b);
  EXPECT_FALSE(r.equivalent);
  bool named = false;
  for (const auto& s : r.structural) named |= s.find("'C' only in B") != std::string::npos;
  EXPECT_TRUE(named) << dump(r);
}

// transform_modes against the oracle: the generator's direct sums over the points with the
// rotated shapes. All frequencies equal, so any orthogonal T keeps Ke = diag(w^2).
TEST(Diff, TransformModesMatchesDirectSumsOfTheRotatedShapes) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<PointMass> pts;
  for (int p = 0; p < 6; ++p) {
    PointMass pm;
    pm.m = 1 + std::abs(u(rng));
    pm.c = Eigen::Vector3d(u(rng), u(rng), u(rng));
    pm.inertia = 0.05 * Eigen::Matrix3d::Identity() + 0.01 * Eigen::Vector3d(u(rng), u(rng), u(rng)).cwiseAbs().asDiagonal().toDenseMatrix();
    pts.push_back(pm);
  }
  // M-orthonormal shapes first (the generator's own normalisation), then rotate them.
  const MatrixXd Phi0 = MatrixXd::NullaryExpr(18, 4, [&] { return u(rng); });
  const MatrixXd Psi0 = MatrixXd::NullaryExpr(18, 4, [&] { return u(rng); });
  std::vector<ExportedNode> all;
  for (int p = 0; p < 6; ++p) all.push_back({std::string(1, char('a' + p)), p});
  const Eigen::Vector4d w = Eigen::Vector4d::Constant(7.0);
  const Sid a = from_shapes(pts, Phi0, Psi0, w, all, "craig-bampton");
  MatrixXd Phi(18, 4), Psi(18, 4);
  for (int p = 0; p < 6; ++p) {
    Phi.middleRows(3 * p, 3) = a.nodes[p].phi;
    Psi.middleRows(3 * p, 3) = a.nodes[p].psi;
  }
  const MatrixXd T = random_orthogonal(4, rng);
  const Sid direct = from_shapes(pts, Phi * T, Psi * T, w, all, "craig-bampton");
  const Sid transformed = transform_modes(a, T);
  DiffOptions exact;
  exact.align = false;
  exact.rtol = 1e-12;
  const DiffReport r = diff(direct, transformed, exact);
  EXPECT_TRUE(r.equivalent) << dump(r);
  // And the transformed body still satisfies every basis-independent identity.
  EXPECT_TRUE(validate(transformed).ok());
}

// Ke.M1 has three mode indices; its transform is checked against the chain's own definition
// Ke.M1[k] = Phi^T K_G(N(Phi_k)) Phi evaluated on the rotated modes Phi T.
TEST(Diff, TransformModesOfKeM1MatchesTheDefinitionOnRotatedModes) {
  ChainParams p;
  p.points = 9;
  p.modes = 4;
  p.EA = 100;  // free-free: bending pairs at 22 and 62 rad/s, the first axial mode at 31 rad/s
  p.stiffening = true;
  const Chain c = spring_chain(p);
  std::mt19937 rng(4);
  const MatrixXd T = random_orthogonal(4, rng);
  const Sid t = transform_modes(c.sid, T);
  const MatrixXd PhiT = c.model.Phi.leftCols(4) * T;
  double big = 0, err = 0;
  for (int k = 0; k < 4; ++k) {
    const MatrixXd direct = PhiT.transpose() * c.model.geometric_stiffness(c.model.axial_forces(PhiT.col(k))) * PhiT;
    big = std::max(big, direct.cwiseAbs().maxCoeff());
    err = std::max(err, (t.KeM1[k] - direct).cwiseAbs().maxCoeff());
  }
  ASSERT_GT(big, 0);
  EXPECT_LT(err, 1e-12 * big);
  // A sign flip of one mode is aligned away in Ke.M1 like everywhere else.
  Eigen::VectorXd s = Eigen::VectorXd::Ones(4);
  s[1] = -1;
  const DiffReport r = diff(c.sid, transform_modes(c.sid, s.asDiagonal()));
  EXPECT_TRUE(r.equivalent) << dump(r);
  Sid b = c.sid;
  Eigen::Index row = 0, col = 0;
  b.KeM1[2].cwiseAbs().maxCoeff(&row, &col);
  ASSERT_GT(std::abs(b.KeM1[2](row, col)), 0.1 * big) << "the axial mode (k = 2) stiffens the bending modes";
  b.KeM1[2](row, col) *= 1.01;
  const DiffReport d = diff(c.sid, b);
  ASSERT_FALSE(d.equivalent);
  EXPECT_EQ(d.worst.front().dataset, "/sid/Ke/M1");
}

// Modes are aligned by their surface shapes only where both files have the same vertices in
// the same order. Here B's surface lists the vertices shifted by one, and each vertex's shape
// of mode 1 is minus its neighbour's: paired by position, B's surface says "mode 1 flipped"
// louder than every other feature. The alignment must not take it: it must find exactly the real
// flips, every member but the surface must compare equal, and the surface is reported.
TEST(Diff, RenumberedSurfacesDoNotMisleadTheAlignment) {
  Sid a = symmetric_chain();
  const Eigen::Index nv = 400, nq = a.nq();
  a.visual.vertices.resize(nv, 3);
  a.visual.triangles.resize(nv - 2, 3);
  a.visual.modes.assign(static_cast<std::size_t>(nq), {});
  for (Eigen::Index i = 0; i < nv; ++i) a.visual.vertices.row(i) << 0.01 * static_cast<double>(i), 0.0, 0.0;
  for (Eigen::Index t = 0; t + 2 < nv; ++t) a.visual.triangles.row(t) << t, t + 1, t + 2;
  for (Eigen::Index k = 0; k < nq; ++k) {
    auto& m = a.visual.modes[static_cast<std::size_t>(k)];
    m.resize(nv, 3);
    for (Eigen::Index i = 0; i < nv; ++i)  // mode 1 alternates in sign from vertex to vertex
      m.row(i) << (k == 1 ? (i % 2 ? -100.0 : 100.0) : 0.1 * static_cast<double>(k + 1)), 0.0, 0.0;
  }
  Eigen::VectorXd s = Eigen::VectorXd::Ones(nq);
  s[0] = s[3] = -1;
  Sid b = transform_modes(a, s.asDiagonal());
  // B's vertex i is A's vertex i + 1 (cyclically), with its shapes.
  const Visual va = b.visual;
  for (Eigen::Index i = 0; i < nv; ++i) {
    b.visual.vertices.row(i) = va.vertices.row((i + 1) % nv);
    for (Eigen::Index k = 0; k < nq; ++k)
      b.visual.modes[static_cast<std::size_t>(k)].row(i) = va.modes[static_cast<std::size_t>(k)].row((i + 1) % nv);
  }
  for (Eigen::Index t = 0; t + 2 < nv; ++t) b.visual.triangles.row(t) << (t + nv - 1) % nv, t, t + 1;
  const DiffReport r = diff(a, b);
  // Modes 0 and 1, 2 and 3 are repeated pairs: the flips show in the pairs' rotations.
  EXPECT_LT((r.alignment.T - MatrixXd(s.asDiagonal())).cwiseAbs().maxCoeff(), 1e-9) << r.alignment.T;
  EXPECT_FALSE(r.equivalent);
  for (const auto& d : r.worst) EXPECT_EQ(d.dataset.rfind("/visual/", 0), 0u) << dump(r);
}

// A group of modes whose linear features (Pdm, rPdm, the nodes' shapes) are rounding noise -- a
// Craig-Bampton fixed-interface mode with no net momentum and zero at its interface nodes --
// carries no sign or orientation: the alignment must leave it as written, not turn B's modes by
// the noise (Pdm 1e-13 in A and -1.6e-13 in B flipped a shell's mode and reported every
// member of it as different).
TEST(Diff, ModesWithoutLinearFeaturesAreLeftAsWritten) {
  Sid a = symmetric_chain();
  ASSERT_NEAR(a.refmod.frequency_hz[0], a.refmod.frequency_hz[1], 1e-9 * a.refmod.frequency_hz[0]);
  auto silence = [](Sid& s, double noise) {
    for (Eigen::Index k : {0, 1}) {
      s.integrals.Pdm.col(k).setConstant(noise * static_cast<double>(k + 1));
      for (auto& r : s.integrals.rPdm) r.col(k).setConstant(-noise);
      for (auto& n : s.nodes) {
        n.phi.col(k).setConstant(noise);
        n.psi.col(k).setConstant(noise);
      }
    }
  };
  Sid b = a;
  silence(a, 1e-13);
  silence(b, -1.6e-13);
  const DiffReport r = diff(a, b);
  EXPECT_LT((r.alignment.T - MatrixXd::Identity(a.nq(), a.nq())).cwiseAbs().maxCoeff(), 1e-12) << r.alignment.T;
  EXPECT_TRUE(r.equivalent) << dump(r);
}

