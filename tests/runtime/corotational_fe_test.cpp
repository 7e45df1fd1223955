// The co-rotational inertia route (every term from the FE mass matrix of all nodes: B^T M_FE B,
// -B^T M_FE w and their derivatives, body_fe_inertia.cpp) against the shape-integral route, on
// bodies whose FE mass matrix is not lumped: the consistent mass of a rod's two-node elements
// and a TET10 bar meshed and reduced by the preprocessor's library (its assembled consistent
// mass). Both are evaluations of the same integrals (M = int B^T B dm, 'Improved efficiency in
// FFR methods for flexible multibody dynamics by means of shape integrals preprocessing', eqs.
// 5-7; docs/references.md) by independent code — the FE side sums over the nodes here, the
// invariants were summed once by the preprocessor — so they must agree at any state to round-off
// and give the same motion, in the absolute and in the relative formulation.
#include "fe_bodies.hpp"
#include "models.hpp"
#include "support.hpp"

#include "ffr/formats/sid_io.hpp"
#include "ffr/runtime/relative.hpp"

#include <gtest/gtest.h>

#include <random>

using namespace ffr::runtime;

namespace {

struct Terms {
  MatrixXd M, C, K, T;
  VectorXd Q;
};

// The body's terms at a generic state on the frame constraints' manifold (orthonormal A; off it
// the two routes extend M differently, M_yy = int Phi^T A^T A Phi dm being sum PPdm[a][a] only
// when A^T A = I), with nonzero accelerations for the modal-acceleration tangent.
Terms terms_at(const Model& model, int body, unsigned seed) {
  Data d(model);
  const Body& b = model.bodies[static_cast<std::size_t>(body)];
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  const Eigen::Matrix3d A = Eigen::AngleAxisd(0.7, Vector3d(0.3, -0.5, 0.8).normalized()).toRotationMatrix();
  const Vector3d w(0.4, -1.2, 2.0), al(-3.0, 1.5, 0.7);
  auto skew = [](const Vector3d& v) {
    Eigen::Matrix3d S;
    S << 0, -v(2), v(1), v(2), 0, -v(0), -v(1), v(0), 0;
    return S;
  };
  const Eigen::Matrix3d Ad = A * skew(w), Add = A * (skew(al) + skew(w) * skew(w));
  const int o = b.offset;
  d.state.q.segment<3>(o) = Vector3d(0.1, 0.2, -0.3);
  d.state.qd.segment<3>(o) = Vector3d(0.5, -0.1, 0.2);
  d.state.qdd.segment<3>(o) = Vector3d(-2.0, 4.0, 1.0);
  for (int k = 0; k < 3; ++k) {
    d.state.q.segment<3>(o + 3 + 3 * k) = A.col(k);
    d.state.qd.segment<3>(o + 3 + 3 * k) = Ad.col(k);
    d.state.qdd.segment<3>(o + 3 + 3 * k) = Add.col(k);
  }
  for (int i = 0; i < b.nq; ++i) {
    d.state.q(o + 12 + i) = 1e-4 * u(rng) / std::sqrt(b.Myy(i, i)) * std::sqrt(b.mass);
    d.state.qd(o + 12 + i) = 0.1 * u(rng) * std::sqrt(b.mass);
    d.state.qdd(o + 12 + i) = 10 * u(rng) * std::sqrt(b.mass);
  }
  update_bodies(model, d);
  update_markers(model, d);
  mass_matrices(model, d);
  // The inertia terms alone, by the route the body is set up for (the elastic and applied terms
  // are the same code either way and would swamp a difference).
  const int nb = b.ncoord();
  BodyData& bd = d.bodies[static_cast<std::size_t>(body)];
  const auto zd = d.state.qd.segment(o, nb);
  Terms t{bd.M, MatrixXd::Zero(nb, nb), MatrixXd::Zero(nb, nb), MatrixXd(), VectorXd::Zero(nb)};
  if (b.full_mass) {
    fe_inertia_forces(b, bd, zd, t.Q);
    fe_inertia_tangents(b, bd, zd, t.K, t.C);
  } else {
    body_inertia_forces(b, bd, zd, t.Q);
    body_inertia_tangents(b, bd, zd, t.K, t.C);
  }
  MatrixXd T = MatrixXd::Zero(model.ncoord, model.ncoord);
  add_modal_acceleration_tangent(model, d, 1.0, T);
  t.T = T.block(o + 12, o + 12, b.nq, b.nq);
  return t;
}

double rel(const MatrixXd& a, const MatrixXd& b) { return (a - b).cwiseAbs().maxCoeff() / std::max(1e-300, a.cwiseAbs().maxCoeff()); }

void expect_same_terms(const Model& inv, const Model& cor, int body, double tol) {
  const Terms a = terms_at(inv, body, 3), b = terms_at(cor, body, 3);
  const double dM = rel(a.M, b.M), dQ = rel(a.Q, b.Q), dC = rel(a.C, b.C), dK = rel(a.K, b.K), dT = rel(a.T, b.T);
  std::printf("invariants vs FE mass matrix (relative): M %.2e, Q %.2e, C %.2e, K %.2e, modal acceleration tangent %.2e\n", dM, dQ, dC,
              dK, dT);
  EXPECT_LT(dM, tol);
  EXPECT_LT(dQ, tol);
  EXPECT_LT(dC, tol);
  EXPECT_LT(dK, tol);
  EXPECT_LT(dT, tol);
  // Not vacuous: the velocity terms and the K block are there.
  EXPECT_GT(a.Q.cwiseAbs().maxCoeff(), 0.0);
  EXPECT_GT(a.K.cwiseAbs().maxCoeff(), 0.0);
}

struct Crank {
  test::TempDir dir{"corot_fe"};
  Model inv, cor;
};

// The benchmark's slider-crank (tools/models) with `rod` as its flexible rod, both routes.
std::unique_ptr<Crank> slider_crank(const bench::FeBody& rod, const std::string& formulation, double end) {
  auto c = std::make_unique<Crank>();
  ffr::formats::write_sid(rod.sid, c->dir / "rod.sid.h5");
  std::string json = bench::slider_crank_json("rod.sid.h5", 1e-3, end, 150.0);
  const std::string key = "\"solver\": {";
  json.insert(json.find(key) + key.size(), "\"formulation\": \"" + formulation + "\", ");
  c->inv = test::model_from(json, c->dir.path);
  c->cor = c->inv;
  c->cor.bodies[1].full_mass = rod.full_mass;
  return c;
}

double same_motion(const Crank& c, int steps) {
  Data a(c.inv), b(c.cor);
  initialize(c.inv, a);
  initialize(c.cor, b);
  double worst = 0;
  for (int i = 0; i < steps; ++i) {
    step(c.inv, a);
    step(c.cor, b);
    worst = std::max(worst, (a.state.q - b.state.q).cwiseAbs().maxCoeff());
  }
  // The same decisions all along (iterations, tangent refreshes): the runs differ only by the
  // round-off of the two routes' sums.
  EXPECT_EQ(a.stats.newton_iterations, b.stats.newton_iterations);
  EXPECT_EQ(a.stats.factorizations, b.stats.factorizations);
  return worst;
}

}  // namespace

TEST(CorotationalFe, ConsistentRodTermsAgree) {
  const bench::FeBody rod = bench::consistent_rod(bench::rod_params(11, 6));
  auto c = slider_crank(rod, "absolute", 0.01);
  expect_same_terms(c->inv, c->cor, 1, 1e-11);
}

TEST(CorotationalFe, SolidBarTermsAgree) {
  test::TempDir dir("corot_solid");
  const bench::FeBody bar = bench::solid_bar(dir.path, 0.3, 0.008, 0.004, 8);
  std::printf("TET10 bar: %ld DOF\n", bar.dof);
  auto c = slider_crank(bar, "absolute", 0.01);
  expect_same_terms(c->inv, c->cor, 1, 1e-10);
}

// The bounds: the routes' terms differ by round-off (1e-16 relative, above), which the step's
// tangent (penalty 1e4, the rod's stiff modes) amplifies; measured over the 100 steps, with equal
// iteration and refresh counts, the runs stay 1e-11 apart in the absolute formulation and
// 1e-10 ... 1e-9 in the relative one (its joint coordinates and projections), with no growth.
// An inertia term wrong by even 1e-6 of itself parts them by far more (the lumped-mass test,
// corotational_test.cpp, gives the tangent-decision case).
TEST(CorotationalFe, SameMotionAbsolute) {
  const bench::FeBody rod = bench::consistent_rod(bench::rod_params(11, 6));
  auto c = slider_crank(rod, "absolute", 0.1);
  const double d = same_motion(*c, 100);
  std::printf("absolute, 100 steps: max |q_inv - q_fe| = %.2e m\n", d);
  EXPECT_LT(d, 1e-9);
}

TEST(CorotationalFe, SameMotionRelative) {
  const bench::FeBody rod = bench::consistent_rod(bench::rod_params(11, 6));
  auto c = slider_crank(rod, "relative", 0.1);
  ASSERT_TRUE(c->inv.relative && c->cor.relative);
  const double d = same_motion(*c, 100);
  std::printf("relative, 100 steps: max |q_inv - q_fe| = %.2e m\n", d);
  EXPECT_LT(d, 5e-9);
}
