// The same TET10 mesh through ffr-reduce and through CalculiX *FREQUENCY (an independent FE
// code, `ccx` 2.20 from Debian): frequencies agree to 1e-4 relative, and the modal
// participation factors CalculiX prints (Phi^T M r for unit translations and rotations about
// the global origin, mass-normalised modes) equal Ct.M0 and Cr.M0 up to each mode's sign.
#include "ffr/preproc/mesh/gmsh_import.hpp"
#include "ffr/preproc/pipeline.hpp"
#include "support.hpp"

#include <gtest/gtest.h>

using namespace ffr;

namespace {

struct Fixture {
  test::TempDir dir{"calculix"};
  preproc::Material mat{2.1e11, 0.3, 7850};
  Fixture() {
    test::write_text(dir / "bar.geo", R"(SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 0.2, 0.02, 0.012};
Physical Volume("body") = {1};
Physical Surface("clamp") = Surface In BoundingBox{-1e-6, -1, -1, 1e-6, 1, 1};
)");
    test::gmsh_mesh(dir / "bar.geo", dir / "bar.msh", 0.004, 2);
  }
  formats::Sid reduce(const std::string& reduction) {
    test::write_text(dir / "bar.json", R"({"geometry": "bar.msh",
      "materials": [{"group": "body", "E": 2.1e11, "nu": 0.3, "rho": 7850}],
      "interfaces": [{"name": "root", "group": "clamp"}], "visual": false,
      "reduction": )" + reduction + "}");
    return preproc::run_pipeline(preproc::load_part(dir / "bar.json"));
  }
  preproc::Mesh mesh() {
    preproc::PartSpec p = preproc::load_part(dir / "bar.json");
    return preproc::load_mesh(p);
  }
};

// Compares mode k of ffr with mode j of CalculiX.
void compare(const formats::Sid& sid, Eigen::Index k, const test::CcxModes& ccx, Eigen::Index j) {
  const double f = sid.refmod.frequency_hz(k), fc = ccx.frequency_hz[static_cast<std::size_t>(j)];
  EXPECT_NEAR(f / fc, 1.0, 1e-4) << "mode " << k + 1 << ": " << f << " Hz (ffr) vs " << fc << " Hz (CalculiX)";
  const Eigen::RowVector3d t = sid.Ct.M0.row(k), r = sid.Cr.M0.row(k);
  const Eigen::RowVector3d tc = ccx.participation.row(j).head<3>(), rc = ccx.participation.row(j).tail<3>();
  const double sign = (t.dot(tc) + r.dot(rc)) >= 0 ? 1.0 : -1.0;
  const double scale_t = std::max(tc.norm(), 1e-3 * std::sqrt(sid.refmod.mass));
  const double scale_r = std::max(rc.norm(), 1e-3 * std::sqrt(sid.J.M0.trace()));
  EXPECT_LT((sign * t - tc).norm(), 2e-3 * scale_t) << "mode " << k + 1 << " Ct.M0 " << t << " vs CalculiX " << tc;
  EXPECT_LT((sign * r - rc).norm(), 2e-3 * scale_r) << "mode " << k + 1 << " Cr.M0 " << r << " vs CalculiX " << rc;
}

}  // namespace

TEST(CalculiX, ClampedModesOnTheIdenticalMesh) {
  Fixture fx;
  const formats::Sid sid = fx.reduce(R"({"method": "clamped", "interface": "root", "modes": 6})");
  const auto ccx = test::calculix_frequency(fx.mesh(), fx.mat, "body", "clamp", 6, fx.dir.path());
  ASSERT_EQ(ccx.frequency_hz.size(), 6u);
  for (Eigen::Index k = 0; k < 6; ++k) compare(sid, k, ccx, k);
}

TEST(CalculiX, FreeFreeModesOnTheIdenticalMesh) {
  Fixture fx;
  const formats::Sid sid = fx.reduce(R"({"method": "free", "modes": 6})");
  // CalculiX returns the six rigid-body modes first (near-zero frequencies), then the elastic ones.
  const auto ccx = test::calculix_frequency(fx.mesh(), fx.mat, "body", "", 12, fx.dir.path());
  ASSERT_EQ(ccx.frequency_hz.size(), 12u);
  for (int j = 0; j < 6; ++j) EXPECT_LT(ccx.frequency_hz[static_cast<std::size_t>(j)], 1e-3 * ccx.frequency_hz[6]);
  for (Eigen::Index k = 0; k < 6; ++k) {
    EXPECT_NEAR(sid.refmod.frequency_hz(k) / ccx.frequency_hz[static_cast<std::size_t>(k + 6)], 1.0, 1e-4) << "elastic mode " << k + 1;
    // Free-free elastic modes carry no net momentum: Ct.M0 = Cr.M0 = 0 on both sides.
    EXPECT_LT(sid.Ct.M0.row(k).norm(), 1e-8 * std::sqrt(sid.refmod.mass));
    EXPECT_LT(sid.Cr.M0.row(k).norm(), 1e-8 * std::sqrt(sid.J.M0.trace()));
  }
}
