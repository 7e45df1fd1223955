// Nastran bulk data (.bdf) as a part's geometry.
//
// References, none computed by ffr:
//  - gmsh's own bulk-data writer (gmsh 4.8, `-format bdf`) in its three field formats (free,
//    small and large field, `Mesh.BdfFieldFormat` 0, 1, 2) of one TET10 mesh: the nodes (to the
//    digits each format prints) and the elements' nodes (in gmsh order, through the CTETRA
//    order gmsh writes) equal those of the MSH 4.1 file of that mesh.
//  - The same mesh written here in free field at full precision (GRID, CTETRA over two lines,
//    SET1, PSOLID, MAT1 in the layouts of the MSC Nastran Quick Reference Guide) gives the same
//    SID as the MSH file (formats::diff, rtol 1e-9), material taken from the deck.
//  - A CBAR/PBAR cantilever against Euler-Bernoulli beam theory (first bending frequency
//    (1.8751^2 / 2 pi) sqrt(E I / (rho A L^4))): I1 bends in the plane of the bar and its
//    orientation vector v (Quick Reference Guide, PBAR and CBAR), I2 out of it.
#include "ffr/formats/diff.hpp"
#include "ffr/formats/h5.hpp"
#include "ffr/formats/text_file.hpp"
#include "ffr/preproc/mesh/gmsh_import.hpp"
#include "ffr/preproc/pipeline.hpp"
#include "mesh/bdf_reader.hpp"
#include "deck_refusal.hpp"
#include "support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>

using namespace ffr;

namespace {

// gmsh's bulk data of `msh` in field format `format`, without the CTRIA6 cards gmsh writes for
// the surface group (ffr takes no TRI6 shells) and their continuation lines.
std::string gmsh_bdf(const std::filesystem::path& msh, const std::filesystem::path& bdf, int format) {
  const auto r = test::run("gmsh " + msh.string() + " -0 -setnumber Mesh.BdfFieldFormat " + std::to_string(format) +
                           " -format bdf -o " + bdf.string());
  if (r.status != 0 || !std::filesystem::exists(bdf)) throw std::runtime_error("gmsh failed: " + r.output);
  std::istringstream in(formats::read_text_file(bdf));
  std::ostringstream out;
  std::string line;
  bool drop = false;
  while (std::getline(in, line)) {
    const bool continuation = line.empty() || line[0] == '+' || line[0] == '*' || line[0] == ' ' || line[0] == ',';
    if (!continuation) drop = line.rfind("CTRIA6", 0) == 0;
    if (!drop) out << line << "\n";
  }
  return out.str();
}

struct TetBar {
  test::TempDir dir{"interop_bdf"};
  preproc::Mesh msh;
  TetBar() {
    test::write_text(dir / "bar.geo", R"(SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 0.2, 0.02, 0.012};
Physical Volume("body") = {1};
Physical Surface("clamp") = Surface In BoundingBox{-1e-6, -1, -1, 1e-6, 1, 1};
)");
    test::gmsh_mesh(dir / "bar.geo", dir / "bar.msh", 0.006, 2);
    preproc::PartSpec p;
    p.geometry = dir / "bar.msh";
    msh = preproc::load_mesh(p);
  }
  const preproc::ElementBlock& body() const {
    for (const auto& b : msh.blocks)
      if (b.group == "body") return b;
    throw std::runtime_error("no body");
  }
  // The clamp's node tags as SET1 1 in free field, 8 a line.
  std::string clamp_set() const {
    std::ostringstream s;
    s << "SET1,1";
    int k = 2;  // the SID takes the first of the line's 8 data fields
    for (const auto n : msh.node_groups.at("clamp")) {
      if (k == 9) {
        s << "\n+";
        k = 1;
      }
      s << "," << msh.node_tag(n);
      ++k;
    }
    s << "\n";
    return s.str();
  }
};

// element tag -> node tags in gmsh order, of every TET10 of the blocks of `group`.
std::map<std::size_t, std::vector<std::size_t>> elements(const preproc::Mesh& m, const std::string& group) {
  std::map<std::size_t, std::vector<std::size_t>> out;
  for (const auto& b : m.blocks)
    if (b.group == group && b.type == preproc::ElementType::Tet10)
      for (preproc::Index e = 0; e < b.size(); ++e)
        for (int i = 0; i < 10; ++i) out[m.element_tag(b, e)].push_back(m.node_tag(b.element(e)[i]));
  return out;
}

}  // namespace

TEST(BdfDeck, GmshBulkDataInThreeFieldFormats) {
  TetBar bar;
  const auto reference = elements(bar.msh, "body");
  ASSERT_FALSE(reference.empty());
  std::map<std::size_t, Eigen::Vector3d> x;
  for (preproc::Index n = 0; n < bar.msh.num_nodes(); ++n) x[bar.msh.node_tag(n)] = bar.msh.x.row(n).transpose();
  // Free and small field print 6 decimals, large field 9 significant digits.
  const std::vector<std::pair<int, double>> formats = {{0, 5.1e-7}, {1, 5.1e-7}, {2, 5.1e-10}};
  for (const auto& [format, tol] : formats) {
    const auto file = bar.dir / ("f" + std::to_string(format) + ".bdf");
    test::write_text(file, gmsh_bdf(bar.dir / "bar.msh", file, format));
    const preproc::Mesh m = preproc::detail::read_bdf(file.string(), nullptr);
    ASSERT_EQ(m.num_nodes(), bar.msh.num_nodes()) << "format " << format;
    double worst = 0;
    for (preproc::Index n = 0; n < m.num_nodes(); ++n)
      worst = std::max(worst, (m.x.row(n).transpose() - x.at(m.node_tag(n))).cwiseAbs().maxCoeff());
    EXPECT_LE(worst, tol) << "format " << format;
    // gmsh writes the volume's physical tag as the property id.
    EXPECT_EQ(elements(m, "pid1"), reference) << "format " << format;
    EXPECT_EQ(elements(m, "all"), reference) << "format " << format;
  }
}

namespace {

// The mesh in free field at full precision: GRID, CTETRA (Nastran's G1..G10: gmsh's with its
// last two edge nodes swapped, Quick Reference Guide CTETRA), over two lines.
std::string free_field_deck(const preproc::Mesh& m, const preproc::ElementBlock& b) {
  std::ostringstream s;
  s.precision(17);
  s << "$ written by the test\nBEGIN BULK\n";
  for (preproc::Index n = 0; n < m.num_nodes(); ++n)
    s << "GRID," << m.node_tag(n) << ",," << m.x(n, 0) << "," << m.x(n, 1) << "," << m.x(n, 2) << "\n";
  const int order[10] = {0, 1, 2, 3, 4, 5, 6, 7, 9, 8};
  for (preproc::Index e = 0; e < b.size(); ++e) {
    s << "CTETRA," << m.element_tag(b, e) << ",7";
    for (int i = 0; i < 10; ++i) s << (i == 6 ? ",+C\n+C," : ",") << m.node_tag(b.element(e)[order[i]]);
    s << "\n";
  }
  return s.str();
}

}  // namespace

TEST(BdfDeck, FullPrecisionDeckGivesTheSameSidAsTheMsh) {
  TetBar bar;
  test::write_text(bar.dir / "bar.bdf", free_field_deck(bar.msh, bar.body()) + bar.clamp_set() +
                                            "PSOLID,7,3\nMAT1,3,2.1+11,,0.3,7850.\nEIGRL,10,,,6\nENDDATA\n");
  const auto reduce = [&](const std::string& json) {
    test::write_text(bar.dir / "part.json", json);
    return preproc::run_pipeline(preproc::load_part(bar.dir / "part.json"));
  };
  const formats::Sid a = reduce(R"({"geometry": "bar.msh", "visual": false,
    "materials": [{"group": "body", "E": 2.1e11, "nu": 0.3, "rho": 7850}],
    "interfaces": [{"name": "root", "group": "clamp"}], "stiffening": true,
    "reduction": {"method": "clamped", "interface": "root", "modes": 6}})");
  const formats::Sid b = reduce(R"({"geometry": "bar.bdf", "visual": false,
    "interfaces": [{"name": "root", "group": "set1"}], "stiffening": true,
    "reduction": {"method": "clamped", "interface": "root", "modes": 6}})");
  formats::DiffOptions o;
  o.rtol = 1e-9;
  const auto d = formats::diff(a, b, o);
  std::string worst;
  for (const auto& w : d.worst) worst += "\n  " + w.dataset + w.index + ": " + std::to_string(w.rel);
  EXPECT_EQ(d.datasets_different, 0) << worst;
  EXPECT_GT(d.datasets_compared, 30);  // the SID with its stiffening datasets
  // The one difference: the group the interface was made from has the deck's name.
  EXPECT_EQ(d.structural, (std::vector<std::string>{"/interfaces 'root': 'root, rigid, clamp' vs 'root, rigid, set1'"}));
}

// A cantilever of 40 CBARs along x, v = +y (small field, PBAR over three lines), clamped at
// x = 0: the first bending mode in y (the plane of x and v) follows I1, the first in z I2.
TEST(BdfDeck, BarSectionsBendAsTheQuickReferenceGuideSays) {
  test::TempDir dir("interop_bar");
  const double L = 1.0, A = 1e-4, I1 = 8e-10, I2 = 2e-10, E = 2.1e11, rho = 7850;
  const int n = 40;
  std::ostringstream s;
  char buf[128];
  for (int i = 0; i <= n; ++i) {
    std::snprintf(buf, sizeof buf, "GRID    %-8d        %-8.5f0.      0.\n", i + 1, L * i / n);
    s << buf;
  }
  for (int i = 0; i < n; ++i) {
    std::snprintf(buf, sizeof buf, "CBAR    %-8d2       %-8d%-8d0.      1.      0.\n", 100 + i, i + 1, i + 2);
    s << buf;
  }
  s << "PBAR    2       5       1.-4    8.-10   2.-10   5.-10\n+\n+\n";
  s << "MAT1    5       2.1+11          .3      7850.\nSET1    9       1\n";
  test::write_text(dir / "beam.bdf", s.str());
  test::write_text(dir / "beam.json", R"({"geometry": "beam.bdf", "visual": false,
    "interfaces": [{"name": "root", "group": "set9"}],
    "reduction": {"method": "clamped", "interface": "root", "modes": 2}})");
  const formats::Sid sid = preproc::run_pipeline(preproc::load_part(dir / "beam.json"));
  const double beta = 1.8751040687119611;  // first root of cos(x) cosh(x) = -1
  const auto f = [&](double I) { return beta * beta / (2 * M_PI) * std::sqrt(E * I / (rho * A * std::pow(L, 4))); };
  ASSERT_EQ(sid.refmod.frequency_hz.size(), 2);
  // Mode 1 (the lower, I2) moves in z, mode 2 (I1) in y: their momentum Ct.M0 says which.
  EXPECT_NEAR(sid.refmod.frequency_hz(0) / f(I2), 1.0, 1e-4);
  EXPECT_NEAR(sid.refmod.frequency_hz(1) / f(I1), 1.0, 1e-4);
  EXPECT_GT(std::abs(sid.Ct.M0(0, 2)), 1e3 * std::abs(sid.Ct.M0(0, 1)));
  EXPECT_GT(std::abs(sid.Ct.M0(1, 1)), 1e3 * std::abs(sid.Ct.M0(1, 2)));
  std::printf("CBAR cantilever: f1 / f(I2) - 1 = %.2e, f2 / f(I1) - 1 = %.2e\n", sid.refmod.frequency_hz(0) / f(I2) - 1,
              sid.refmod.frequency_hz(1) / f(I1) - 1);
}

// The same cantilever with a CONM2 on its tip grid, mass mu times the beam's: the first bending
// frequency from the exact Euler-Bernoulli frequency equation of a cantilever with a tip mass,
//   1 + cos(l) cosh(l) + mu l (cos(l) sinh(l) - sin(l) cosh(l)) = 0,  omega = l^2 sqrt(EI / (rho A L^4))
// (the classical result for a cantilever with a tip mass, e.g. Blevins, "Formulas for Natural
// Frequency and Mode Shape", chapter on beams with masses; solved by bisection here).
TEST(BdfDeck, Conm2TipMassOnACantileverGivesTheExactFrequency) {
  test::TempDir dir("interop_conm2");
  const double L = 1.0, A = 1e-4, I2 = 2e-10, E = 2.1e11, rho = 7850, mu = 1.5;
  const double tip = mu * rho * A * L;
  const int n = 40;
  std::ostringstream s;
  char buf[160];
  for (int i = 0; i <= n; ++i) {
    std::snprintf(buf, sizeof buf, "GRID    %-8d        %-8.5f0.      0.\n", i + 1, L * i / n);
    s << buf;
  }
  for (int i = 0; i < n; ++i) {
    std::snprintf(buf, sizeof buf, "CBAR    %-8d2       %-8d%-8d0.      1.      0.\n", 100 + i, i + 1, i + 2);
    s << buf;
  }
  s << "PBAR    2       5       1.-4    8.-10   2.-10   5.-10\n+\n+\n";
  s << "MAT1    5       2.1+11          .3      7850.\nSET1    9       1\n";
  const std::string beam = s.str();
  // Free field, the tip mass with a small inertia of its own (no offset: it moves with the grid).
  std::snprintf(buf, sizeof buf, "CONM2,900,%d,,%.17g\n,1.e-9,,1.e-9,,,1.e-9\n", n + 1, tip);
  test::write_text(dir / "beam.bdf", beam + buf);
  test::write_text(dir / "beam.json", R"({"geometry": "beam.bdf", "visual": false,
    "interfaces": [{"name": "root", "group": "set9"}],
    "reduction": {"method": "clamped", "interface": "root", "modes": 1}})");
  const formats::Sid sid = preproc::run_pipeline(preproc::load_part(dir / "beam.json"));
  const auto g = [&](double l) { return 1 + std::cos(l) * std::cosh(l) + mu * l * (std::cos(l) * std::sinh(l) - std::sin(l) * std::cosh(l)); };
  double a = 0.1, b = 1.8751040687119611;  // below the bare cantilever's first root
  ASSERT_LT(g(a) * g(b), 0.0);
  for (int k = 0; k < 200; ++k) {
    const double m = 0.5 * (a + b);
    (g(a) * g(m) <= 0 ? b : a) = m;
  }
  const double lambda = 0.5 * (a + b);
  const double exact = lambda * lambda / (2 * M_PI) * std::sqrt(E * I2 / (rho * A * std::pow(L, 4)));
  const double bare = 1.8751040687119611 * 1.8751040687119611 / (2 * M_PI) * std::sqrt(E * I2 / (rho * A * std::pow(L, 4)));
  EXPECT_NEAR(sid.refmod.frequency_hz(0) / exact, 1.0, 1e-4);
  EXPECT_LT(exact, 0.6 * bare);  // the mass matters: without it the check would fail
  EXPECT_NEAR(sid.refmod.mass, rho * A * L + tip, 1e-9 * sid.refmod.mass);
  std::printf("CONM2 tip mass (mu = %.1f): f1 = %.6f Hz, exact %.6f Hz, ratio - 1 = %.2e\n", mu, sid.refmod.frequency_hz(0),
              exact, sid.refmod.frequency_hz(0) / exact - 1);
}

namespace {

// The 40-element cantilever of the CBAR tests along x (v = +y, clamped at grid 1 through SET1
// 9), its elements given by `card` ("CBAR" or "CBEAM") on property 2, `property` the property's
// lines and MAT1 5 steel.
std::string cantilever(const std::string& card, const std::string& property) {
  const int n = 40;
  std::ostringstream s;
  char buf[128];
  for (int i = 0; i <= n; ++i) {
    std::snprintf(buf, sizeof buf, "GRID    %-8d        %-8.5f0.      0.\n", i + 1, static_cast<double>(i) / n);
    s << buf;
  }
  for (int i = 0; i < n; ++i) {
    std::snprintf(buf, sizeof buf, "%-8s%-8d2       %-8d%-8d0.      1.      0.\n", card.c_str(), 100 + i, i + 1, i + 2);
    s << buf;
  }
  return s.str() + property + "MAT1    5       2.1+11          .3      7850.\nSET1    9       1\n";
}

formats::Sid reduce_cantilever(const test::TempDir& dir, const std::string& name, const std::string& deck, int modes) {
  test::write_text(dir / (name + ".bdf"), deck);
  test::write_text(dir / (name + ".json"), R"({"geometry": ")" + name + R"(.bdf", "visual": false,
    "interfaces": [{"name": "root", "group": "set9"}],
    "reduction": {"method": "clamped", "interface": "root", "modes": )" + std::to_string(modes) + "}}");
  return preproc::run_pipeline(preproc::load_part(dir / (name + ".json")));
}

void expect_same_sid(const formats::Sid& a, const formats::Sid& b, const std::string& what) {
  formats::DiffOptions o;
  o.rtol = 1e-9;
  const auto d = formats::diff(a, b, o);
  std::string worst;
  for (const auto& w : d.worst) worst += "\n  " + w.dataset + w.index + ": " + std::to_string(w.a) + " vs " + std::to_string(w.b);
  for (const auto& st : d.structural) worst += "\n  " + st;
  EXPECT_TRUE(d.equivalent) << what << ": " << d.datasets_different << " datasets differ:" << worst;
  EXPECT_GT(d.datasets_compared, 10) << what;
}

// A root of 1 + cos(x) cosh(x) (the clamped-free Euler-Bernoulli beam's frequency equation) in
// [a, b], by bisection.
double cantilever_root(double a, double b) {
  const auto g = [](double x) { return 1 + std::cos(x) * std::cosh(x); };
  if (g(a) * g(b) > 0) throw std::runtime_error("no sign change");
  for (int k = 0; k < 200; ++k) {
    const double m = 0.5 * (a + b);
    (g(a) * g(m) <= 0 ? b : a) = m;
  }
  return 0.5 * (a + b);
}

// PBEAM 2: end A's line with `section` (A, I1, I2, I12, J in small field), the line of its
// stress points, then `tail` (stations, K1 ... N2(B)).
std::string pbeam(const std::string& section, const std::string& tail) { return "PBEAM   2       5       " + section + "\n+\n" + tail; }
const char* kSection = "1.-4    8.-10   2.-10           5.-10";

}  // namespace

// A cantilever of 40 CBEAMs, PBEAM with K1 = K2 = 0 (rigid in shear: Euler-Bernoulli; Quick
// Reference Guide, PBEAM), against the Euler-Bernoulli clamped-free frequencies
// f_n = (beta_n L)^2 / (2 pi L^2) sqrt(E I / (rho A)), beta_n L the roots of
// 1 + cos(beta L) cosh(beta L) = 0: 1.8751 and 4.6941 (Blevins, "Formulas for Natural Frequency
// and Mode Shape", table of single-span beams, clamped-free; found by bisection here), the
// first two in each plane: I2 moves the beam in z, I1 in y (the plane of x and v). ffr's beam
// carries the section's rotary inertia, which Euler-Bernoulli theory leaves out: it lowers f_n
// by the order of (beta_n r)^2 / 2, r^2 = I / A: about 1e-5 on this slender section (L / r =
// 1118); 40 cubic elements add less than 1e-6: hence 3e-5. And the same cantilever of CBARs with PBAR
// (K1, K2 blank: rigid in shear) gives the same SID.
TEST(BdfDeck, CbeamCantileverIsEulerBernoulliAndTheCbarSid) {
  test::TempDir dir("interop_cbeam");
  const double A = 1e-4, I1 = 8e-11, I2 = 2e-11, E = 2.1e11, rho = 7850;
  const double b1 = cantilever_root(1.5, 2.5), b2 = cantilever_root(4.5, 5.0);
  ASSERT_NEAR(b1, 1.8751, 1e-4);
  ASSERT_NEAR(b2, 4.6941, 1e-4);
  const auto f = [&](double beta, double I) { return beta * beta / (2 * M_PI) * std::sqrt(E * I / (rho * A)); };
  const formats::Sid beam =
      reduce_cantilever(dir, "beam", cantilever("CBEAM", pbeam("1.-4    8.-11   2.-11           5.-11", "+       0.      0.\n")), 4);
  // In order: z (I2) 1st, y (I1) 1st, z 2nd, y 2nd (1.29, 2.59, 8.11, 16.2 Hz).
  const double expected[4] = {f(b1, I2), f(b1, I1), f(b2, I2), f(b2, I1)};
  const int axis[4] = {2, 1, 2, 1};
  ASSERT_EQ(beam.refmod.frequency_hz.size(), 4);
  for (Eigen::Index k = 0; k < 4; ++k) {
    EXPECT_NEAR(beam.refmod.frequency_hz(k) / expected[k], 1.0, 3e-5) << "mode " << k + 1;
    // The mode's momentum (Ct.M0) lies along its axis.
    EXPECT_GT(std::abs(beam.Ct.M0(k, axis[k])), 1e3 * std::abs(beam.Ct.M0(k, 3 - axis[k]))) << "mode " << k + 1;
    std::printf("CBEAM cantilever mode %d: %.6f Hz, Euler-Bernoulli %.6f Hz, ratio - 1 = %.2e\n", static_cast<int>(k + 1),
                beam.refmod.frequency_hz(k), expected[k], beam.refmod.frequency_hz(k) / expected[k] - 1);
  }
  const formats::Sid bar =
      reduce_cantilever(dir, "bar", cantilever("CBAR", "PBAR    2       5       1.-4    8.-11   2.-11   5.-11\n"), 4);
  expect_same_sid(beam, bar, "CBEAM/PBEAM vs CBAR/PBAR");
}

// PBEAM's defaults and stations: K1, K2 blank are 1.0 (PBAR with K1 = K2 = 1.0 gives the same
// SID); stations that repeat end A's section, or leave it blank, are the constant section
// (YESA and NO stations without their line of stress points, a YES station with it).
TEST(BdfDeck, PbeamDefaultsAndConstantStations) {
  test::TempDir dir("interop_pbeam");
  const formats::Sid bar = reduce_cantilever(
      dir, "bar", cantilever("CBAR", "PBAR    2       5       1.-4    8.-10   2.-10   5.-10\n+\n+       1.      1.\n"), 4);
  const formats::Sid plain = reduce_cantilever(dir, "plain", cantilever("CBEAM", pbeam(kSection, "")), 4);
  expect_same_sid(plain, bar, "PBEAM with K1, K2 blank vs PBAR with K1 = K2 = 1.0");
  const std::string stations = "+       YESA    .25\n"
                               "+       YES     .5      1.-4            2.-10   0.\n+       .01     .01\n"
                               "+       NO      1.      1.0E-4  8.0E-10 2.0E-10         5.0E-10 0.\n"
                               "+       1.      1.      0.      0.      0.      0.      0.      0.\n";
  const formats::Sid tapered_not = reduce_cantilever(dir, "stations", cantilever("CBEAM", pbeam(kSection, stations)), 4);
  expect_same_sid(tapered_not, bar, "PBEAM with constant stations vs PBAR");
}
namespace {

const char* kTet = "GRID,1,,0.,0.,0.\nGRID,2,,1.,0.,0.\nGRID,3,,0.,1.,0.\nGRID,4,,0.,0.,1.\n";
const char* kProps = "PSOLID,1,2\nMAT1,2,2.1+11,,0.3,7850.\n";

std::string refusal(const test::TempDir& dir, const std::string& deck, const std::string& group = "pid1") {
  return test::deck_refusal(dir, "bad.bdf", deck, group);
}

// One CBEAM (line 3) between two grids, its property (line 4) and MAT1 5, grid 1 in SET1 9.
const char* kPbeam = "PBEAM,2,5,1.-4,8.-10,2.-10,,5.-10\n";
std::string beam(const std::string& element, const std::string& property) {
  return "GRID,1,,0.,0.,0.\nGRID,2,,1.,0.,0.\n" + element + property + "MAT1,5,2.1+11,,0.3,7850.\nSET1,9,1\n";
}

}  // namespace

TEST(BdfRefusals, EveryBadDeckNamesFileLineCardAndWhatWasExpected) {
  test::TempDir dir("bdf_bad");
  const std::string tet = std::string(kTet) + "CTETRA,1,1,1,2,3,4\n";
  struct Case {
    std::string deck, group, expected;
  };
  const std::vector<Case> cases = {
      {tet + kProps + "CONM1,5,1\n", "pid1", "bad.bdf: line 8 (CONM1 5): CONM1 (a 6 x 6 mass matrix) is not supported"},
      {tet + kProps + "CONM2,5,9,,2.0\n", "pid1", "bad.bdf: line 8 (CONM2 5): field 3 (G): grid 9 is not defined"},
      {tet + kProps + "CONM2,5,1,3,2.0\n", "pid1", "bad.bdf: line 8 (CONM2 5): field 4 (CID): coordinate systems are not supported"},
      {tet + kProps + "CONM2,5,1,,-2.0\n", "pid1", "bad.bdf: line 8 (CONM2 5): field 5 (M): a positive mass is expected"},
      {tet + kProps + "CONM2,5,1,,2.0\n,1.,,1.,,,5.\n", "pid1", "bad.bdf: line 8 (CONM2 5): continuation 1 (I11 ... I33): the principal moments violate"},
      {tet + kProps + "CPENTA,2,1,1,2,3,4,1,2\n", "pid1", "bad.bdf: line 8 (CPENTA 2): card CPENTA is not supported"},
      {std::string(kTet) + "CTETRA,1,1,1,2,3,4,1,2\n" + kProps, "pid1",
       "bad.bdf: line 5 (CTETRA 1): CTETRA with 6 grids: ffr takes 4 or all 10"},
      {tet, "pid1", "bad.bdf: line 5 (CTETRA 1): field 3 (PID): no property 1 (PSOLID) in the deck"},
      {tet + "PSHELL,1,2,0.01,2\nMAT1,2,2.1+11,,0.3,7850.\n", "pid1",
       "bad.bdf: line 5 (CTETRA 1): field 3 (PID): property 1 is a PSHELL, expected a PSOLID"},
      {tet + "PSOLID,1,2\n", "pid1", "bad.bdf: line 6 (PSOLID 1): field 3 (MID): no MAT1 2 in the deck"},
      {tet + "PSOLID,1,2\nMAT1,2,2.1+11,,0.3\n", "pid1", "bad.bdf: line 7 (MAT1 2): field 6 (RHO): no density"},
      {tet + "PSOLID,1,2\nMAT1,2,2.1+11\n", "pid1", "bad.bdf: line 7 (MAT1 2): give two of E, G and NU"},
      {tet + "PSOLID,1,2\nMAT1,2,2.1x11,,0.3,7850.\n", "pid1", "bad.bdf: line 7 (MAT1 2): field 3 (E): expected a number, found '2.1X11'"},
      {std::string(kTet) + "CTETRA,1,1,1,2,3,9\n" + kProps, "pid1", "bad.bdf: line 5: element 1: node 9 is not defined"},
      {"GRID,1,5,0.,0.,0.\n" + tet + kProps, "pid1", "bad.bdf: line 1 (GRID 1): field 3 (CP): coordinate systems are not supported"},
      {"+,1,2\n" + tet + kProps, "pid1", "bad.bdf: line 1: a continuation line without a card before it"},
      {tet + kProps + "SET1,3,1,2,3,4,5,6,7,8,9,10\n", "pid1", "bad.bdf: line 8: a free-field line holds at most 8 data fields"},
      {tet + kProps + "SET1,3,1,2,3,4,5,6,7,8\n", "pid1", "bad.bdf: line 8: field 10 of a free-field line is its continuation marker (blank, '+...' or '*...'), found '8'"},
      {tet + kProps + "PARAM,WTMASS,0.00259\n", "pid1", "bad.bdf: line 8 (PARAM WTMASS): PARAM WTMASS is not taken"},
      {tet + "PSOLID,1,2,,,,FULL\n" + "MAT1,2,2.1+11,,0.3,7850.\n", "pid1",
       "bad.bdf: line 6 (PSOLID 1): fields 5, 7 (IN, ISOP) = '', 'FULL': ffr takes both blank"},
      {tet + "PSOLID,1,2,,3,,FULL\n" + "MAT1,2,2.1+11,,0.3,7850.\n", "pid1",
       "bad.bdf: line 6 (PSOLID 1): fields 5, 7 (IN, ISOP) = '3', 'FULL': ffr takes both blank"},
      {tet + "PSOLID,1,2,,2,,FULL\n" + "MAT1,2,2.1+11,,0.3,7850.\n", "pid1",
       "bad.bdf: line 5 (CTETRA 1): field 3 (PID): PSOLID 1 (line 6) has IN = 2, ISOP = FULL, which chooses the 8-grid "
       "CHEXA's integration; ffr integrates CTETRA with 4 grids by its own rule"},
      {tet + kProps + "SET1,3,1,2,3,4,5,6,7\n+,8\n", "set3", "bad.bdf: line 8 (SET1 3): node 5 is not defined"},
      {tet + kProps, "set4", "bad.json: interfaces[0].group: no group 'set4' in the mesh"},
      // A THRU over more grids than the deck defines names grids that are not defined: refused
      // before the list is written out (up to 1e8 ids each before, without a bound on their sum).
      {tet + kProps + "SET1,3,1,THRU,100000000\n", "set3",
       "bad.bdf: line 8 (SET1 3): field 5: 1 THRU 100000000 names 100000000 grids, more than the deck's 4 GRID cards"},
      {tet + kProps + "SET1,3,2,THRU,6\n", "set3", "bad.bdf: line 8 (SET1 3): field 5: 2 THRU 6 names 5 grids, more than the deck's 4 GRID cards"},
      {tet + kProps + "SET1,3,1,THRU,4,5\n", "set3", "bad.bdf: line 8 (SET1 3): node 5 is not defined"},
      {"BEGIN BULK\n" + tet + kProps + "ENDDATA\nGARBAGE\n", "nowhere", "no group 'nowhere'"},
      // CBEAM and PBEAM: what ffr's beam does not have, named by card, line and field.
      {beam("CBEAM,1,2,1,2,0.,1.,0.\n,1\n", kPbeam), "set9",
       "bad.bdf: line 3 (CBEAM 1): continuation 1, field 2 ('1') is not supported: pin flags (PA, PB)"},
      {beam("CBEAM,1,2,1,2,0.,1.,0.\n,,,0.1\n", kPbeam), "set9",
       "bad.bdf: line 3 (CBEAM 1): continuation 1, field 4 (an offset) is not supported unless 0"},
      {beam("CBEAM,1,2,1,2,0.,1.,0.\n,\n,7\n", kPbeam), "set9",
       "bad.bdf: line 3 (CBEAM 1): continuation 2, field 2 ('7') is not supported: warping scalar points (SA, SB)"},
      {beam("CBEAM,1,2,1,2,0.,1.,0.,GOO\n", kPbeam), "set9",
       "bad.bdf: line 3 (CBEAM 1): field 9 (OFFT/BIT): only OFFT = GGG (or blank) is supported"},
      {beam("CBEAM,1,2,1,2,0.,0.,0.\n", kPbeam), "set9",
       "bad.bdf: line 3 (CBEAM 1): fields 6-8 (X1, X2, X3): the orientation vector is zero"},
      {beam("CBEAM,1,2,1,2,0.,1.,0.\n", "PBAR,2,5,1.-4,8.-10,2.-10,5.-10\n"), "set9",
       "bad.bdf: line 3 (CBEAM 1): field 3 (PID): property 2 is a PBAR, expected a PBEAM"},
      {beam("CBAR,1,2,1,2,0.,1.,0.\n", kPbeam), "set9",
       "bad.bdf: line 3 (CBAR 1): field 3 (PID): property 2 is a PBEAM, expected a PBAR"},
      {beam("CBEAM,1,2,1,2,0.,1.,0.\n", "PBEAM,2,5,1.-4,8.-10,2.-10,,5.-10\n,\n,NO,1.,2.-4\n"), "set9",
       "bad.bdf: line 4 (PBEAM 2): continuation 2, field 4 (A at X/XB = 1.): '2.-4' differs from end A's: tapered beams are not supported"},
      {beam("CBEAM,1,2,1,2,0.,1.,0.\n", "PBEAM,2,5,1.-4,8.-10,2.-10,,5.-10\n,\n,YESA,0.5,,,3.-10\n"), "set9",
       "continuation 2, field 6 (I2 at X/XB = 0.5): '3.-10' differs from end A's: tapered beams are not supported"},
      {beam("CBEAM,1,2,1,2,0.,1.,0.\n", "PBEAM,2,5,1.-4,8.-10,2.-10,,5.-10\n,\n,NO,1.5\n"), "set9",
       "bad.bdf: line 4 (PBEAM 2): continuation 2, field 3 (X/XB): a station lies in (0, 1]"},
      {beam("CBEAM,1,2,1,2,0.,1.,0.\n", "PBEAM,2,5,1.-4,8.-10,2.-10,1.-10,5.-10\n"), "set9",
       "bad.bdf: line 4 (PBEAM 2): field 7 (I12: give the section in its principal axes) is not supported unless 0"},
      {beam("CBEAM,1,2,1,2,0.,1.,0.\n", "PBEAM,2,5,1.-4,8.-10,2.-10\n"), "set9",
       "bad.bdf: line 4 (PBEAM 2): fields 4-6, 8 (A, I1, I2, J): must be positive"},
      {beam("CBEAM,1,2,1,2,0.,1.,0.\n", "PBEAM,2,5,1.-4,8.-10,2.-10,,5.-10,0.1\n"), "set9",
       "bad.bdf: line 4 (PBEAM 2): field 9 (NSM, non-structural mass) is not supported unless 0"},
      {beam("CBEAM,1,2,1,2,0.,1.,0.\n", "PBEAM,2,5,1.-4,8.-10,2.-10,,5.-10\n,\n,,,,,,,1.-12\n"), "set9",
       "bad.bdf: line 4 (PBEAM 2): continuation 2, field 8 (CW(A), warping: ffr's beams do not warp) is not supported unless 0"},
      {beam("CBEAM,1,2,1,2,0.,1.,0.\n", "PBEAM,2,5,1.-4,8.-10,2.-10,,5.-10\n,\n,\n,,,,,0.01\n"), "set9",
       "bad.bdf: line 4 (PBEAM 2): continuation 3, field 6 (N1, N2: an offset of the neutral axis) is not supported unless 0"},
      {beam("CBEAM,1,2,1,2,0.,1.,0.\n", "PBEAM,2,5,1.-4,8.-10,2.-10,,5.-10\n,\n,-1.\n"), "set9",
       "bad.bdf: line 4 (PBEAM 2): continuation 2, field 2, continuation 2, field 3 (K1, K2): must be positive, 0 (rigid in shear) or blank"},
      {beam("CBEAM,1,2,1,2,0.,1.,0.\n", "PBEAM,2,5,1.-4,8.-10,2.-10,,5.-10\n,\n,MAYBE,1.\n"), "set9",
       "bad.bdf: line 4 (PBEAM 2): continuation 2, field 2 (K1): expected a number, found 'MAYBE'"},
      {beam("CBEAM,1,2,1,2,0.,1.,0.\n", "PBEAM,2,5,1.-4,8.-10,2.-10,,5.-10\n,\n,\n,\n,1.\n"), "set9",
       "bad.bdf: line 4 (PBEAM 2): continuation 4, field 2 ('1.') is not supported: PBEAM ends with the line of M1(A) ... N2(B)"},
      // A CHEXA of a PSOLID with IN = 2, ISOP = FULL that is degenerate: refused as any element.
      {"GRID,1,,0.,0.,0.\nGRID,2,,1.,0.,0.\nGRID,3,,1.,1.,0.\nGRID,4,,0.,1.,0.\nCHEXA,1,1,1,2,3,4,1,2\n,3,4\n"
       "PSOLID,1,2,,2,,FULL\nMAT1,2,2.1+11,,0.3,7850.\n",
       "pid1", "bad.bdf: element 1 (HEX8, group pid1): HEX8 element is degenerate"},
  };
  for (const Case& c : cases) {
    const std::string what = refusal(dir, c.deck, c.group);
    EXPECT_NE(what.find(c.expected), std::string::npos) << "deck:\n" << c.deck << "\nmessage: " << what << "\nexpected: " << c.expected;
  }
}

// Every SET1 and SPC1 list is bounded by the deck's grids, but their sum is bounded only by
// kMaxDeckSetMembers (5e7): 7 000 sets of all 8 000 grids each (5.6e7 ids, from 340 kB of
// cards) are refused at the first id past it, on the 6 251st card (6 250 * 8 000 = 5e7).
TEST(BdfRefusals, SetListsAreBoundedInAll) {
  test::TempDir dir("bdf_sets");
  std::string deck = "GRID,1,,0.,0.,0.\nGRID,2,,1.,0.,0.\nGRID,3,,0.,1.,0.\n";
  for (int g = 4; g <= 8000; ++g) deck += "GRID," + std::to_string(g) + ",,0.,0.," + std::to_string(g) + ".\n";
  deck += std::string("CTETRA,1,1,1,2,3,4\n") + kProps;
  for (int s = 1; s <= 7000; ++s) deck += "SET1," + std::to_string(s) + ",1,THRU,8000\n";
  // The first SET1 is line 8000 + 1 + 2 + 1.
  const std::string what = refusal(dir, deck, "set1");
  EXPECT_NE(what.find("bad.bdf: line 14254 (SET1 6251): field 3: the deck's SET1 and SPC1 cards would list more than 50000000 grids in all"),
            std::string::npos) << what;
}

// The command line: a tapered PBEAM and a CHEXA whose PSOLID asks for an integration ffr does
// not have, each exit status 2, the message naming file, line, card and field on stderr, no SID.
TEST(BdfRefusals, CommandLineExitsWithTwoAndWritesNothing) {
  test::TempDir dir("bdf_cli");
  const std::vector<std::pair<std::string, std::string>> decks = {
      {beam("CBEAM,1,2,1,2,0.,1.,0.\n", "PBEAM,2,5,1.-4,8.-10,2.-10,,5.-10\n,\n,NO,1.,2.-4\n"),
       "bad.bdf: line 4 (PBEAM 2): continuation 2, field 4 (A at X/XB = 1.)"},
      {std::string(kTet) + "CTETRA,1,1,1,2,3,4\nPSOLID,1,2,,3,,FULL\nMAT1,2,2.1+11,,0.3,7850.\n",
       "bad.bdf: line 6 (PSOLID 1): fields 5, 7 (IN, ISOP)"}};
  for (const auto& [deck, expected] : decks) {
    (void)refusal(dir, deck, deck.find("CBEAM") != std::string::npos ? "set9" : "pid1");
    const auto r = test::run(test::bin("ffr-reduce").string() + " " + (dir / "bad.json").string() + " -o " + (dir / "bad.sid.h5").string());
    EXPECT_EQ(r.status, 2) << r.output;
    EXPECT_NE(r.output.find(expected), std::string::npos) << r.output;
    EXPECT_FALSE(std::filesystem::exists(dir / "bad.sid.h5"));
  }
}

namespace {

// element tag -> (type, node tags in gmsh order) of every element of the blocks of `group`.
std::map<std::size_t, std::pair<std::string, std::vector<std::size_t>>> all_elements(const preproc::Mesh& m,
                                                                                      const std::string& group) {
  std::map<std::size_t, std::pair<std::string, std::vector<std::size_t>>> out;
  for (const auto& b : m.blocks)
    if (b.group == group)
      for (preproc::Index e = 0; e < b.size(); ++e) {
        auto& el = out[m.element_tag(b, e)];
        el.first = preproc::name(b.type);
        for (int i = 0; i < preproc::num_nodes(b.type); ++i) el.second.push_back(m.node_tag(b.element(e)[i]));
      }
  return out;
}

}  // namespace

// gmsh's CHEXA (20 grids) and CQUAD4 cards land in gmsh's own HEX20 and QUAD4 node order.
TEST(BdfDeck, GmshHex20AndQuadsLandInGmshOrder) {
  test::TempDir dir("interop_bdf_hex");
  test::write_text(dir / "hex.geo", R"(Point(1) = {0, 0, 0}; Point(2) = {0.2, 0, 0}; Line(1) = {1, 2};
e[] = Extrude{0, 0.02, 0}{Line{1}; Layers{3}; Recombine;};
v[] = Extrude{0, 0, 0.012}{Surface{e[1]}; Layers{2}; Recombine;};
Transfinite Curve{1} = 13;
Physical Volume("body") = {v[1]};
)");
  test::write_text(dir / "plate.geo", R"(SetFactory("OpenCASCADE");
Rectangle(1) = {0, 0, 0, 0.3, 0.1};
Recombine Surface{1};
Physical Surface("skin") = {1};
)");
  const std::vector<std::pair<std::string, std::string>> cases = {{"hex", "-3 -order 2 -setnumber Mesh.SecondOrderIncomplete 1"},
                                                                   {"plate", "-2 -clmax 0.02"}};
  for (const auto& [name, opts] : cases) {
    const auto geo = dir / (name + ".geo"), msh = dir / (name + ".msh"), bdf = dir / (name + ".bdf");
    const auto r = test::run("gmsh " + opts + " -format msh41 " + geo.string() + " -o " + msh.string() + " && gmsh " + msh.string() +
                             " -0 -setnumber Mesh.BdfFieldFormat 2 -format bdf -o " + bdf.string());
    ASSERT_EQ(r.status, 0) << r.output;
    preproc::PartSpec p;
    p.geometry = msh;
    const preproc::Mesh a = preproc::load_mesh(p);
    const preproc::Mesh b = preproc::detail::read_bdf(bdf.string(), nullptr);
    const auto ea = all_elements(a, name == "hex" ? "body" : "skin"), eb = all_elements(b, "pid1");
    ASSERT_FALSE(ea.empty());
    EXPECT_EQ(ea.begin()->second.first, name == "hex" ? "HEX20" : "QUAD4");
    EXPECT_EQ(ea, eb) << name;
  }
}
