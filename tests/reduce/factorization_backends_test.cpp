// The two factorization backends (reduction.factorization: "supernodal", the default, and
// "cholmod", CHOLMOD's own factorization and solves, the reference) give the same SID on a
// solid, a shell and a beam part, each clamped, free and Craig-Bampton: formats::diff (what
// ffr-diff runs) at rtol 1e-9. Reference: CHOLMOD's cholmod_l_factorize / cholmod_l_solve2,
// code nobody here wrote; the factors differ by rounding only, so every member of the SID must
// agree far below the modes' own accuracy.
#include "ffr/formats/diff.hpp"
#include "ffr/preproc/part/part.hpp"
#include "ffr/preproc/pipeline.hpp"
#include "support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <tuple>

using namespace ffr;

namespace {

enum class Body { Solid, Shell, Beam };
enum class Method { Clamped, Free, CraigBampton };

std::string name_of(Body b) { return b == Body::Solid ? "solid" : b == Body::Shell ? "shell" : "beam"; }
std::string name_of(Method m) {
  return m == Method::Clamped ? "clamped" : m == Method::Free ? "free" : "craig_bampton";
}

// Small meshes (a few hundred to a few thousand DOF) whose eigen-solves still take the block
// Lanczos path with its factor (not the dense fallback): 2 x its basis of 24 vectors fits.
const char* kSolidGeo = R"(SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 0.2, 0.02, 0.012};
Physical Volume("body") = {1};
Physical Surface("left") = Surface In BoundingBox{-1e-6, -1, -1, 1e-6, 1, 1};
Physical Surface("right") = Surface In BoundingBox{0.2 - 1e-6, -1, -1, 0.2 + 1e-6, 1, 1};
)";
const char* kShellGeo = R"(Point(1) = {0, 0, 0}; Point(2) = {0.5, 0, 0}; Point(3) = {0.5, 0.1, 0}; Point(4) = {0, 0.1, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Transfinite Curve{1, 3} = 26; Transfinite Curve{2, 4} = 6;
Transfinite Surface{1}; Recombine Surface{1};
Physical Surface("plate") = {1}; Physical Curve("left") = {4}; Physical Curve("right") = {2};
)";
const char* kBeamGeo = R"(Point(1) = {0, 0, 0}; Point(2) = {1, 0, 0}; Line(1) = {1, 2};
Transfinite Curve{1} = 41; Physical Curve("beam") = {1}; Physical Point("left") = {1}; Physical Point("right") = {2};
)";

std::string part_json(Body b, Method m, const std::string& factorization) {
  std::string s;
  switch (b) {
    case Body::Solid:
      s = R"({"geometry": "part.geo", "mesh": {"size": 0.008, "order": 1},
        "materials": [{"group": "body", "E": 2.1e11, "nu": 0.3, "rho": 7850}],)";
      break;
    case Body::Shell:
      s = R"({"geometry": "part.geo", "mesh": {"order": 1},
        "shells": [{"group": "plate", "thickness": 0.002, "E": 7e10, "nu": 0.3, "rho": 2700}],)";
      break;
    case Body::Beam:
      s = R"({"geometry": "part.geo", "mesh": {"order": 1},
        "beams": [{"group": "beam", "E": 2.1e11, "nu": 0.3, "rho": 7850, "y_axis": [0, 1, 0],
                   "section": {"A": 1.2e-3, "Iy": 4e-8, "Iz": 3.6e-7, "J": 1.5e-7}}],)";
      break;
  }
  s += R"( "interfaces": [{"name": "L", "group": "left"}, {"name": "R", "group": "right"}], "visual": false,
    "reduction": {)";
  switch (m) {
    case Method::Clamped: s += R"("method": "clamped", "interface": "L", "modes": 5)"; break;
    case Method::Free: s += R"("method": "free", "modes": 5)"; break;
    case Method::CraigBampton: s += R"("method": "craig-bampton", "interfaces": ["L", "R"], "frame": "L", "modes": 5)"; break;
  }
  return s + R"(, "factorization": ")" + factorization + R"("}})";
}

formats::Sid reduce(const test::TempDir& dir, Body b, Method m, const std::string& factorization) {
  test::write_text(dir / "part.geo", b == Body::Solid ? kSolidGeo : b == Body::Shell ? kShellGeo : kBeamGeo);
  test::write_text(dir / "part.json", part_json(b, m, factorization));
  return preproc::run_pipeline(preproc::load_part(dir / "part.json"));
}

class FactorizationBackends : public ::testing::TestWithParam<std::tuple<Body, Method>> {};

}  // namespace

TEST_P(FactorizationBackends, GiveTheSameSid) {
  const auto [body, method] = GetParam();
  test::TempDir dir("backends");
  const formats::Sid supernodal = reduce(dir, body, method, "supernodal");
  const formats::Sid cholmod = reduce(dir, body, method, "cholmod");
  ASSERT_EQ(supernodal.provenance.extra.at("factorization"), "supernodal");
  ASSERT_EQ(cholmod.provenance.extra.at("factorization"), "cholmod");
  ASSERT_EQ(supernodal.nq(), cholmod.nq());
  ASSERT_GE(supernodal.nq(), 5);
  formats::DiffOptions opt;  // as ffr-diff --rtol 1e-9
  opt.rtol = 1e-9;
  opt.group_rtol = std::max(opt.group_rtol, opt.rtol);
  const formats::DiffReport rep = formats::diff(supernodal, cholmod, opt);
  std::string worst;
  for (const auto& d : rep.worst)
    worst += "\n  " + d.dataset + d.index + ": " + std::to_string(d.a) + " vs " + std::to_string(d.b) + " (rel " +
             std::to_string(d.rel) + ")";
  EXPECT_TRUE(rep.equivalent) << rep.datasets_different << " of " << rep.datasets_compared << " datasets differ:" << worst;
  EXPECT_GT(rep.datasets_compared, 10);
}

INSTANTIATE_TEST_SUITE_P(AllPartTypes, FactorizationBackends,
                         ::testing::Combine(::testing::Values(Body::Solid, Body::Shell, Body::Beam),
                                            ::testing::Values(Method::Clamped, Method::Free, Method::CraigBampton)),
                         [](const auto& info) {
                           return name_of(std::get<0>(info.param)) + "_" + name_of(std::get<1>(info.param));
                         });
