// The SID's optional /stress group (formats/SPEC.md section 12.1): written with the SID, left
// out by read_sid (what the runtime loads), read back exactly by read_modal_stress, refused when
// its shape is wrong (in memory by validate's size check, in a file naming the dataset), and the
// von Mises and principal stresses against closed forms.
#include "ffr/formats/h5.hpp"
#include "ffr/formats/modal_stress.hpp"
#include "ffr/formats/sid_io.hpp"
#include "ffr/formats/synthetic.hpp"
#include "ffr/formats/validate.hpp"
#include "support.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace ffr;

namespace {

formats::ModalStress stress_for(Eigen::Index nq, Eigen::Index ns) {
  formats::ModalStress s;
  s.selection = "group:top";
  s.recovery = "test";
  for (Eigen::Index i = 0; i < ns; ++i) s.node.push_back(100 + i);
  s.position = formats::ModalStress::RowsX3::Random(ns, 3);
  for (Eigen::Index k = 0; k < nq; ++k) s.modes.push_back(formats::ModalStress::RowsX6::Random(ns, 6) * 1e8);
  return s;
}

formats::Sid chain() {
  formats::synthetic::ChainParams p;
  p.modes = 3;
  return formats::synthetic::spring_chain(p).sid;
}

}  // namespace

TEST(StressGroup, WrittenWithTheSidAndReadOnlyByItsOwnReader) {
  test::TempDir dir("stress_format");
  formats::Sid sid = chain();
  sid.stress = stress_for(sid.nq(), 5);
  formats::write_sid(sid, dir / "s.sid.h5");
  const formats::Sid back = formats::read_sid(dir / "s.sid.h5");
  EXPECT_FALSE(back.stress.has_value());
  EXPECT_TRUE(formats::validate(sid).ok());
  const auto s = formats::read_modal_stress(dir / "s.sid.h5");
  ASSERT_TRUE(s.has_value());
  EXPECT_EQ(s->selection, "group:top");
  EXPECT_EQ(s->node, sid.stress->node);
  EXPECT_EQ(s->position, sid.stress->position);
  ASSERT_EQ(s->modes.size(), sid.stress->modes.size());
  for (std::size_t k = 0; k < s->modes.size(); ++k) EXPECT_EQ(s->modes[k], sid.stress->modes[k]);
  // A SID without the group.
  sid.stress.reset();
  formats::write_sid(sid, dir / "plain.sid.h5");
  EXPECT_FALSE(formats::read_modal_stress(dir / "plain.sid.h5").has_value());
}

TEST(StressGroup, WrongShapesAreRefused) {
  test::TempDir dir("stress_shape");
  formats::Sid sid = chain();
  sid.stress = stress_for(sid.nq() + 1, 4);  // one block too many
  const auto report = formats::validate(sid);
  ASSERT_FALSE(report.ok());
  EXPECT_NE(report.checks.front().note.find("stress.modes"), std::string::npos) << report.checks.front().note;
  EXPECT_THROW(formats::write_sid(sid, dir / "bad.sid.h5"), std::invalid_argument);
  EXPECT_FALSE(std::filesystem::exists(dir / "bad.sid.h5"));
  sid.stress = stress_for(sid.nq(), 4);
  sid.stress->modes[1](2, 3) = NAN;
  EXPECT_THROW(formats::write_sid(sid, dir / "bad.sid.h5"), std::invalid_argument);

  // A file whose /stress/modes has 5 columns: refused naming the dataset.
  {
    formats::h5::Writer w(dir / "file.sid.h5");
    w.attr("/", "format", std::string("ffr-sid"));
    w.attr("/", "format_version", std::int64_t{2});
    const double f[2] = {1, 2};
    w.write("/refmod/frequency_hz", f, {2});
    const std::int64_t nodes[3] = {1, 2, 3};
    w.write("/stress/node", nodes, {3});
    const std::vector<double> pos(9, 0.0), modes(2 * 3 * 5, 1.0);
    w.write("/stress/position", pos.data(), {3, 3});
    w.write("/stress/modes", modes.data(), {2, 3, 5});
    w.close();
  }
  try {
    formats::read_modal_stress(dir / "file.sid.h5");
    ADD_FAILURE() << "a /stress/modes of shape [2,3,5] was accepted";
  } catch (const formats::FormatError& e) {
    EXPECT_EQ(e.object(), "/stress/modes") << e.what();
  }
}

// Shell rows (SPEC.md section 12.1): /stress/layer and /stress/normal round-trip, a solid-only
// group is written without them (as before shells carried stress), and a layer outside 0..3 or
// a missing normal is refused naming the dataset.
TEST(StressGroup, ShellLayersRoundTripAndBadLayersAreRefused) {
  test::TempDir dir("stress_layers");
  formats::Sid sid = chain();
  sid.stress = stress_for(sid.nq(), 4);
  sid.stress->layer = {formats::kSolid, formats::kShellTop, formats::kShellMiddle, formats::kShellBottom};
  sid.stress->normal = formats::ModalStress::RowsX3::Zero(4, 3);
  for (int r = 1; r < 4; ++r) sid.stress->normal.row(r) << 0, 0, 1;
  formats::write_sid(sid, dir / "s.sid.h5");
  const auto s = formats::read_modal_stress(dir / "s.sid.h5");
  ASSERT_TRUE(s.has_value());
  EXPECT_EQ(s->layer, sid.stress->layer);
  EXPECT_EQ(s->normal, sid.stress->normal);
  EXPECT_STREQ(formats::layer_name(s->layer_of(3)), "bottom");
  sid.stress->layer[2] = 7;
  EXPECT_THROW(formats::check_modal_stress(*sid.stress, sid.nq()), std::invalid_argument);
  EXPECT_THROW(formats::write_sid(sid, dir / "bad.sid.h5"), std::invalid_argument);

  sid.stress = stress_for(sid.nq(), 4);  // solid only: no layer datasets
  formats::write_sid(sid, dir / "solid.sid.h5");
  EXPECT_FALSE(formats::h5::Reader(dir / "solid.sid.h5").exists("/stress/layer"));
  const auto solid = formats::read_modal_stress(dir / "solid.sid.h5");
  ASSERT_TRUE(solid.has_value());
  EXPECT_TRUE(solid->layer.empty());
  EXPECT_EQ(solid->layer_of(2), formats::kSolid);

  for (const bool normal : {true, false}) {
    {
      formats::h5::Writer w(dir / "file.sid.h5");
      w.attr("/", "format", std::string("ffr-sid"));
      w.attr("/", "format_version", std::int64_t{1});
      const double f[1] = {1};
      w.write("/refmod/frequency_hz", f, {1});
      const std::int64_t nodes[2] = {1, 1}, layer[2] = {1, normal ? 4 : 3};
      w.write("/stress/node", nodes, {2});
      const std::vector<double> pos(6, 0.0), modes(12, 1.0);
      w.write("/stress/position", pos.data(), {2, 3});
      w.write("/stress/modes", modes.data(), {1, 2, 6});
      w.write("/stress/layer", layer, {2});
      if (normal) w.write("/stress/normal", pos.data(), {2, 3});
      w.close();
    }
    try {
      formats::read_modal_stress(dir / "file.sid.h5");
      ADD_FAILURE() << "a bad /stress/layer group was accepted";
    } catch (const formats::FormatError& e) {
      EXPECT_EQ(e.object(), normal ? "/stress/layer" : "/stress/normal") << e.what();
    }
  }
}

// Closed forms: uniaxial sigma gives von Mises |sigma|; pure shear tau gives sqrt(3) tau and
// principal stresses (tau, 0, -tau); a hydrostatic state gives 0.
TEST(StressGroup, EquivalentAndPrincipalStresses) {
  Eigen::Matrix<double, 6, 1> s;
  s << -3e8, 0, 0, 0, 0, 0;
  EXPECT_NEAR(formats::von_mises(s), 3e8, 1e-6);
  s << 0, 0, 0, 0, 2e7, 0;
  EXPECT_NEAR(formats::von_mises(s), std::sqrt(3.0) * 2e7, 1e-6);
  const Eigen::Vector3d p = formats::principal_stresses(s);
  EXPECT_NEAR(p[0], 2e7, 1e-6);
  EXPECT_NEAR(p[1], 0, 1e-6);
  EXPECT_NEAR(p[2], -2e7, 1e-6);
  s << 5e6, 5e6, 5e6, 0, 0, 0;
  EXPECT_NEAR(formats::von_mises(s), 0, 1e-6);
}
