// Round trip of every SID member through write_sid/read_sid must be bit-exact.
#include "ffr/formats/sid_io.hpp"
#include "ffr/formats/synthetic.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <random>

using namespace ffr::formats;

namespace {

// Fills every member with distinct random numbers so a swapped axis or index shows up.
Sid random_sid(int nq, int nodes, bool stiffening, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  auto fill = [&](auto& m) { for (Eigen::Index i = 0; i < m.size(); ++i) m.data()[i] = u(rng); };
  Sid s;
  for (int p = 0; p < nodes; ++p) s.nodes.push_back({"node" + std::to_string(p), {}, {}, {}, {}});
  if (stiffening) s.stiffening = Stiffening{};
  if (stiffening) s.stiffening->interfaces.push_back({"root", {}, {}});
  s.resize(nq);
  s.refmod.mass = 3.5;
  fill(s.refmod.frequency_hz);
  if (nq > 1) s.refmod.mode_type[1] = ModeType::Constraint;
  s.refmod.reference = "clamped:root";
  fill(s.mdCM.M0); fill(s.mdCM.M1); fill(s.J.M0);
  for (auto& m : s.J.M1) fill(m);
  fill(s.Ct.M0); fill(s.Cr.M0);
  for (auto& m : s.Cr.M1) fill(m);
  fill(s.Me); fill(s.Ke); fill(s.De);
  for (auto& m : s.Gr) fill(m);
  for (auto& m : s.Ge) fill(m);
  fill(s.Oe.M0);
  for (auto& m : s.Oe.M1) fill(m);
  fill(s.ksigma.M0); fill(s.ksigma.M1);
  fill(s.integrals.rdm); fill(s.integrals.rrdm); fill(s.integrals.Pdm);
  for (auto& m : s.integrals.rPdm) fill(m);
  for (auto& r : s.integrals.PPdm) for (auto& m : r) fill(m);
  fill(s.rotary.I); fill(s.rotary.PsiI); fill(s.rotary.PsiIPsi);
  if (stiffening) {
    for (auto& m : s.stiffening->K0t) fill(m);
    for (auto& m : s.stiffening->K0r) fill(m);
    for (auto& m : s.stiffening->K0om) fill(m);
    for (auto& m : s.stiffening->interfaces[0].K0F) fill(m);
    for (auto& m : s.stiffening->interfaces[0].K0M) fill(m);
    s.KeM1.assign(static_cast<std::size_t>(nq), Eigen::MatrixXd::Zero(nq, nq));
    for (auto& m : s.KeM1) fill(m);
  }
  for (auto& n : s.nodes) { fill(n.origin); fill(n.phi); fill(n.psi); fill(n.AP0); }
  if (nodes > 0) s.interfaces.push_back({"root", 0, "rigid", "clamp"});
  s.provenance.part_sha256 = "abc";
  s.provenance.reduction_method = "clamped";
  s.provenance.reduction_parameters = R"({"modes": 4})";
  s.provenance.damping_model = "ratio 0.01";
  s.provenance.element_counts["TET10"] = 1234;
  s.provenance.mass_model["J"] = "consistent";
  s.provenance.extra["note"] = "x";
  return s;
}

template <class A>
void expect_bits(const A& a, const A& b, const char* what) {
  ASSERT_EQ(a.rows(), b.rows()) << what;
  ASSERT_EQ(a.cols(), b.cols()) << what;
  for (Eigen::Index i = 0; i < a.size(); ++i) ASSERT_EQ(a.data()[i], b.data()[i]) << what << " at " << i;
}
template <class A>
void expect_bits(const std::vector<A>& a, const std::vector<A>& b, const char* what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  for (std::size_t k = 0; k < a.size(); ++k) expect_bits(a[k], b[k], what);
}

void expect_equal(const Sid& a, const Sid& b) {
  EXPECT_EQ(a.refmod.mass, b.refmod.mass);
  expect_bits(a.refmod.frequency_hz, b.refmod.frequency_hz, "frequency");
  EXPECT_EQ(a.refmod.mode_type, b.refmod.mode_type);
  EXPECT_EQ(a.refmod.reference, b.refmod.reference);
  expect_bits(a.mdCM.M0, b.mdCM.M0, "mdCM.M0"); expect_bits(a.mdCM.M1, b.mdCM.M1, "mdCM.M1");
  expect_bits(a.J.M0, b.J.M0, "J.M0"); expect_bits(a.J.M1, b.J.M1, "J.M1");
  expect_bits(a.Ct.M0, b.Ct.M0, "Ct.M0"); expect_bits(a.Cr.M0, b.Cr.M0, "Cr.M0"); expect_bits(a.Cr.M1, b.Cr.M1, "Cr.M1");
  expect_bits(a.Me, b.Me, "Me"); expect_bits(a.Ke, b.Ke, "Ke"); expect_bits(a.De, b.De, "De");
  expect_bits(a.Gr, b.Gr, "Gr"); expect_bits(a.Ge, b.Ge, "Ge");
  expect_bits(a.Oe.M0, b.Oe.M0, "Oe.M0"); expect_bits(a.Oe.M1, b.Oe.M1, "Oe.M1");
  expect_bits(a.ksigma.M0, b.ksigma.M0, "ksigma.M0"); expect_bits(a.ksigma.M1, b.ksigma.M1, "ksigma.M1");
  expect_bits(a.integrals.rdm, b.integrals.rdm, "rdm"); expect_bits(a.integrals.rrdm, b.integrals.rrdm, "rrdm");
  expect_bits(a.integrals.Pdm, b.integrals.Pdm, "Pdm");
  for (int i = 0; i < 3; ++i) expect_bits(a.integrals.rPdm[i], b.integrals.rPdm[i], "rPdm");
  for (int i = 0; i < 3; ++i) for (int j = 0; j < 3; ++j) expect_bits(a.integrals.PPdm[i][j], b.integrals.PPdm[i][j], "PPdm");
  expect_bits(a.rotary.I, b.rotary.I, "rotary.I"); expect_bits(a.rotary.PsiI, b.rotary.PsiI, "PsiI");
  expect_bits(a.rotary.PsiIPsi, b.rotary.PsiIPsi, "PsiIPsi");
  expect_bits(a.KeM1, b.KeM1, "Ke.M1");
  ASSERT_EQ(a.stiffening.has_value(), b.stiffening.has_value());
  if (a.stiffening) {
    expect_bits(a.stiffening->K0t, b.stiffening->K0t, "K0t");
    expect_bits(a.stiffening->K0r, b.stiffening->K0r, "K0r");
    expect_bits(a.stiffening->K0om, b.stiffening->K0om, "K0om");
    ASSERT_EQ(a.stiffening->interfaces.size(), b.stiffening->interfaces.size());
    for (std::size_t i = 0; i < a.stiffening->interfaces.size(); ++i) {
      EXPECT_EQ(a.stiffening->interfaces[i].name, b.stiffening->interfaces[i].name);
      expect_bits(a.stiffening->interfaces[i].K0F, b.stiffening->interfaces[i].K0F, "K0F");
      expect_bits(a.stiffening->interfaces[i].K0M, b.stiffening->interfaces[i].K0M, "K0M");
    }
  }
  ASSERT_EQ(a.nodes.size(), b.nodes.size());
  for (std::size_t p = 0; p < a.nodes.size(); ++p) {
    EXPECT_EQ(a.nodes[p].name, b.nodes[p].name);
    expect_bits(a.nodes[p].origin, b.nodes[p].origin, "origin");
    expect_bits(a.nodes[p].phi, b.nodes[p].phi, "phi");
    expect_bits(a.nodes[p].psi, b.nodes[p].psi, "psi");
    expect_bits(a.nodes[p].AP0, b.nodes[p].AP0, "AP0");
  }
  ASSERT_EQ(a.interfaces.size(), b.interfaces.size());
  for (std::size_t i = 0; i < a.interfaces.size(); ++i) {
    EXPECT_EQ(a.interfaces[i].name, b.interfaces[i].name);
    EXPECT_EQ(a.interfaces[i].node, b.interfaces[i].node);
    EXPECT_EQ(a.interfaces[i].coupling, b.interfaces[i].coupling);
    EXPECT_EQ(a.interfaces[i].group, b.interfaces[i].group);
  }
  EXPECT_EQ(a.provenance.part_sha256, b.provenance.part_sha256);
  EXPECT_EQ(a.provenance.reduction_method, b.provenance.reduction_method);
  EXPECT_EQ(a.provenance.reduction_parameters, b.provenance.reduction_parameters);
  EXPECT_EQ(a.provenance.damping_model, b.provenance.damping_model);
  EXPECT_EQ(a.provenance.element_counts, b.provenance.element_counts);
  EXPECT_EQ(a.provenance.mass_model, b.provenance.mass_model);
  EXPECT_EQ(a.provenance.extra, b.provenance.extra);
  ASSERT_EQ(a.visual.empty(), b.visual.empty());
  if (!a.visual.empty()) {
    expect_bits(a.visual.vertices, b.visual.vertices, "visual.vertices");
    ASSERT_TRUE(a.visual.triangles == b.visual.triangles);
    expect_bits(a.visual.modes, b.visual.modes, "visual.modes");
  }
}

std::filesystem::path temp_file(const std::string& name) {
  auto dir = std::filesystem::temp_directory_path() / ("ffr_roundtrip_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return dir / name;
}

}  // namespace

TEST(SidRoundTrip, EveryMemberBitExact) {
  for (bool stiff : {false, true}) {
    const Sid a = random_sid(5, 3, stiff, 42 + stiff);
    const auto path = temp_file(stiff ? "stiff.sid.h5" : "plain.sid.h5");
    write_sid(a, path);
    const Sid b = read_sid(path);
    expect_equal(a, b);
  }
}

TEST(SidRoundTrip, ZeroModesAndNoNodes) {
  const Sid a = random_sid(0, 0, false, 7);
  const auto path = temp_file("empty.sid.h5");
  write_sid(a, path);
  expect_equal(a, read_sid(path));
}

TEST(SidRoundTrip, InconsistentSizesAreRefusedBeforeWriting) {
  Sid a = random_sid(3, 2, false, 1);
  a.Me.resize(2, 2);
  const auto path = temp_file("bad.sid.h5");
  std::filesystem::remove(path);
  EXPECT_THROW(write_sid(a, path), std::invalid_argument);
  EXPECT_FALSE(std::filesystem::exists(path));
}

// A physically meaningful body (synthetic spring chain with stiffening and damping) plus a
// small visual surface: every member, the provenance and /visual come back bit-exact.
TEST(SidRoundTrip, SyntheticChainWithVisualBitExact) {
  ffr::formats::synthetic::ChainParams p;
  p.points = 7;
  p.modes = 5;
  p.stiffening = true;
  p.damping_ratio = 0.03;
  p.start = Eigen::Vector3d(0.1, -0.2, 0.3);
  Sid a = ffr::formats::synthetic::spring_chain(p).sid;
  a.visual.vertices.resize(3, 3);
  a.visual.vertices << 0, 0, 0, 1, 0, 0, 0, 1, 0;
  a.visual.triangles.resize(1, 3);
  a.visual.triangles << 0, 1, 2;
  a.visual.modes.assign(5, decltype(a.visual.modes)::value_type::Random(3, 3));
  const auto path = temp_file("chain.sid.h5");
  write_sid(a, path);
  expect_equal(a, read_sid(path));
}
