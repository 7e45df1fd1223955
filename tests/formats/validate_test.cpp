// validate(): passes on clean synthetic bodies (whose members come from direct point sums,
// not from the integral formulas validate checks against), and each identity is caught on a
// body crafted to violate it. A final test makes sure no check of the report goes untested.
#include "ffr/formats/synthetic.hpp"
#include "ffr/formats/validate.hpp"

#include <gtest/gtest.h>

#include <functional>
#include <random>
#include <set>
#include <sstream>

using namespace ffr::formats;
using namespace ffr::formats::synthetic;

namespace {

// Five points with rotary inertia, three shapes: J.M0, Cr.M0 and Me carry a rotary part.
Sid rotary_body(bool with_constraint_mode) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<PointMass> pts;
  for (int p = 0; p < 5; ++p) {
    PointMass pm;
    pm.m = 1 + std::abs(u(rng));
    pm.c = Eigen::Vector3d(u(rng), u(rng), u(rng));
    const Eigen::Matrix3d A = Eigen::Matrix3d::NullaryExpr([&] { return u(rng); });
    pm.inertia = 0.1 * (A * A.transpose() + Eigen::Matrix3d::Identity());
    pts.push_back(pm);
  }
  const Eigen::MatrixXd Phi = Eigen::MatrixXd::NullaryExpr(15, 3, [&] { return u(rng); });
  const Eigen::MatrixXd Psi = Eigen::MatrixXd::NullaryExpr(15, 3, [&] { return u(rng); });
  Sid s = from_shapes(pts, Phi, Psi, Eigen::Vector3d(5, 8, 13), {{"A", 0}, {"B", 3}}, "craig-bampton", 0.05);
  s.interfaces = {{"A", 0, "rigid", "a"}, {"B", 1, "averaged", "b"}};
  if (with_constraint_mode) s.refmod.mode_type[2] = ModeType::Constraint;
  return s;
}

Sid chain(bool clamped) {
  ChainParams p;
  p.points = 9;
  p.clamped = clamped;
  p.EIy = 1.5;
  p.modes = 4;
  p.damping_ratio = 0.02;
  p.stiffening = true;
  return spring_chain(p).sid;
}

enum Body { kRotary, kRotaryCB, kFree, kClamped };
Sid body(Body b) {
  switch (b) {
    case kRotary: return rotary_body(false);
    case kRotaryCB: return rotary_body(true);
    case kFree: return chain(false);
    default: return chain(true);
  }
}

struct Violation {
  std::string check;
  Body body;
  std::function<void(Sid&)> spoil;
};

constexpr double d = 1e-4;  // every natural scale of these bodies is O(1); tolerances <= 1e-6

std::vector<Violation> violations() {
  return {
      {"mass positive", kRotary, [](Sid& s) { s.refmod.mass = -1; }},
      {"Me symmetric", kRotary, [](Sid& s) { s.Me(0, 1) += d; }},
      {"Ke symmetric", kRotary, [](Sid& s) { s.Ke(0, 1) += d * 100; }},
      {"De symmetric", kRotary, [](Sid& s) { s.De(0, 1) += d; }},
      {"J.M0 symmetric", kRotary, [](Sid& s) { s.J.M0(0, 1) += d; }},
      {"rrdm symmetric", kRotary, [](Sid& s) { s.integrals.rrdm(0, 1) += d; }},
      {"rotary.I symmetric", kRotary, [](Sid& s) { s.rotary.I(0, 1) += d; }},
      {"rotary.PsiIPsi symmetric", kRotary, [](Sid& s) { s.rotary.PsiIPsi(0, 1) += d; }},
      {"Me positive definite", kRotary, [](Sid& s) { s.Me(0, 0) = -0.5; }},
      {"Ke positive semi-definite", kRotary, [](Sid& s) { s.Ke(0, 0) = -1; }},
      {"De positive semi-definite", kRotary, [](Sid& s) { s.De(0, 0) = -0.1; }},
      {"J.M0 positive semi-definite", kRotary, [](Sid& s) { s.J.M0 = Eigen::Vector3d(-1, 2, 2).asDiagonal(); }},
      {"J.M0 principal moments: triangle inequality", kRotary,
       [](Sid& s) { s.J.M0 = Eigen::Vector3d(1, 1, 3).asDiagonal(); }},
      {"J about the centre of mass positive semi-definite", kRotary, [](Sid& s) { s.mdCM.M0 *= 10; }},
      {"J about the centre of mass: triangle inequality", kRotary,
       [](Sid& s) {
         const Eigen::Vector3d dm = s.mdCM.M0;
         const Eigen::Matrix3d shift = (dm.squaredNorm() * Eigen::Matrix3d::Identity() - dm * dm.transpose()) / s.refmod.mass;
         s.J.M0 = Eigen::Matrix3d(Eigen::Vector3d(0.1, 0.1, 0.5).asDiagonal()) + shift;
       }},
      {"rrdm - rdm rdm^T / m positive semi-definite", kRotary, [](Sid& s) { s.integrals.rdm *= 10; }},
      {"rotary.I positive semi-definite", kRotary, [](Sid& s) { s.rotary.I(0, 0) = -1; }},
      {"rotary.PsiIPsi positive semi-definite", kRotary, [](Sid& s) { s.rotary.PsiIPsi(1, 1) = -1; }},
      {"frequency_hz >= 0", kRotary, [](Sid& s) { s.refmod.frequency_hz[0] = -1; }},
      {"normal modes: frequency_hz > 0", kRotary, [](Sid& s) { s.refmod.frequency_hz[2] = 0; }},
      {"node names unique and non-empty", kRotary, [](Sid& s) { s.nodes[1].name = s.nodes[0].name; }},
      {"interface names unique and non-empty", kRotary, [](Sid& s) { s.interfaces[1].name = ""; }},
      {"AP0 are rotation matrices", kRotary, [](Sid& s) { s.nodes[0].AP0(0, 0) = -1; }},
      {"stiffening symmetric in (k,i)", kFree, [](Sid& s) { s.stiffening->K0om[0](1, 2) += d; }},
      {"Ke.M1 symmetric in (i,j)", kFree, [](Sid& s) { s.KeM1[1](0, 2) += d; }},
      // members against the primitive integrals
      {"mdCM.M0 = rdm", kRotary, [](Sid& s) { s.integrals.rdm.x() += d; }},
      {"mdCM.M1 = Pdm^T", kRotary, [](Sid& s) { s.integrals.Pdm(0, 1) += d; }},
      {"Ct.M0 = Pdm^T", kRotary, [](Sid& s) { s.Ct.M0(1, 0) += d; }},
      {"J.M0 = tr(rrdm) I - rrdm + rotary.I", kRotary, [](Sid& s) { s.J.M0(2, 2) += d; }},
      {"J.M1 = 2 tr(R_k) I - R_k - R_k^T", kRotary, [](Sid& s) { s.J.M1[1](0, 0) += d; }},
      {"Gr = 2 tr(R_k) I - 2 R_k^T", kRotary, [](Sid& s) { s.Gr[1](0, 1) += d; }},
      {"Cr.M0 = eps R_k + rotary.PsiI", kRotary, [](Sid& s) { s.rotary.PsiI(0, 2) += d; }},
      {"Oe.M0 from rPdm", kRotary, [](Sid& s) { s.integrals.rPdm[0](1, 2) += d; }},
      {"Cr.M1 = eps PPdm", kRotary, [](Sid& s) { s.Cr.M1[0](1, 2) += d; }},
      {"Ge = 2 eps PPdm", kRotary, [](Sid& s) { s.Ge[0](1, 2) += d; }},
      {"Oe.M1 from PPdm", kRotary, [](Sid& s) { s.Oe.M1[0](1, 4) += d; }},
      {"Me = sum_a PPdm[a][a] + rotary.PsiIPsi", kRotary, [](Sid& s) { s.rotary.PsiIPsi(0, 0) += d; }},
      // cross-member identities (formats/SPEC.md section 9)
      {"mdCM.M1 = Ct.M0", kRotary, [](Sid& s) { s.mdCM.M1(0, 0) += d; }},
      {"Gr + Gr^T = 2 J.M1", kRotary, [](Sid& s) { s.Gr[0](0, 1) += d; }},
      {"diag Gr = diag J.M1", kRotary, [](Sid& s) { s.Gr[0](1, 1) += d; }},
      {"J.M1 symmetric", kRotary, [](Sid& s) { s.J.M1[0](0, 1) += d; }},
      {"J.M1 diagonal = -2 Oe.M0 (xx,yy,zz)", kRotary, [](Sid& s) { s.Oe.M0(0, kYY) += d; }},
      {"J.M1 off-diagonal = -Oe.M0 (xy,yz,xz)", kRotary, [](Sid& s) { s.Oe.M0(0, kYZ) += d; }},
      {"Ge = 2 Kr (Cr.M1)", kRotary, [](Sid& s) { s.Ge[1](0, 0) += d; }},
      {"Kr antisymmetric in (i,k)", kRotary, [](Sid& s) { s.Cr.M1[0](1, 0) += d; }},
      {"Oe.M1 symmetric in (i,k)", kRotary, [](Sid& s) { s.Oe.M1[0](1, kXY) += d; }},
      {"sum of Oe.M1 (xx,yy,zz) = -2 (Me - PsiIPsi)", kRotary, [](Sid& s) { s.Oe.M1[1](1, kXX) += d; }},
      {"PPdm[a][b] = PPdm[b][a]^T", kRotary, [](Sid& s) { s.integrals.PPdm[0][1](0, 1) += d; }},
      // identities of some mode types and references
      {"frequency_hz = sqrt(Ke_kk / Me_kk) / 2pi", kRotary, [](Sid& s) { s.refmod.frequency_hz[1] *= 1.001; }},
      {"normal modes: Me = I", kFree, [](Sid& s) { s.Me(1, 2) = s.Me(2, 1) = 1e-3; }},
      {"normal modes: Ke = diag(omega^2)", kFree, [](Sid& s) { s.Ke(0, 1) = s.Ke(1, 0) = 1e-3 * s.Ke(3, 3); }},
      {"normal and constraint modes: Ke coupling = 0", kRotaryCB,
       [](Sid& s) { s.Ke(0, 2) = s.Ke(2, 0) = 1e-3 * s.Ke(2, 2); }},
      {"damping model: De as stated", kFree, [](Sid& s) { s.De(1, 1) *= 1.01; }},
      {"free: Ct.M0 = 0", kFree, [](Sid& s) { s.Ct.M0(0, 1) = 1e-3; }},
      {"free: Cr.M0 = 0", kFree, [](Sid& s) { s.Cr.M0(2, 2) = 1e-3; }},
      {"reference is free, clamped:<interface> or craig-bampton", kClamped,
       [](Sid& s) { s.refmod.reference = "clamped:C"; }},
      {"clamped: the held interface node does not move", kClamped, [](Sid& s) { s.nodes[0].psi(1, 0) = 1e-3; }},
  };
}

std::string failures(const ValidationReport& r) {
  std::string out;
  for (const auto& c : r.checks)
    if (c.applicable && !c.pass) {
      std::ostringstream o;
      o << "  " << c.name << " rel " << c.rel << " " << c.note << "\n";
      out += o.str();
    }
  return out;
}

}  // namespace

TEST(Validate, CleanSyntheticBodiesPass) {
  for (Body b : {kRotary, kRotaryCB, kFree, kClamped}) {
    const ValidationReport r = validate(body(b));
    EXPECT_TRUE(r.ok()) << "body " << b << ":\n" << failures(r);
    for (const auto& c : r.checks) {
      if (c.applicable) {
        EXPECT_LE(c.rel, 1e-10) << c.name << " on body " << b;
      }
    }
  }
}

TEST(Validate, EachIdentityIsCaughtOnACraftedViolation) {
  for (const auto& v : violations()) {
    Sid s = body(v.body);
    ASSERT_NE(validate(s).find(v.check), nullptr) << "no check named '" << v.check << "'";
    v.spoil(s);
    const ValidationReport r = validate(s);
    const Check* c = r.find(v.check);
    ASSERT_TRUE(c->applicable) << v.check << ": " << c->note;
    EXPECT_FALSE(c->pass) << v.check << " not caught: rel " << c->rel << " tol " << c->tol;
    EXPECT_FALSE(r.ok());
  }
}

TEST(Validate, EveryApplicableCheckHasAViolationTest) {
  std::set<std::string> tested;
  for (const auto& v : violations()) tested.insert(v.check);
  for (Body b : {kRotary, kRotaryCB, kFree, kClamped})
    for (const auto& c : validate(body(b)).checks) EXPECT_TRUE(tested.count(c.name)) << "untested check: " << c.name;
}

TEST(Validate, PropertiesOfOneMemberAreToldFromIdentities) {
  // ffr-sim refuses a body failing a property and only notes a failed identity.
  const ValidationReport r = validate(body(kFree));
  for (const char* name : {"mass positive", "Me symmetric", "Ke symmetric", "Me positive definite", "Ke positive semi-definite",
                           "J.M0 positive semi-definite", "J.M0 principal moments: triangle inequality",
                           "J about the centre of mass: triangle inequality", "frequency_hz >= 0",
                           "normal modes: frequency_hz > 0", "node names unique and non-empty",
                           "interface names unique and non-empty", "AP0 are rotation matrices"})
    EXPECT_EQ(r.find(name)->kind, Check::Kind::Property) << name;
  for (const char* name : {"Me = sum_a PPdm[a][a] + rotary.PsiIPsi", "free: Ct.M0 = 0", "J.M1 symmetric"})
    EXPECT_EQ(r.find(name)->kind, Check::Kind::Identity) << name;
}

TEST(Validate, ChecksThatDoNotApplyAreSkippedNotFailed) {
  const ValidationReport r = validate(body(kRotary));  // craig-bampton, all modes normal
  EXPECT_FALSE(r.find("free: Ct.M0 = 0")->applicable);
  EXPECT_FALSE(r.find("normal and constraint modes: Ke coupling = 0")->applicable);
  EXPECT_FALSE(r.find("clamped: the held interface node does not move")->applicable);
}

TEST(Validate, InconsistentSizesGiveOneFailedCheck) {
  Sid s = body(kRotary);
  s.Me.resize(2, 2);
  const ValidationReport r = validate(s);
  ASSERT_EQ(r.checks.size(), 1u);
  EXPECT_FALSE(r.ok());
  EXPECT_NE(r.checks[0].note.find("Me"), std::string::npos);
}

TEST(Validate, KeM1OfTheWrongShapeIsASizeFailure) {
  Sid s = body(kFree);
  ASSERT_FALSE(s.KeM1.empty());
  s.KeM1[2].resize(3, 4);
  const ValidationReport r = validate(s);
  ASSERT_EQ(r.checks.size(), 1u);
  EXPECT_NE(r.checks[0].note.find("Ke.M1"), std::string::npos) << r.checks[0].note;
  s = body(kFree);
  s.KeM1.pop_back();
  EXPECT_FALSE(validate(s).ok());
}

// Ke.M1 is symmetric in (i,j) only: an asymmetry in k is how it is defined, not a failure.
TEST(Validate, KeM1NeedNotBeSymmetricInK) {
  Sid s = body(kClamped);
  ASSERT_FALSE(s.KeM1.empty());
  s.KeM1[0](1, 1) += 0.5;  // now KeM1[0](1,1) != KeM1[1](0,1)
  EXPECT_TRUE(validate(s).find("Ke.M1 symmetric in (i,j)")->pass);
  s.KeM1[0](0, 1) = NAN;
  EXPECT_FALSE(validate(s).find("Ke.M1 symmetric in (i,j)")->pass);
}

TEST(Validate, NonFiniteValuesFail) {
  Sid s = body(kFree);
  s.Ge[0](1, 1) = NAN;
  const ValidationReport r = validate(s);
  EXPECT_FALSE(r.find("Ge = 2 Kr (Cr.M1)")->pass);
  EXPECT_FALSE(r.find("Ge = 2 eps PPdm")->pass);
}

// The damping check holds in any modal basis: a Craig-Bampton-like rotated basis with ratio
// damping built from the reduced eigenproblem, Rayleigh damping, and none.
TEST(Validate, DampingModelsInAnyBasis) {
  Sid s = body(kRotaryCB);  // ratio 0.05, modes from direct sums
  Eigen::MatrixXd T = Eigen::MatrixXd::Identity(3, 3);
  T(0, 1) = 0.3;  // not orthogonal: Me and Ke are no longer diagonal
  Sid t = s;
  t.Me = T.transpose() * s.Me * T;
  t.Ke = T.transpose() * s.Ke * T;
  t.De = T.transpose() * s.De * T;
  EXPECT_TRUE(validate(t).find("damping model: De as stated")->pass);
  t.provenance.damping_model = "rayleigh alpha=0.5 beta=0.002";
  t.De = 0.5 * t.Me + 0.002 * t.Ke;
  EXPECT_TRUE(validate(t).find("damping model: De as stated")->pass);
  t.De(0, 0) *= 1.01;
  EXPECT_FALSE(validate(t).find("damping model: De as stated")->pass);
  t.provenance.damping_model = "none";
  EXPECT_FALSE(validate(t).find("damping model: De as stated")->pass);
  t.De.setZero();
  EXPECT_TRUE(validate(t).find("damping model: De as stated")->pass);
  t.provenance.damping_model = "matrix";
  EXPECT_FALSE(validate(t).find("damping model: De as stated")->applicable);
}
