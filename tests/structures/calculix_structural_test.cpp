// Shells and beams against CalculiX (ccx 2.20) on the identical mesh. The formulations differ,
// so agreement is at the level of those differences, not round-off:
//  - ffr QUAD4: MITC4 transverse shear, incompatible-mode membrane, Hughes–Brezzi drilling,
//    thickness-integrated consistent mass. ccx S4: expanded internally into a layer of 3D
//    C3D8I bricks through the thickness (CalculiX manual, "Shell elements").
//  - ffr beam: 2-node Timoshenko with interdependent interpolation, shear factor 5/6 for the
//    rectangle, rotary inertia. ccx B31: expanded into C3D20R bricks of the rectangular
//    section (CalculiX manual, "Beam elements"), i.e. 3D elasticity of the bar.
#include "ffr/preproc/mesh/gmsh_import.hpp"
#include "ffr/preproc/pipeline.hpp"
#include "../reduce/support.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <sstream>

using namespace ffr;

TEST(CalculiXStructural, CantileverPlateOfShellsVsS4) {
  test::TempDir dir("ccxshell");
  test::write_text(dir / "plate.geo", R"(
Point(1) = {0, 0, 0}; Point(2) = {0.4, 0, 0}; Point(3) = {0.4, 0.2, 0}; Point(4) = {0, 0.2, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Transfinite Curve{1, 3} = 33; Transfinite Curve{2, 4} = 17; Transfinite Surface{1}; Recombine Surface{1};
Physical Surface("plate") = {1}; Physical Curve("clamp") = {4};
)");
  test::write_text(dir / "plate.json", R"({"geometry": "plate.geo", "mesh": {"order": 1},
    "shells": [{"group": "plate", "thickness": 0.005, "E": 7e10, "nu": 0.3, "rho": 2700}],
    "interfaces": [{"name": "root", "group": "clamp"}],
    "reduction": {"method": "clamped", "interface": "root", "modes": 5}, "visual": false})");
  const auto part = preproc::load_part(dir / "plate.json");
  const formats::Sid sid = preproc::run_pipeline(part);
  test::CcxSection sec;
  sec.kind = "shell";
  sec.thickness = 0.005;
  const auto ccx = test::calculix_frequency_structural(preproc::load_mesh(part), {7e10, 0.3, 2700}, "plate", sec, "clamp", 5,
                                                       dir.path());
  ASSERT_EQ(ccx.frequency_hz.size(), 5u);
  for (Eigen::Index k = 0; k < 5; ++k)
    std::printf("  plate mode %ld: ffr QUAD4 %.3f Hz, CalculiX S4 %.3f Hz (%+.2f %%)\n", static_cast<long>(k + 1),
                sid.refmod.frequency_hz(k), ccx.frequency_hz[static_cast<std::size_t>(k)],
                100 * (sid.refmod.frequency_hz(k) / ccx.frequency_hz[static_cast<std::size_t>(k)] - 1));
  for (Eigen::Index k = 0; k < 5; ++k)
    EXPECT_NEAR(sid.refmod.frequency_hz(k) / ccx.frequency_hz[static_cast<std::size_t>(k)], 1.0, 0.005)
        << "mode " << k + 1 << ": ffr " << sid.refmod.frequency_hz(k) << " Hz, CalculiX S4 " << ccx.frequency_hz[static_cast<std::size_t>(k)];
}

TEST(CalculiXStructural, CantileverOfBeamsVsB31) {
  test::TempDir dir("ccxbeam");
  test::write_text(dir / "beam.geo", R"(Point(1) = {0, 0, 0}; Point(2) = {1, 0, 0}; Line(1) = {1, 2};
Transfinite Curve{1} = 41; Physical Curve("beam") = {1}; Physical Point("root") = {1};
)");
  // Rectangle 30 mm (local y, global y) x 20 mm (local z, global z): Iy = b h^3/12 = 2e-8,
  // Iz = h b^3/12 = 4.5e-8, J (Roark, rectangle 2a x 2b, a/b = 1.5) = 0.196 b h^3... from
  // J = a b^3 (16/3 - 3.36 b/a (1 - b^4/(12 a^4))) with a = 0.015, b = 0.01.
  const double a = 0.015, bb = 0.01;
  const double J = a * bb * bb * bb * (16.0 / 3.0 - 3.36 * bb / a * (1 - std::pow(bb / a, 4) / 12));
  test::write_text(dir / "beam.json", R"({"geometry": "beam.geo", "mesh": {"order": 1},
    "beams": [{"group": "beam", "E": 2.1e11, "nu": 0.3, "rho": 7850, "y_axis": [0, 1, 0],
               "section": {"A": 6e-4, "Iy": 2e-8, "Iz": 4.5e-8, "J": )" + [&] { std::ostringstream o; o.precision(12); o << J; return o.str(); }() + R"(, "ky": 0.8333333, "kz": 0.8333333}}],
    "interfaces": [{"name": "root", "group": "root"}],
    "reduction": {"method": "clamped", "interface": "root", "modes": 6}, "visual": false})");
  const auto part = preproc::load_part(dir / "beam.json");
  const formats::Sid sid = preproc::run_pipeline(part);
  test::CcxSection sec;
  sec.kind = "beam";
  sec.b = 0.03;  // along the local 1-axis = n1
  sec.h = 0.02;
  sec.n1 = Eigen::Vector3d::UnitY();
  const auto ccx = test::calculix_frequency_structural(preproc::load_mesh(part), {2.1e11, 0.3, 7850}, "beam", sec, "root", 6,
                                                       dir.path());
  ASSERT_EQ(ccx.frequency_hz.size(), 6u);
  // Bending modes in both planes (the torsion mode differs more: ccx resolves warping in 3D,
  // the beam uses Saint-Venant's J): compare the first four.
  for (Eigen::Index k = 0; k < 6; ++k)
    std::printf("  beam mode %ld: ffr %.3f Hz, CalculiX B31 %.3f Hz (%+.2f %%)\n", static_cast<long>(k + 1),
                sid.refmod.frequency_hz(k), ccx.frequency_hz[static_cast<std::size_t>(k)],
                100 * (sid.refmod.frequency_hz(k) / ccx.frequency_hz[static_cast<std::size_t>(k)] - 1));
  for (Eigen::Index k = 0; k < 4; ++k)
    EXPECT_NEAR(sid.refmod.frequency_hz(k) / ccx.frequency_hz[static_cast<std::size_t>(k)], 1.0, 0.01)
        << "mode " << k + 1 << ": ffr " << sid.refmod.frequency_hz(k) << " Hz, CalculiX B31 " << ccx.frequency_hz[static_cast<std::size_t>(k)];
}
