// ffr-info --export-fbi and --export-mtx, read back by parsers written here from the layouts
// (the SID_FEM text layout of the standard input data, Wallrapp, "Standard Input Data of
// Flexible Members in Multibody Systems", 1994, as formats/SPEC.md "Exports" states it; the
// Matrix Market array format of the NIST Matrix Market exchange formats): every member of a
// reduced TET10 bar with stiffening equals the SID's, bit for bit (17 significant digits).
#include "ffr/formats/sid_io.hpp"
#include "ffr/formats/text_file.hpp"
#include "ffr/preproc/pipeline.hpp"
#include "support.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <map>
#include <regex>
#include <sstream>

using namespace ffr;

namespace {

// One Taylor member as the file gives it: m0 (nrow x ncol) and m1[k] (nrow x ncol).
struct Block {
  int order = -1;
  Eigen::Index nrow = 0, ncol = 0, nq = 0;
  Eigen::MatrixXd m0;
  std::vector<Eigen::MatrixXd> m1;
  Eigen::Index entries = 0;
};

struct Fbi {
  std::map<std::string, std::string> refmod;
  std::vector<std::map<std::string, Block>> nodes;
  std::vector<std::string> rframe;
  std::map<std::string, Block> members;
};

Fbi parse_fbi(const std::string& text) {
  Fbi f;
  std::istringstream in(text);
  std::string line;
  const std::regex key(R"(^\s*(\w+(?:\(\d+\))?)\s*=\s*(.*?)\s*$)");
  const std::regex m0(R"(^\s*m0\(\s*(\d+),\s*(\d+)\)\s*=\s*(\S+)\s*$)");
  const std::regex m1(R"(^\s*m1\(\s*(\d+),\s*(\d+),\s*(\d+)\)\s*=\s*(\S+)\s*$)");
  std::vector<std::string> stack;  // open sections
  Block* block = nullptr;
  std::string block_name;
  const auto expect = [&](bool ok, const std::string& what) {
    if (!ok) throw std::runtime_error("SID_FEM: " + what + " at '" + line + "'");
  };
  std::smatch m;
  while (std::getline(in, line)) {
    if (block) {
      if (std::regex_match(line, m, m0)) {
        const auto i = std::stol(m[1]) - 1, j = std::stol(m[2]) - 1;
        expect(i >= 0 && i < block->nrow && j >= 0 && j < block->ncol, "m0 index out of range");
        block->m0(i, j) = std::stod(m[3]);
        ++block->entries;
      } else if (std::regex_match(line, m, m1)) {
        const auto i = std::stol(m[1]) - 1, j = std::stol(m[2]) - 1, k = std::stol(m[3]) - 1;
        expect(block->order == 1 && i >= 0 && i < block->nrow && j >= 0 && j < block->ncol && k >= 0 && k < block->nq,
               "m1 index out of range");
        block->m1[static_cast<std::size_t>(k)](i, j) = std::stod(m[4]);
        ++block->entries;
      } else if (line == "end " + block_name) {
        expect(block->entries == block->nrow * block->ncol * (1 + (block->order == 1 ? block->nq : 0)), "entries missing");
        block = nullptr;
      } else if (std::regex_match(line, m, key)) {
        const std::string k = m[1];
        const long v = std::stol(m[2]);
        if (k == "order") block->order = static_cast<int>(v);
        else if (k == "nrow") block->nrow = v;
        else if (k == "ncol") block->ncol = v;
        else if (k == "nq") block->nq = v;
        else expect(k == "nqn" || k == "structure", "unknown key");
        if (k == "structure") {
          expect(v == 3, "structure other than 3");
          block->m0 = Eigen::MatrixXd::Constant(block->nrow, block->ncol, std::nan(""));
          if (block->order == 1)
            block->m1.assign(static_cast<std::size_t>(block->nq), Eigen::MatrixXd::Constant(block->nrow, block->ncol, std::nan("")));
        }
      } else {
        expect(false, "unexpected line in " + block_name);
      }
      continue;
    }
    const std::string ctx = stack.empty() ? "" : stack.back();
    if (line == "part" || line == "new modal" || line == "refmod" || line == "new frame") {
      stack.push_back(line);
    } else if (line.rfind("new node = ", 0) == 0) {
      expect(ctx == "new frame", "node outside the frame");
      expect(std::stol(line.substr(11)) == static_cast<long>(f.nodes.size()) + 1, "nodes out of order");
      f.nodes.emplace_back();
      stack.push_back("node");
    } else if (line.rfind("end ", 0) == 0) {
      const std::string what = line.substr(4);
      const std::string open = what == "node" ? "node" : what == "frame" ? "new frame" : what == "modal" ? "new modal" : what;
      expect(ctx == open, "end of a section not open");
      stack.pop_back();
    } else if (ctx == "refmod" && std::regex_match(line, m, key)) {
      f.refmod[m[1]] = m[2];
    } else if (ctx == "node" && line.rfind("rframe = ", 0) == 0) {
      f.rframe.push_back(line.substr(9));
    } else if (ctx == "node" || ctx == "new modal") {
      block_name = line;
      auto& map = ctx == "node" ? f.nodes.back() : f.members;
      expect(!map.count(line), "member twice");
      block = &map[line];
    } else {
      expect(false, "unexpected line");
    }
  }
  expect(stack.empty() && !block, "file ends inside a section");
  return f;
}

Eigen::MatrixXd read_mtx(const std::filesystem::path& p) {
  std::istringstream in(formats::read_text_file(p));
  std::string line;
  std::getline(in, line);
  if (line != "%%MatrixMarket matrix array real general") throw std::runtime_error("header " + line);
  while (in.peek() == '%') std::getline(in, line);
  Eigen::Index r = 0, c = 0;
  in >> r >> c;
  Eigen::MatrixXd m(r, c);
  for (Eigen::Index j = 0; j < c; ++j)
    for (Eigen::Index i = 0; i < r; ++i)
      if (!(in >> m(i, j))) throw std::runtime_error("short file " + p.string());
  std::string rest;
  if (in >> rest) throw std::runtime_error("extra data in " + p.string());
  return m;
}

Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d s;
  s << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return s;
}

struct Body {
  test::TempDir dir{"interop_export"};
  formats::Sid sid;
  Body() {
    test::write_text(dir / "bar.geo", R"(SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 0.2, 0.02, 0.012};
Physical Volume("body") = {1};
Physical Surface("clamp") = Surface In BoundingBox{-1e-6, -1, -1, 1e-6, 1, 1};
Physical Surface("tip") = Surface In BoundingBox{0.2 - 1e-6, -1, -1, 0.2 + 1e-6, 1, 1};
)");
    test::gmsh_mesh(dir / "bar.geo", dir / "bar.msh", 0.008, 2);
    test::write_text(dir / "bar.json", R"({"geometry": "bar.msh", "visual": false, "stiffening": true,
      "materials": [{"group": "body", "E": 2.1e11, "nu": 0.3, "rho": 7850}],
      "interfaces": [{"name": "root", "group": "clamp"}, {"name": "tip", "group": "tip", "coupling": "averaged"}],
      "damping": {"ratio": 0.02},
      "reduction": {"method": "clamped", "interface": "root", "modes": 4}})");
    formats::write_sid(preproc::run_pipeline(preproc::load_part(dir / "bar.json")), dir / "bar.sid.h5");
    sid = formats::read_sid(dir / "bar.sid.h5");
  }
};

void expect_equal(const Block& b, const Eigen::MatrixXd& m0, const std::vector<Eigen::MatrixXd>* m1, const std::string& what) {
  ASSERT_EQ(b.nrow, m0.rows()) << what;
  ASSERT_EQ(b.ncol, m0.cols()) << what;
  EXPECT_EQ(b.order, m1 ? 1 : 0) << what;
  EXPECT_TRUE(b.m0 == m0) << what << " m0";
  if (m1) {
    ASSERT_EQ(b.m1.size(), m1->size()) << what;
    for (std::size_t k = 0; k < m1->size(); ++k) EXPECT_TRUE(b.m1[k] == (*m1)[k]) << what << " m1 mode " << k + 1;
  }
}

}  // namespace

TEST(Export, SidFemEveryMemberReadsBack) {
  Body body;
  const formats::Sid& s = body.sid;
  const auto r = test::run(test::bin("ffr-info").string() + " " + (body.dir / "bar.sid.h5").string() + " --export-fbi -o " +
                           (body.dir / "bar.fbi").string());
  ASSERT_EQ(r.status, 0) << r.output;
  const Fbi f = parse_fbi(formats::read_text_file(body.dir / "bar.fbi"));
  const Eigen::Index nq = s.nq();
  ASSERT_EQ(nq, 4);
  ASSERT_TRUE(s.stiffening.has_value());
  EXPECT_EQ(std::stod(f.refmod.at("mass")), s.refmod.mass);
  EXPECT_EQ(std::stol(f.refmod.at("nelastq")), nq);
  for (Eigen::Index k = 0; k < nq; ++k) EXPECT_EQ(f.refmod.count("ielastq(" + std::to_string(k + 1) + ")"), 1u);

  ASSERT_EQ(f.nodes.size(), s.nodes.size());
  for (std::size_t p = 0; p < s.nodes.size(); ++p) {
    const auto& n = s.nodes[p];
    const auto& b = f.nodes[p];
    std::vector<Eigen::MatrixXd> origin1, ap1;
    for (Eigen::Index k = 0; k < nq; ++k) {
      origin1.push_back(n.phi.col(k));
      ap1.push_back(skew(n.psi.col(k)) * n.AP0);
    }
    expect_equal(b.at("origin"), n.origin, &origin1, n.name + " origin");
    expect_equal(b.at("phi"), n.phi, nullptr, n.name + " phi");
    expect_equal(b.at("psi"), n.psi, nullptr, n.name + " psi");
    expect_equal(b.at("AP"), n.AP0, &ap1, n.name + " AP");
    EXPECT_EQ(b.size(), 4u);
  }
  const auto K = [](Eigen::Index k) { return static_cast<std::size_t>(k); };
  std::vector<Eigen::MatrixXd> md1, j1, ct1, cr1, oe1, ks1, ke1;
  Eigen::MatrixXd gr(3, 3 * nq), ge(nq, 3 * nq);
  for (Eigen::Index k = 0; k < nq; ++k) {
    md1.push_back(s.mdCM.M1.row(k).transpose());
    j1.push_back(s.J.M1[K(k)]);
    ct1.push_back(s.stiffening->K0t[K(k)]);
    cr1.push_back(s.Cr.M1[K(k)] + s.stiffening->K0r[K(k)]);
    oe1.push_back(s.Oe.M1[K(k)] + s.stiffening->K0om[K(k)]);
    ks1.push_back(s.ksigma.M1.row(k).transpose());
    if (!s.KeM1.empty()) ke1.push_back(s.KeM1[K(k)]);
    gr.middleCols(3 * k, 3) = s.Gr[K(k)];
    ge.middleCols(3 * k, 3) = s.Ge[K(k)];
  }
  expect_equal(f.members.at("mdCM"), s.mdCM.M0, &md1, "mdCM");
  expect_equal(f.members.at("J"), s.J.M0, &j1, "J");
  expect_equal(f.members.at("Ct"), s.Ct.M0, &ct1, "Ct");
  expect_equal(f.members.at("Cr"), s.Cr.M0, &cr1, "Cr");
  expect_equal(f.members.at("Me"), s.Me, nullptr, "Me");
  expect_equal(f.members.at("Gr"), gr, nullptr, "Gr");
  expect_equal(f.members.at("Ge"), ge, nullptr, "Ge");
  expect_equal(f.members.at("Oe"), s.Oe.M0, &oe1, "Oe");
  expect_equal(f.members.at("ksigma"), s.ksigma.M0, &ks1, "ksigma");
  expect_equal(f.members.at("Ke"), s.Ke, s.KeM1.empty() ? nullptr : &ke1, "Ke");
  expect_equal(f.members.at("De"), s.De, nullptr, "De");
  EXPECT_EQ(f.members.size(), 11u);
  // Damping 0.02 of the part: De is not zero, so its entries were compared for real.
  EXPECT_GT(s.De.norm(), 0.0);
}

TEST(Export, MatrixMarketReadsBack) {
  Body body;
  const auto dir = body.dir / "mtx";
  const auto r = test::run(test::bin("ffr-info").string() + " " + (body.dir / "bar.sid.h5").string() + " --export-mtx -o " + dir.string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(read_mtx(dir / "Me.mtx") == body.sid.Me);
  EXPECT_TRUE(read_mtx(dir / "Ke.mtx") == body.sid.Ke);
  EXPECT_TRUE(read_mtx(dir / "De.mtx") == body.sid.De);
  for (std::size_t k = 0; k < body.sid.KeM1.size(); ++k)
    EXPECT_TRUE(read_mtx(dir / ("KeM1_" + std::to_string(k + 1) + ".mtx")) == body.sid.KeM1[k]) << k;
}

// A damaged SID or a missing -o: exit status 2 and no file written.
TEST(Export, BadInputWritesNothing) {
  test::TempDir dir("interop_export_bad");
  test::write_text(dir / "bad.sid.h5", "not an HDF5 file");
  const std::string info = test::bin("ffr-info").string();
  auto r = test::run(info + " " + (dir / "bad.sid.h5").string() + " --export-fbi -o " + (dir / "out.fbi").string());
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("bad.sid.h5"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "out.fbi"));
  r = test::run(info + " " + (dir / "bad.sid.h5").string() + " --export-mtx -o " + (dir / "mtx").string());
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "mtx" / "Me.mtx"));
  r = test::run(info + " " + (dir / "bad.sid.h5").string() + " --export-fbi");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("--export-fbi needs -o OUT"), std::string::npos) << r.output;
  // -o naming the SID itself replaced it by the text (exit 0).
  r = test::run(info + " " + (dir / "bad.sid.h5").string() + " --export-fbi -o " + (dir / "." / "bad.sid.h5").string());
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("would overwrite the SID file " + (dir / "bad.sid.h5").string()), std::string::npos) << r.output;
  std::ifstream kept(dir / "bad.sid.h5");
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(kept), {}), "not an HDF5 file");
}
