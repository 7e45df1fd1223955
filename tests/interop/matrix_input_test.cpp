// Assembled K and M as a part's input ("matrices" of the part file), checked against:
//  - ffr's own assembly of the same deck: its K and M written as Matrix Market (rows in a
//    shuffled order, with the DOF map saying which is which) give the SID of the deck itself
//    (formats::diff, rtol 1e-9, mode signs free) for clamped, free and Craig-Bampton reductions;
//  - CalculiX (`ccx` 2.20 from Debian): its *FREQUENCY, SOLVER=MATRIXSTORAGE export of the deck
//    (job.sti, job.mas, job.dof; CalculiX 2.20 manual, *FREQUENCY) read as matrix input gives
//    the SID of ffr reading the deck; C3D20 integrates as ffr's HEX20 (27 points), where the
//    deck's own frequencies agree with ccx to 1.5e-7 (inp_reader_test.cpp);
//  - a lumped mass (HRZ lumping of ccx's consistent mass, built here): the frequencies of a
//    dense generalized eigen-solve of the same clamped K and M in this test (Eigen's
//    GeneralizedSelfAdjointEigenSolver), an oracle sharing no code with the reducer;
//  - the same own K and M written as Abaqus *MATRIX GENERATE output and as Nastran DMIG punch
//    files (formats as their manuals give them, cited below): the SID of the deck, rtol 1e-9;
//  - bad input: exit status 2 naming the file, the line and what was expected, no SID.
#include "ffr/formats/diff.hpp"
#include "ffr/formats/h5.hpp"
#include "ffr/formats/sid_io.hpp"
#include "ffr/formats/text_file.hpp"
#include "ffr/preproc/assembly/assembly.hpp"
#include "ffr/preproc/mesh/gmsh_import.hpp"
#include "ffr/preproc/pipeline.hpp"
#include "support.hpp"

#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <map>
#include <set>
#include <sstream>

using namespace ffr;

namespace {

// A 0.2 x 0.02 x 0.012 bar of 12 x 3 x 2 HEX20 (C3D20) cells as gmsh writes it as a deck, with
// node sets clamp (x = 0) and tip (x = 0.2), steel from the deck.
struct HexBar {
  test::TempDir dir{"interop_mtx"};
  std::string deck;
  HexBar() {
    test::write_text(dir / "bar.geo", R"(Point(1) = {0, 0, 0}; Point(2) = {0.2, 0, 0}; Line(1) = {1, 2};
e[] = Extrude{0, 0.02, 0}{Line{1}; Layers{3}; Recombine;};
v[] = Extrude{0, 0, 0.012}{Surface{e[1]}; Layers{2}; Recombine;};
Transfinite Curve{1} = 13;
Physical Volume("body") = {v[1]};
Physical Surface("clamp") = Surface In BoundingBox{-1e-6, -1, -1, 1e-6, 1, 1};
Physical Surface("tip") = Surface In BoundingBox{0.2 - 1e-6, -1, -1, 0.2 + 1e-6, 1, 1};
)");
    test::gmsh_mesh(dir / "bar.geo", dir / "bar.msh", 0.006, 2);
    const auto r = test::run("gmsh " + (dir / "bar.msh").string() + " -0 -setnumber Mesh.SaveGroupsOfNodes 1 -format inp -o " +
                             (dir / "gmsh.inp").string());
    if (r.status != 0) throw std::runtime_error("gmsh failed: " + r.output);
    // Only the C3D20 block and its element set "body" (gmsh's plane elements are no part).
    std::istringstream in(formats::read_text_file(dir / "gmsh.inp"));
    std::ostringstream out;
    std::string line;
    bool drop = false;
    while (std::getline(in, line)) {
      if (!line.empty() && line[0] == '*' && line.rfind("**", 0) != 0) {
        drop = (line.rfind("*ELEMENT", 0) == 0 && line.find("type=C3D") == std::string::npos) ||
               (line.rfind("*ELSET", 0) == 0 && line.find("ELSET=body") == std::string::npos);
      }
      if (!drop) out << line << "\n";
    }
    deck = out.str() +
           "*MATERIAL, NAME=STEEL\n*ELASTIC\n2.1e11, 0.3\n*DENSITY\n7850\n*SOLID SECTION, ELSET=body, MATERIAL=STEEL\n";
    test::write_text(dir / "bar.inp", deck);
  }

  static std::string reduction(const std::string& method) {
    if (method == "clamped") return R"({"method": "clamped", "interface": "root", "modes": 6})";
    if (method == "free") return R"({"method": "free", "modes": 6})";
    return R"({"method": "craig-bampton", "interfaces": ["root", "end"], "frame": "root", "modes": 4})";
  }
  std::filesystem::path part(const std::string& name, const std::string& method, const std::string& matrices = "",
                             const std::string& geometry = "bar.inp") {
    const auto p = dir / name;
    test::write_text(p, R"({"geometry": ")" + geometry + R"(", "visual": false,
      "interfaces": [{"name": "root", "group": "clamp"}, {"name": "end", "group": "tip", "coupling": "averaged"}],
      )" + (matrices.empty() ? std::string() : "\"matrices\": " + matrices + ",") +
                            R"( "reduction": )" + reduction(method) + "}");
    return p;
  }
  formats::Sid reduce(const std::filesystem::path& part) { return preproc::run_pipeline(preproc::load_part(part)); }
};

// ffr's own K and M of the deck over its mesh DOFs, and the deck's node tag and component of
// each DOF.
struct OwnMatrices {
  Eigen::MatrixXd unused;
  preproc::SparseMatrix K, M;
  std::vector<std::pair<std::size_t, int>> dof;  ///< (node tag, component 1..3)
};
OwnMatrices own_matrices(const std::filesystem::path& part_file) {
  const preproc::PartSpec part = preproc::load_part(part_file);
  const preproc::Mesh mesh = preproc::load_mesh(part);
  const preproc::FeModel model = preproc::build_model(mesh, part);
  const preproc::Assembled fe = preproc::assemble(model);
  OwnMatrices o;
  const Eigen::Index n = model.mesh_dofs();
  o.K = fe.K.topLeftCorner(n, n);
  o.M = fe.M.topLeftCorner(n, n);
  o.dof.resize(static_cast<std::size_t>(n));
  for (Eigen::Index d = 0; d < n; ++d) {
    Eigen::Index node = 0;
    int c = 0;
    bool itf = false;
    model.dof_owner(d, node, c, itf);
    o.dof[static_cast<std::size_t>(d)] = {mesh.node_tag(node), c + 1};
  }
  return o;
}

// Writes A (full storage) as Matrix Market's symmetric coordinate format, row r of the file
// being DOF perm[r]: the lower triangle, 17 digits.
void write_mtx(const std::filesystem::path& p, const preproc::SparseMatrix& A, const std::vector<Eigen::Index>& perm) {
  std::vector<Eigen::Index> row_of(perm.size());
  for (std::size_t r = 0; r < perm.size(); ++r) row_of[static_cast<std::size_t>(perm[r])] = static_cast<Eigen::Index>(r);
  std::ostringstream body;
  body.precision(17);
  long long nnz = 0;
  for (Eigen::Index c = 0; c < A.outerSize(); ++c)
    for (preproc::SparseMatrix::InnerIterator it(A, c); it; ++it) {
      const Eigen::Index i = row_of[static_cast<std::size_t>(it.row())], j = row_of[static_cast<std::size_t>(it.col())];
      if (i < j || it.value() == 0) continue;
      body << i + 1 << " " << j + 1 << " " << it.value() << "\n";
      ++nnz;
    }
  test::write_text(p, "%%MatrixMarket matrix coordinate real symmetric\n% written by matrix_input_test\n" +
                          std::to_string(A.rows()) + " " + std::to_string(A.cols()) + " " + std::to_string(nnz) + "\n" +
                          body.str());
}

void write_dofs(const std::filesystem::path& p, const OwnMatrices& o, const std::vector<Eigen::Index>& perm) {
  std::ostringstream s;
  s << "# node component\n";
  for (const auto d : perm) s << o.dof[static_cast<std::size_t>(d)].first << " " << o.dof[static_cast<std::size_t>(d)].second << "\n";
  test::write_text(p, s.str());
}

// A shuffle that moves every row: stride 7 through the DOFs (coprime to their count).
std::vector<Eigen::Index> shuffled(Eigen::Index n) {
  Eigen::Index stride = 7;
  while (std::__gcd(stride, n) != 1) ++stride;
  std::vector<Eigen::Index> p(static_cast<std::size_t>(n));
  for (Eigen::Index r = 0; r < n; ++r) p[static_cast<std::size_t>(r)] = (r * stride + 3) % n;
  return p;
}

double expect_same_sid(const formats::Sid& a, const formats::Sid& b, double rtol) {
  formats::DiffOptions o;
  o.rtol = rtol;
  const auto d = formats::diff(a, b, o);
  std::string worst;
  for (const auto& w : d.worst) worst += "\n  " + w.dataset + w.index + ": " + std::to_string(w.a) + " vs " + std::to_string(w.b);
  for (const auto& s : d.structural) worst += "\n  " + s;
  EXPECT_TRUE(d.equivalent) << d.datasets_different << " datasets differ:" << worst;
  double f = 0;
  for (Eigen::Index k = 0; k < a.refmod.frequency_hz.size(); ++k)
    f = std::max(f, std::abs(b.refmod.frequency_hz(k) / a.refmod.frequency_hz(k) - 1.0));
  return f;
}

const char* kMtx = R"({"format": "matrix_market", "K": "K.mtx", "M": "M.mtx", "dofs": "dofs.txt"})";

}  // namespace

class MatrixMarketInput : public ::testing::TestWithParam<std::string> {};

// ffr's own K and M of the deck, as Matrix Market in shuffled rows: the SID of the deck.
TEST_P(MatrixMarketInput, OwnAssemblyGivesTheSidOfTheDeck) {
  HexBar bar;
  const std::string method = GetParam();
  const OwnMatrices own = own_matrices(bar.part("deck.json", method));
  const auto perm = shuffled(own.K.rows());
  write_mtx(bar.dir / "K.mtx", own.K, perm);
  write_mtx(bar.dir / "M.mtx", own.M, perm);
  write_dofs(bar.dir / "dofs.txt", own, perm);
  const formats::Sid deck = bar.reduce(bar.dir / "deck.json");
  const formats::Sid mtx = bar.reduce(bar.part("mtx.json", method, kMtx));
  const double f = expect_same_sid(deck, mtx, 1e-9);
  // The matrices, not the deck's elements, made it (the provenance says so).
  EXPECT_EQ(mtx.provenance.mass_model.at("/sid/Me").rfind("consistent (nodes coupled) translational mass from M.mtx", 0), 0u)
      << mtx.provenance.mass_model.at("/sid/Me");
  EXPECT_EQ(mtx.provenance.extra.count("matrices"), 1u);
  EXPECT_EQ(deck.provenance.extra.count("matrices"), 0u);
  std::printf("%s: Matrix Market input vs the deck: largest relative frequency difference %.2e\n", method.c_str(), f);
}

INSTANTIATE_TEST_SUITE_P(Reductions, MatrixMarketInput, ::testing::Values("clamped", "free", "craig_bampton"),
                         [](const auto& info) { return info.param; });

// CalculiX's export of the deck: job.sti, job.mas and job.dof, read as matrix input.
struct CalculixExport {
  HexBar bar;
  CalculixExport() {
    test::write_text(bar.dir / "job.inp", bar.deck + "*STEP\n*FREQUENCY, SOLVER=MATRIXSTORAGE\n*END STEP\n");
    const auto r = test::run("cd " + bar.dir.path().string() + " && OMP_NUM_THREADS=1 ccx -i job");
    if (!std::filesystem::exists(bar.dir / "job.sti")) throw std::runtime_error("ccx wrote no job.sti: " + r.output.substr(0, 2000));
  }
};

TEST(CalculixInput, MatrixStorageGivesTheSidOfTheDeck) {
  CalculixExport ccx;
  const formats::Sid deck = ccx.bar.reduce(ccx.bar.part("deck.json", "clamped"));
  const formats::Sid mat = ccx.bar.reduce(
      ccx.bar.part("ccx.json", "clamped", R"({"format": "calculix", "K": "job.sti", "M": "job.mas"})"));
  // ccx writes 14 significant digits, and integrates C3D20 as ffr's HEX20.
  const double f = expect_same_sid(deck, mat, 1e-9);
  EXPECT_LE(f, 1.5e-7);
  // And by the command-line tool outside scripts use.
  formats::write_sid(deck, ccx.bar.dir / "deck.sid.h5");
  formats::write_sid(mat, ccx.bar.dir / "ccx.sid.h5");
  const auto r = test::run(test::bin("ffr-diff").string() + " " + (ccx.bar.dir / "deck.sid.h5").string() + " " +
                           (ccx.bar.dir / "ccx.sid.h5").string() + " --rtol 1e-9");
  EXPECT_EQ(r.status, 0) << r.output;
  std::printf("CalculiX .sti/.mas vs the deck: largest relative frequency difference %.2e\n", f);
}

namespace {
struct FileEntries {
  std::vector<std::tuple<int, int, double>> e;
  explicit FileEntries(const std::filesystem::path& p) {
    std::istringstream in(formats::read_text_file(p));
    int i, j;
    double v;
    while (in >> i >> j >> v) e.emplace_back(i, j, v);
  }
};
}  // namespace

// HRZ lumping of ccx's consistent mass (diagonal scaled to keep each component's total mass;
// Hinton, Rock and Zienkiewicz, "A note on mass lumping and related processes in the finite
// element method", 1976): the clamped frequencies of a dense generalized eigen-solve here.
TEST(CalculixInput, LumpedMassReproducesTheDenseEigenSolve) {
  CalculixExport ccx;
  const auto& dir = ccx.bar.dir;
  std::vector<std::pair<std::size_t, int>> dof;
  {
    std::istringstream in(formats::read_text_file(dir / "job.dof"));
    std::string line;
    while (std::getline(in, line)) {
      const auto dot = line.find('.');
      dof.emplace_back(std::stoul(line.substr(0, dot)), std::stoi(line.substr(dot + 1)));
    }
  }
  const Eigen::Index n = static_cast<Eigen::Index>(dof.size());
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n, n), M = Eigen::MatrixXd::Zero(n, n);
  for (const auto& [i, j, v] : FileEntries(dir / "job.sti").e) K(i - 1, j - 1) = K(j - 1, i - 1) = v;
  for (const auto& [i, j, v] : FileEntries(dir / "job.mas").e) M(i - 1, j - 1) = M(j - 1, i - 1) = v;
  // HRZ: each component's diagonal scaled to that component's total mass.
  Eigen::VectorXd lumped(n);
  for (int c = 1; c <= 3; ++c) {
    double total = 0, diag = 0;
    for (Eigen::Index i = 0; i < n; ++i)
      if (dof[static_cast<std::size_t>(i)].second == c) {
        diag += M(i, i);
        for (Eigen::Index j = 0; j < n; ++j)
          if (dof[static_cast<std::size_t>(j)].second == c) total += M(i, j);
      }
    for (Eigen::Index i = 0; i < n; ++i)
      if (dof[static_cast<std::size_t>(i)].second == c) lumped(i) = M(i, i) * total / diag;
  }
  {
    std::ostringstream s;
    s.precision(17);
    for (Eigen::Index i = 0; i < n; ++i) s << i + 1 << " " << i + 1 << " " << lumped(i) << "\n";
    test::write_text(dir / "lumped.mas", s.str());
  }
  // The clamp's nodes (x = 0) held.
  const auto part = ccx.bar.part("lumped.json", "clamped",
                                 R"({"format": "calculix", "K": "job.sti", "M": "lumped.mas", "dofs": "job.dof"})");
  const preproc::Mesh mesh = preproc::load_mesh(preproc::load_part(part));
  std::set<std::size_t> clamp;
  for (Eigen::Index i = 0; i < mesh.num_nodes(); ++i)
    if (std::abs(mesh.x(i, 0)) < 1e-9) clamp.insert(mesh.node_tag(i));
  std::vector<Eigen::Index> free;
  for (Eigen::Index i = 0; i < n; ++i)
    if (!clamp.count(dof[static_cast<std::size_t>(i)].first)) free.push_back(i);
  ASSERT_EQ(static_cast<Eigen::Index>(free.size()), n - 3 * static_cast<Eigen::Index>(clamp.size()));
  const Eigen::Index nf = static_cast<Eigen::Index>(free.size());
  Eigen::MatrixXd Kf(nf, nf);
  Eigen::MatrixXd Mf = Eigen::MatrixXd::Zero(nf, nf);
  for (Eigen::Index a = 0; a < nf; ++a) {
    Mf(a, a) = lumped(free[static_cast<std::size_t>(a)]);
    for (Eigen::Index b = 0; b < nf; ++b) Kf(a, b) = K(free[static_cast<std::size_t>(a)], free[static_cast<std::size_t>(b)]);
  }
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(Kf, Mf, Eigen::EigenvaluesOnly);
  ASSERT_EQ(es.info(), Eigen::Success);

  const formats::Sid sid = ccx.bar.reduce(part);
  EXPECT_EQ(sid.provenance.mass_model.at("/sid/Me").rfind("lumped", 0), 0u) << sid.provenance.mass_model.at("/sid/Me");
  // Lumping moves the frequencies: the consistent-mass deck's must differ (so the check can fail).
  const formats::Sid consistent = ccx.bar.reduce(ccx.bar.part("deck.json", "clamped"));
  double worst = 0;
  for (Eigen::Index k = 0; k < 6; ++k) {
    const double dense = std::sqrt(es.eigenvalues()(k)) / (2 * M_PI);
    const double rel = sid.refmod.frequency_hz(k) / dense - 1.0;
    worst = std::max(worst, std::abs(rel));
    EXPECT_LE(std::abs(rel), 1e-9) << "mode " << k + 1 << ": " << sid.refmod.frequency_hz(k) << " Hz (ffr) vs " << dense
                                   << " Hz (dense eigen-solve)";
    EXPECT_GT(std::abs(consistent.refmod.frequency_hz(k) / dense - 1.0), 1e-5) << "mode " << k + 1;
  }
  EXPECT_NEAR(sid.refmod.mass, lumped.sum() / 3, 1e-12 * sid.refmod.mass);
  std::printf("lumped mass: largest relative frequency difference to the dense eigen-solve %.2e\n", worst);
}

// ---- Bad input: exit status 2, a message naming the file, the line and what was expected, no SID.
namespace {
struct BadCase {
  const char* name;
  const char* file;      ///< the file the message names
  const char* expected;  ///< a piece of the message
};
class MatrixInputRefusal : public ::testing::TestWithParam<BadCase> {};

std::string replace_line(const std::string& text, int line, const std::string& with) {
  std::istringstream in(text);
  std::ostringstream out;
  std::string l;
  for (int k = 1; std::getline(in, l); ++k) out << (k == line ? with : l) << "\n";
  return out.str();
}
// A Matrix Market text with one more entry (the size line's count raised).
std::string append_entry(const std::string& mtx, const std::string& entry) {
  std::istringstream in(mtx);
  std::string l;
  for (int k = 0; k < 3; ++k) std::getline(in, l);
  std::istringstream ls(l);
  long rows = 0, cols = 0, nnz = 0;
  ls >> rows >> cols >> nnz;
  return replace_line(mtx, 3, std::to_string(rows) + " " + std::to_string(cols) + " " + std::to_string(nnz + 1)) + entry + "\n";
}
}  // namespace

TEST_P(MatrixInputRefusal, ExitTwoNamingFileAndLine) {
  const BadCase c = GetParam();
  HexBar bar;
  const OwnMatrices own = own_matrices(bar.part("deck.json", "clamped"));
  std::vector<Eigen::Index> perm(static_cast<std::size_t>(own.K.rows()));
  for (std::size_t i = 0; i < perm.size(); ++i) perm[i] = static_cast<Eigen::Index>(i);
  write_mtx(bar.dir / "K.mtx", own.K, perm);
  write_mtx(bar.dir / "M.mtx", own.M, perm);
  write_dofs(bar.dir / "dofs.txt", own, perm);
  std::string matrices = kMtx;
  const std::string name = c.name;
  const std::string K = formats::read_text_file(bar.dir / "K.mtx"), M = formats::read_text_file(bar.dir / "M.mtx");
  if (name == "size") {
    // K's size line one row and column larger than the DOF map.
    std::istringstream in(K);
    std::string l;
    for (int k = 0; k < 3; ++k) std::getline(in, l);
    std::istringstream ls(l);
    long rows = 0, cols = 0, nnz = 0;
    ls >> rows >> cols >> nnz;
    test::write_text(bar.dir / "K.mtx", replace_line(K, 3, std::to_string(rows + 1) + " " + std::to_string(cols + 1) + " " +
                                                               std::to_string(nnz)));
  } else if (name == "asymmetric") {
    // M in general storage with one transpose off by 1 %.
    std::istringstream in(M);
    std::string l, out;
    std::getline(in, l);
    out = "%%MatrixMarket matrix coordinate real general\n";
    std::vector<std::tuple<long, long, double>> e;
    long rows = 0, cols = 0, nnz = 0;
    while (std::getline(in, l)) {
      if (l[0] == '%') continue;
      std::istringstream ls(l);
      if (rows == 0) {
        ls >> rows >> cols >> nnz;
        continue;
      }
      long i, j;
      double v;
      ls >> i >> j >> v;
      e.emplace_back(i, j, v);
    }
    std::ostringstream body;
    body.precision(17);
    long count = 0;
    bool bent = false;
    for (const auto& [i, j, v] : e) {
      body << i << " " << j << " " << v << "\n";
      ++count;
      if (i != j) {
        body << j << " " << i << " " << (bent ? v : 1.01 * v) << "\n";
        bent = true;
        ++count;
      }
    }
    test::write_text(bar.dir / "M.mtx", out + std::to_string(rows) + " " + std::to_string(cols) + " " +
                                            std::to_string(count) + "\n" + body.str());
  } else if (name == "indefinite") {
    // The first node's mass negative, in all three components (still Ms (x) I3).
    std::istringstream in(M);
    std::ostringstream out;
    out.precision(17);
    std::string l;
    const std::size_t tag = own.dof[0].first;
    int k = 0;
    while (std::getline(in, l)) {
      ++k;
      long i, j;
      double v;
      std::istringstream ls(l);
      if (k > 3 && (ls >> i >> j >> v) && i == j && own.dof[static_cast<std::size_t>(i - 1)].first == tag)
        out << i << " " << j << " " << -v << "\n";
      else out << l << "\n";
    }
    test::write_text(bar.dir / "M.mtx", out.str());
  } else if (name == "missing") {
    std::filesystem::remove(bar.dir / "K.mtx");
  } else if (name == "malformed") {
    test::write_text(bar.dir / "K.mtx", replace_line(K, 10, "7 5 1.0e+x"));
  } else if (name == "rotation") {
    test::write_text(bar.dir / "dofs.txt", replace_line(formats::read_text_file(bar.dir / "dofs.txt"), 2, "1 4"));
  } else if (name == "unjoined") {
    // A spring between the first and the last DOF's nodes (the bar's two ends).
    test::write_text(bar.dir / "K.mtx", append_entry(K, std::to_string(own.K.rows()) + " 1 -1.0e6"));
  } else if (name == "coupled") {
    // A mass coupling x and y of the first node: not Ms (x) I3.
    test::write_text(bar.dir / "M.mtx", append_entry(M, "2 1 1.0e-4"));
  } else if (name == "stiffening") {
    matrices = std::string(kMtx) + R"(, "stiffening": true)";
  }
  const auto part = bar.part("bad.json", "clamped", matrices);
  const auto out = bar.dir / "bad.sid.h5";
  const auto r = test::run(test::bin("ffr-reduce").string() + " " + part.string() + " -o " + out.string());
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_FALSE(std::filesystem::exists(out));
  EXPECT_NE(r.output.find(c.file), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(c.expected), std::string::npos) << r.output;
  std::printf("%s: %s\n", c.name, r.output.substr(0, 400).c_str());
}

INSTANTIATE_TEST_SUITE_P(
    Cases, MatrixInputRefusal,
    ::testing::Values(BadCase{"size", "K.mtx", "line 3: the matrix has"},
                      BadCase{"asymmetric", "M.mtx", "not symmetric"},
                      BadCase{"indefinite", "M.mtx", "not positive definite"},
                      BadCase{"missing", "bad.json", "file not found"},
                      BadCase{"malformed", "K.mtx", "line 10: 'row column value'"},
                      BadCase{"rotation", "dofs.txt", "line 2: rotational DOF"},
                      BadCase{"stiffening", "bad.json", "needs element stresses"},
                      BadCase{"unjoined", "K.mtx", "which no element of the deck joins"},
                      BadCase{"coupled", "M.mtx", "a translational mass Ms (x) I3 is expected"}),
    [](const auto& info) { return std::string(info.param.name); });

// ---- Abaqus *MATRIX GENERATE output and Nastran DMIG: ffr's own K and M of the deck written in
// those layouts give the SID of the deck (rtol 1e-9), as the Matrix Market route above.
// Layouts: Abaqus Analysis User's Guide, "Generating matrices" (*MATRIX OUTPUT,
// FORMAT=MATRIX INPUT: "row node, row DOF, column node, column DOF, value", the lower triangle);
// MSC/NX Nastran Quick Reference Guide, DMIG (header "DMIG, NAME, 0, IFO, TIN, TOUT", columns
// "DMIG, NAME, GJ, CJ, , G1, C1, A1, B1" with continuations G, C, A, B; large field: 16
// characters a field, continuation lines starting with '*').
namespace {
// (row, col) entries of the lower (lower = true) or upper triangle of own's matrix, by DOF.
std::vector<std::tuple<Eigen::Index, Eigen::Index, double>> triangle(const preproc::SparseMatrix& A, bool lower) {
  std::vector<std::tuple<Eigen::Index, Eigen::Index, double>> t;
  for (Eigen::Index c = 0; c < A.outerSize(); ++c)
    for (preproc::SparseMatrix::InnerIterator it(A, c); it; ++it)
      if (it.value() != 0 && (lower ? it.row() >= it.col() : it.row() <= it.col())) t.emplace_back(it.row(), it.col(), it.value());
  return t;
}

void write_abaqus(const std::filesystem::path& p, const OwnMatrices& o, const preproc::SparseMatrix& A, const char* what) {
  std::ostringstream s;
  s.precision(17);
  s << "** ASSEMBLED " << what << " MATRIX, written by matrix_input_test\n** row node, row dof, column node, column dof, value\n";
  for (const auto& [r, c, v] : triangle(A, true)) {
    const auto& a = o.dof[static_cast<std::size_t>(r)];
    const auto& b = o.dof[static_cast<std::size_t>(c)];
    s << a.first << ", " << a.second << ", " << b.first << ", " << b.second << ", " << std::scientific << v << std::defaultfloat << "\n";
  }
  test::write_text(p, s.str());
}

// DMIG NAME as a punch file: large field (16 characters, 'D' exponents, 9 significant digits
// fit) or free field (17 digits), one column card per DOF column, the upper triangle.
void write_dmig(const std::filesystem::path& p, const OwnMatrices& o, const preproc::SparseMatrix& A, const std::string& name,
                bool large) {
  std::map<Eigen::Index, std::vector<std::pair<Eigen::Index, double>>> cols;
  for (const auto& [r, c, v] : triangle(A, false)) cols[c].emplace_back(r, v);
  std::ostringstream s;
  auto f16 = [](const std::string& v) { return v + std::string(16 - std::min<std::size_t>(16, v.size()), ' '); };
  auto f8 = [](const std::string& v) { return v + std::string(8 - std::min<std::size_t>(8, v.size()), ' '); };
  auto dreal = [](double v) {
    char b[32];
    std::snprintf(b, sizeof b, "%16.9E", v);
    std::string t = b;
    t[t.find('E')] = 'D';
    return t;
  };
  s << "$ DMIG " << name << " written by matrix_input_test\n";
  if (large) s << f8("DMIG*") << f16(name) << f16("0") << f16("6") << f16("2") << "\n" << f8("*") << f16("0") << "\n";
  else s << "DMIG," << name << ",0,6,2,0\n";
  char buf[40];
  for (const auto& [c, entries] : cols) {
    const auto& gj = o.dof[static_cast<std::size_t>(c)];
    if (large) s << f8("DMIG*") << f16(name) << f16(std::to_string(gj.first)) << f16(std::to_string(gj.second)) << f16("") << "\n";
    else s << "DMIG," << name << "," << gj.first << "," << gj.second << ",";
    for (std::size_t k = 0; k < entries.size(); ++k) {
      const auto& gi = o.dof[static_cast<std::size_t>(entries[k].first)];
      if (large) {
        s << f8("*") << f16(std::to_string(gi.first)) << f16(std::to_string(gi.second)) << dreal(entries[k].second) << "\n";
      } else {
        std::snprintf(buf, sizeof buf, "%.17g", entries[k].second);
        // Fields 6-9 of the first line, then 4 groups of (G, C, A, B) a continuation line.
        s << "," << gi.first << "," << gi.second << "," << buf << ",";
        if (k % 2 == 0) s << "\n";  // after field 9, and after fields 2-9 of each continuation
        s << (k % 2 == 0 && k + 1 < entries.size() ? "+" : "");
      }
    }
    if (!large) s << "\n";
  }
  test::write_text(p, s.str());
}
}  // namespace

TEST(NodeDofMatrices, AbaqusMatrixGenerateGivesTheSidOfTheDeck) {
  HexBar bar;
  const OwnMatrices own = own_matrices(bar.part("deck.json", "craig_bampton"));
  write_abaqus(bar.dir / "job_STIF1.mtx", own, own.K, "STIFFNESS");
  write_abaqus(bar.dir / "job_MASS1.mtx", own, own.M, "MASS");
  const formats::Sid deck = bar.reduce(bar.dir / "deck.json");
  const formats::Sid abq =
      bar.reduce(bar.part("abq.json", "craig_bampton", R"({"format": "abaqus", "K": "job_STIF1.mtx", "M": "job_MASS1.mtx"})"));
  const double f = expect_same_sid(deck, abq, 1e-9);
  EXPECT_EQ(abq.provenance.extra.at("matrices").rfind("abaqus: K job_STIF1.mtx", 0), 0u) << abq.provenance.extra.at("matrices");
  std::printf("Abaqus *MATRIX GENERATE vs the deck: largest relative frequency difference %.2e\n", f);
}

TEST(NodeDofMatrices, NastranDmigGivesTheSidOfTheDeck) {
  HexBar bar;
  const OwnMatrices own = own_matrices(bar.part("deck.json", "clamped"));
  // K in free field (17 digits) under a name of the part file's, M as a large-field punch
  // (10 significant digits: compared at the rounding's level below).
  write_dmig(bar.dir / "k.pch", own, own.K, "KSTIFF", false);
  write_dmig(bar.dir / "m.pch", own, own.M, "MAAX", true);
  const formats::Sid deck = bar.reduce(bar.dir / "deck.json");
  const formats::Sid dmig = bar.reduce(
      bar.part("dmig.json", "clamped", R"({"format": "dmig", "K": "k.pch", "M": "m.pch", "K_name": "KSTIFF"})"));
  const double f = expect_same_sid(deck, dmig, 1e-7);
  EXPECT_LE(f, 1e-9);
  EXPECT_EQ(dmig.provenance.extra.at("matrices").rfind("dmig KSTIFF, MAAX: K k.pch", 0), 0u) << dmig.provenance.extra.at("matrices");
  // Both in free field at 17 digits: the SID of the deck to 1e-9.
  write_dmig(bar.dir / "m17.pch", own, own.M, "MAAX", false);
  const formats::Sid dmig17 = bar.reduce(
      bar.part("dmig17.json", "clamped", R"({"format": "dmig", "K": "k.pch", "M": "m17.pch", "K_name": "KSTIFF"})"));
  const double f17 = expect_same_sid(deck, dmig17, 1e-9);
  std::printf("DMIG vs the deck: largest relative frequency difference %.2e (large-field M), %.2e (free field)\n", f, f17);
}

// Bad input of both readers, each by ffr-reduce: exit 2, the file and the line named, no SID.
TEST(NodeDofMatrices, BadInputExitsTwoNamingFileAndLine) {
  HexBar bar;
  const OwnMatrices own = own_matrices(bar.part("deck.json", "clamped"));
  write_abaqus(bar.dir / "K.mtx", own, own.K, "STIFFNESS");
  write_abaqus(bar.dir / "M.mtx", own, own.M, "MASS");
  write_dmig(bar.dir / "K.pch", own, own.K, "KAAX", false);
  write_dmig(bar.dir / "M.pch", own, own.M, "MAAX", false);
  const std::string K = formats::read_text_file(bar.dir / "K.mtx"), Kp = formats::read_text_file(bar.dir / "K.pch");
  const std::string tag = std::to_string(own.dof[0].first);
  // The transpose of K's first off-diagonal entry, 1 % off.
  std::string transposed_off_by_one_percent;
  for (const auto& [r, c, v] : triangle(own.K, true))
    if (r != c) {
      const auto& a = own.dof[static_cast<std::size_t>(r)];
      const auto& b = own.dof[static_cast<std::size_t>(c)];
      std::ostringstream s;
      s.precision(17);
      s << b.first << ", " << b.second << ", " << a.first << ", " << a.second << ", " << 1.01 * v << "\n";
      transposed_off_by_one_percent = s.str();
      break;
    }
  struct Case {
    std::string name, format, file, content, expected;
  };
  const std::vector<Case> cases{
      {"abaqus_fields", "abaqus", "K.mtx", replace_line(K, 5, "1, 1, 1, 2.5e3"), "K.mtx: line 5: 'row node, row DOF"},
      {"abaqus_number", "abaqus", "K.mtx", replace_line(K, 6, tag + ", 1, " + tag + ", 1, 1.0e+x"), "K.mtx: line 6: 'row node"},
      {"abaqus_keyword", "abaqus", "K.mtx", replace_line(K, 3, "*MATRIX INPUT, NAME=K"), "K.mtx: line 3: keyword line"},
      {"abaqus_rotation", "abaqus", "K.mtx", K + tag + ", 5, " + tag + ", 5, 1.0\n", "rotational DOF 5 of node " + tag},
      {"abaqus_node", "abaqus", "K.mtx", K + "999999, 1, 999999, 1, 1.0\n", "node 999999 is not in the deck"},
      {"abaqus_asymmetric", "abaqus", "K.mtx", K + transposed_off_by_one_percent, "not symmetric"},
      {"dmig_header", "dmig", "K.pch", replace_line(Kp, 2, "$ no header"), "K.pch: line 3 (DMIG KAAX): a column of DMIG KAAX before its header"},
      {"dmig_complex", "dmig", "K.pch", replace_line(Kp, 2, "DMIG,KAAX,0,6,3,0"), "K.pch: line 2 (DMIG KAAX): field 5 (TIN) is 3"},
      {"dmig_card", "dmig", "K.pch", Kp + "GRID,1,,0.,0.,0.\n", "only DMIG cards are expected"},
      {"dmig_number", "dmig", "K.pch", replace_line(Kp, 3, "DMIG,KAAX," + tag + ",1,," + tag + ",1,1.0+x"), "K.pch: line 3 (DMIG KAAX): field 8 (Ai): expected a number"},
      {"dmig_name", "dmig", "K.pch", Kp, "no DMIG header card of matrix KXX"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.name);
    test::write_text(bar.dir / ("bad_" + c.file), c.content);
    const bool abq = c.format == "abaqus";
    const std::string kf = "bad_" + c.file, mf = abq ? "M.mtx" : "M.pch";
    const std::string matrices = R"({"format": ")" + c.format + R"(", "K": ")" + kf + R"(", "M": ")" + mf + "\"" +
                                 (c.name == "dmig_name" ? R"(, "K_name": "KXX")" : "") + "}";
    const auto part = bar.part("bad.json", "clamped", matrices);
    const auto out = bar.dir / "bad.sid.h5";
    const auto r = test::run(test::bin("ffr-reduce").string() + " " + part.string() + " -o " + out.string());
    EXPECT_EQ(r.status, 2) << r.output;
    EXPECT_FALSE(std::filesystem::exists(out));
    std::string expected = c.expected;
    if (expected.rfind("K.", 0) == 0) expected = "bad_" + expected;
    EXPECT_NE(r.output.find(expected), std::string::npos) << r.output;
    std::printf("%s: %s\n", c.name.c_str(), r.output.substr(0, 300).c_str());
  }
}

// ---- Issue 39's check: one part meshed by gmsh, as its MSH file, as gmsh's .inp deck, as a
// Nastran bulk-data deck (free field, 17 digits) and as ffr's assembled K and M of the deck in
// Matrix Market (and as Abaqus *MATRIX GENERATE output and DMIG, the latter on the bulk data's
// grids): the SIDs equal by ffr-diff (rtol 1e-9), the command-line tool outside scripts use. The groups are named as the bulk data names them (pid7, set1, set2) so that the
// interfaces' descriptions agree too.
TEST(SamePartFourWays, MshInpBdfAndMatricesGiveOneSid) {
  test::TempDir dir("interop_chain");
  test::write_text(dir / "bar.geo", R"(Point(1) = {0, 0, 0}; Point(2) = {0.2, 0, 0}; Line(1) = {1, 2};
e[] = Extrude{0, 0.02, 0}{Line{1}; Layers{3}; Recombine;};
v[] = Extrude{0, 0, 0.012}{Surface{e[1]}; Layers{2}; Recombine;};
Transfinite Curve{1} = 13;
Physical Volume("pid7") = {v[1]};
Physical Surface("set1") = Surface In BoundingBox{-1e-6, -1, -1, 1e-6, 1, 1};
Physical Surface("set2") = Surface In BoundingBox{0.2 - 1e-6, -1, -1, 0.2 + 1e-6, 1, 1};
)");
  test::gmsh_mesh(dir / "bar.geo", dir / "bar.msh", 0.006, 2);
  const auto r = test::run("gmsh " + (dir / "bar.msh").string() + " -0 -setnumber Mesh.SaveGroupsOfNodes 1 -format inp -o " +
                           (dir / "gmsh.inp").string());
  ASSERT_EQ(r.status, 0) << r.output;
  {
    // gmsh's deck without its plane elements, with the steel of the part file.
    std::istringstream in(formats::read_text_file(dir / "gmsh.inp"));
    std::ostringstream out;
    std::string line;
    bool drop = false;
    while (std::getline(in, line)) {
      if (!line.empty() && line[0] == '*' && line.rfind("**", 0) != 0)
        drop = (line.rfind("*ELEMENT", 0) == 0 && line.find("type=C3D") == std::string::npos) ||
               (line.rfind("*ELSET", 0) == 0 && line.find("ELSET=pid7") == std::string::npos);
      if (!drop) out << line << "\n";
    }
    test::write_text(dir / "bar.inp", out.str() + "*MATERIAL, NAME=STEEL\n*ELASTIC\n2.1e11, 0.3\n*DENSITY\n7850\n"
                                                  "*SOLID SECTION, ELSET=pid7, MATERIAL=STEEL\n");
  }
  const std::string rest = R"(, "visual": false,
    "interfaces": [{"name": "root", "group": "set1"}, {"name": "end", "group": "set2", "coupling": "averaged"}],
    "reduction": {"method": "craig-bampton", "interfaces": ["root", "end"], "frame": "root", "modes": 4}})";
  test::write_text(dir / "msh.json", R"({"geometry": "bar.msh", "materials": [{"group": "pid7", "E": 2.1e11, "nu": 0.3, "rho": 7850}])" + rest);
  test::write_text(dir / "inp.json", R"({"geometry": "bar.inp")" + rest);
  // The bulk data of the MSH's mesh: CHEXA in Nastran's node order (Quick Reference Guide,
  // CHEXA: corners, then the bottom face's edges, the vertical edges, the top face's edges).
  {
    const preproc::Mesh m = preproc::load_mesh(preproc::load_part(dir / "msh.json"));
    std::ostringstream s;
    s.precision(17);
    s << "BEGIN BULK\n";
    for (preproc::Index n = 0; n < m.num_nodes(); ++n)
      s << "GRID," << m.node_tag(n) << ",," << m.x(n, 0) << "," << m.x(n, 1) << "," << m.x(n, 2) << "\n";
    const int nastran_of_gmsh[20] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 11, 12, 9, 13, 10, 14, 15, 16, 19, 17, 18};
    std::map<std::string, std::set<std::size_t>> sets;
    for (const auto& b : m.blocks) {
      if (b.type != preproc::ElementType::Hex20 || b.group != "pid7") continue;
      for (preproc::Index e = 0; e < b.size(); ++e) {
        std::size_t g[20];
        for (int k = 0; k < 20; ++k) g[nastran_of_gmsh[k]] = m.node_tag(b.element(e)[k]);
        s << "CHEXA," << m.element_tag(b, e) << ",7";
        for (int k = 0; k < 20; ++k) s << (k == 6 || k == 14 ? "\n+," : ",") << g[k];
        s << "\n";
      }
    }
    for (preproc::Index n = 0; n < m.num_nodes(); ++n) {
      if (std::abs(m.x(n, 0)) < 1e-9) sets["1"].insert(m.node_tag(n));
      if (std::abs(m.x(n, 0) - 0.2) < 1e-9) sets["2"].insert(m.node_tag(n));
    }
    for (const auto& [id, tags] : sets) {
      s << "SET1," << id;
      int k = 1;
      for (const auto t : tags) {
        s << (k % 8 == 0 ? "\n+," : ",") << t;
        ++k;
      }
      s << "\n";
    }
    s << "PSOLID,7,3\nMAT1,3,2.1+11,,0.3,7850.\nENDDATA\n";
    test::write_text(dir / "bar.bdf", s.str());
  }
  test::write_text(dir / "bdf.json", R"({"geometry": "bar.bdf")" + rest);
  // ffr's K and M of the .inp deck as Matrix Market, rows shuffled.
  const OwnMatrices own = own_matrices(dir / "inp.json");
  const auto perm = shuffled(own.K.rows());
  write_mtx(dir / "K.mtx", own.K, perm);
  write_mtx(dir / "M.mtx", own.M, perm);
  write_dofs(dir / "dofs.txt", own, perm);
  test::write_text(dir / "mtx.json", R"({"geometry": "bar.inp", "matrices": )" + std::string(kMtx) + rest);
  // And the same K and M as Abaqus *MATRIX GENERATE output and as DMIG (free field, 17 digits).
  write_abaqus(dir / "job_STIF1.mtx", own, own.K, "STIFFNESS");
  write_abaqus(dir / "job_MASS1.mtx", own, own.M, "MASS");
  test::write_text(dir / "abq.json", R"({"geometry": "bar.inp", "matrices": {"format": "abaqus", "K": "job_STIF1.mtx", "M": "job_MASS1.mtx"})" + rest);
  write_dmig(dir / "k.pch", own, own.K, "KAAX", false);
  write_dmig(dir / "m.pch", own, own.M, "MAAX", false);
  test::write_text(dir / "dmig.json", R"({"geometry": "bar.bdf", "matrices": {"format": "dmig", "K": "k.pch", "M": "m.pch"})" + rest);

  for (const char* name : {"msh", "inp", "bdf", "mtx", "abq", "dmig"}) {
    const auto out = dir / (std::string(name) + ".sid.h5");
    const auto red = test::run(test::bin("ffr-reduce").string() + " " + (dir / (std::string(name) + ".json")).string() + " -o " +
                               out.string());
    ASSERT_EQ(red.status, 0) << name << ":\n" << red.output;
  }
  for (const char* name : {"inp", "bdf", "mtx", "abq", "dmig"}) {
    const auto d = test::run(test::bin("ffr-diff").string() + " " + (dir / "msh.sid.h5").string() + " " +
                             (dir / (std::string(name) + ".sid.h5")).string() + " --rtol 1e-9");
    EXPECT_EQ(d.status, 0) << "msh vs " << name << ":\n" << d.output;
    std::printf("ffr-diff msh vs %s (rtol 1e-9): exit %d\n%s\n", name, d.status, d.output.substr(0, 600).c_str());
  }
  // A deck's CONM2 on top of assembled matrices is refused (the matrices' M must hold it).
  {
    std::string t = formats::read_text_file(dir / "bar.bdf");
    t.insert(t.find("PSOLID"), "CONM2,900," + std::to_string(own.dof[0].first) + ",,1.5\n");
    test::write_text(dir / "conm2.bdf", t);
    test::write_text(dir / "conm2.json", R"({"geometry": "conm2.bdf", "matrices": {"format": "dmig", "K": "k.pch", "M": "m.pch"})" + rest);
    const auto bad = test::run(test::bin("ffr-reduce").string() + " " + (dir / "conm2.json").string() + " -o " + (dir / "conm2.sid.h5").string());
    EXPECT_EQ(bad.status, 2) << bad.output;
    EXPECT_FALSE(std::filesystem::exists(dir / "conm2.sid.h5"));
    EXPECT_NE(bad.output.find("conm2.json: matrices: the deck's CONM2 900 cannot be added to assembled matrices"), std::string::npos) << bad.output;
  }
  // The diff can fail: a deck with another Young's modulus differs.
  {
    std::string t = formats::read_text_file(dir / "bar.inp");
    t.replace(t.find("2.1e11, 0.3"), 11, "2.0e11, 0.3");
    test::write_text(dir / "soft.inp", t);
  }
  test::write_text(dir / "soft.json", R"({"geometry": "soft.inp")" + rest);
  ASSERT_EQ(test::run(test::bin("ffr-reduce").string() + " " + (dir / "soft.json").string() + " -o " + (dir / "soft.sid.h5").string()).status, 0);
  const auto d = test::run(test::bin("ffr-diff").string() + " " + (dir / "msh.sid.h5").string() + " " + (dir / "soft.sid.h5").string() +
                           " --rtol 1e-9");
  EXPECT_NE(d.status, 0) << d.output;
}
