// ffr-sim --vtk RUN.pvd: every file parses as XML (a strict parser written here, apart from the
// writer) with the VTK structure ParaView reads (sizes, index ranges, one frame per output
// sample at its time); the flexible body's points move, by exactly the displacement written
// with them; a rigid body is drawn as its inertia box, checked against the box formula
// I_xx = m (b^2 + c^2) / 12 (a box of sides 0.3 x 0.1 x 0.05 m given by its inertia comes back
// with those sides, centred on the centre of mass the run reports); a SID without a surface is
// refused before the run with nothing written; a shell vertex shows the largest von Mises stress
// of its three layers.
#include "ffr/formats/results_io.hpp"
#include "ffr/formats/sid_io.hpp"
#include "ffr/formats/text_file.hpp"
#include "support.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <Eigen/Geometry>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <fstream>
#include <iostream>
#include <cctype>
#include <map>
#include <memory>
#include <sstream>

using namespace ffr;

namespace {

// ---- a strict XML parser (elements, attributes, text; the prolog) --------------------------
struct Element {
  std::string name;
  std::map<std::string, std::string> attrs;
  std::vector<std::unique_ptr<Element>> children;
  std::string text;
  const Element* child(const std::string& n) const {
    for (const auto& c : children)
      if (c->name == n) return c.get();
    return nullptr;
  }
  std::vector<const Element*> all(const std::string& n) const {
    std::vector<const Element*> out;
    for (const auto& c : children)
      if (c->name == n) out.push_back(c.get());
    return out;
  }
};

class Parser {
 public:
  explicit Parser(std::string s) : s_(std::move(s)) {}
  std::unique_ptr<Element> document() {
    skip_space();
    if (s_.compare(i_, 5, "<?xml") == 0) {
      const auto e = s_.find("?>", i_);
      if (e == std::string::npos) fail("unterminated prolog");
      i_ = e + 2;
    }
    skip_space();
    auto root = element();
    skip_space();
    if (i_ != s_.size()) fail("content after the root element");
    return root;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw std::runtime_error("XML: " + what + " at offset " + std::to_string(i_));
  }
  void skip_space() {
    while (i_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[i_]))) ++i_;
  }
  std::string name() {
    const std::size_t b = i_;
    while (i_ < s_.size() && (std::isalnum(static_cast<unsigned char>(s_[i_])) || s_[i_] == '_' || s_[i_] == '-' || s_[i_] == ':')) ++i_;
    if (i_ == b) fail("expected a name");
    return s_.substr(b, i_ - b);
  }
  std::unique_ptr<Element> element() {
    if (s_[i_] != '<') fail("expected '<'");
    ++i_;
    auto e = std::make_unique<Element>();
    e->name = name();
    for (;;) {
      skip_space();
      if (i_ >= s_.size()) fail("unterminated tag");
      if (s_.compare(i_, 2, "/>") == 0) {
        i_ += 2;
        return e;
      }
      if (s_[i_] == '>') {
        ++i_;
        break;
      }
      const std::string a = name();
      skip_space();
      if (s_[i_] != '=') fail("expected '=' after attribute " + a);
      ++i_;
      skip_space();
      if (s_[i_] != '"') fail("attribute value not quoted");
      const auto end = s_.find('"', i_ + 1);
      if (end == std::string::npos) fail("unterminated attribute value");
      if (!e->attrs.emplace(a, s_.substr(i_ + 1, end - i_ - 1)).second) fail("attribute " + a + " twice");
      i_ = end + 1;
    }
    for (;;) {
      const auto lt = s_.find('<', i_);
      if (lt == std::string::npos) fail("unterminated element " + e->name);
      const std::string text = s_.substr(i_, lt - i_);
      if (text.find('&') != std::string::npos || text.find('>') != std::string::npos) fail("stray character in text");
      e->text += text;
      i_ = lt;
      if (s_.compare(i_, 2, "</") == 0) {
        i_ += 2;
        if (name() != e->name) fail("end tag does not match " + e->name);
        skip_space();
        if (s_[i_] != '>') fail("expected '>'");
        ++i_;
        return e;
      }
      e->children.push_back(element());
    }
  }
  std::string s_;
  std::size_t i_ = 0;
};

std::vector<double> numbers(const Element* e) {
  if (!e) throw std::runtime_error("missing DataArray");
  std::istringstream in(e->text);
  std::vector<double> v;
  std::string tok;
  while (in >> tok) {
    std::size_t used = 0;
    v.push_back(std::stod(tok, &used));
    if (used != tok.size()) throw std::runtime_error("not a number: " + tok);
  }
  return v;
}

const Element* array(const Element* parent, const std::string& name) {
  for (const auto* a : parent->all("DataArray"))
    if (a->attrs.count("Name") && a->attrs.at("Name") == name) return a;
  return nullptr;
}

struct Frame {
  std::vector<double> points, displacement, von_mises, has_stress, body;
  std::vector<double> connectivity;
  long long np = 0, nc = 0;
};

Frame read_frame(const std::filesystem::path& p) {
  const auto root = Parser(formats::read_text_file(p)).document();
  EXPECT_EQ(root->name, "VTKFile");
  EXPECT_EQ(root->attrs.at("type"), "UnstructuredGrid");
  const Element* piece = root->child("UnstructuredGrid")->child("Piece");
  Frame f;
  f.np = std::stoll(piece->attrs.at("NumberOfPoints"));
  f.nc = std::stoll(piece->attrs.at("NumberOfCells"));
  f.points = numbers(piece->child("Points")->child("DataArray"));
  const Element* cells = piece->child("Cells");
  f.connectivity = numbers(array(cells, "connectivity"));
  const auto offsets = numbers(array(cells, "offsets")), types = numbers(array(cells, "types"));
  EXPECT_EQ(static_cast<long long>(f.points.size()), 3 * f.np);
  EXPECT_EQ(static_cast<long long>(f.connectivity.size()), 3 * f.nc);
  EXPECT_EQ(static_cast<long long>(offsets.size()), f.nc);
  EXPECT_EQ(static_cast<long long>(types.size()), f.nc);
  for (std::size_t c = 0; c < offsets.size(); ++c) EXPECT_EQ(offsets[c], 3.0 * (c + 1));
  for (double t : types) EXPECT_EQ(t, 5.0);  // VTK_TRIANGLE
  for (double i : f.connectivity) EXPECT_TRUE(i >= 0 && i < f.np);
  const Element* pd = piece->child("PointData");
  f.displacement = numbers(array(pd, "displacement"));
  EXPECT_EQ(static_cast<long long>(f.displacement.size()), 3 * f.np);
  if (array(pd, "von_mises")) {
    f.von_mises = numbers(array(pd, "von_mises"));
    f.has_stress = numbers(array(pd, "has_stress"));
    EXPECT_EQ(static_cast<long long>(f.von_mises.size()), f.np);
  }
  f.body = numbers(array(piece->child("CellData"), "body"));
  EXPECT_EQ(static_cast<long long>(f.body.size()), f.nc);
  return f;
}

// The box's inertia about its centre, global axes: I_xx = m (b^2 + c^2) / 12, ...
constexpr double kMass = 2, kA = 0.3, kB = 0.1, kC = 0.05;

struct Scene {
  test::TempDir dir{"vtk"};
  explicit Scene(bool visual) {
    test::write_text(dir / "bar.geo", R"(SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 0.2, 0.02, 0.012};
Physical Volume("body") = {1};
Physical Surface("clamp") = Surface In BoundingBox{-1e-6, -1, -1, 1e-6, 1, 1};
)");
    test::gmsh_mesh(dir / "bar.geo", dir / "bar.msh", 0.006, 2);
    test::write_text(dir / "bar.json", std::string(R"({"geometry": "bar.msh",
      "materials": [{"group": "body", "E": 2.1e11, "nu": 0.3, "rho": 7850}],
      "interfaces": [{"name": "root", "group": "clamp"}],
      "reduction": {"method": "clamped", "interface": "root", "modes": 4}, "stress": {"surface": true},
      "visual": )") + (visual ? "true" : "false") + "}");
    const auto r = test::run(test::bin("ffr-reduce").string() + " " + (dir / "bar.json").string() + " -o " +
                             (dir / "bar.sid.h5").string() + " --quiet");
    if (r.status != 0) throw std::runtime_error(r.output);
    std::ostringstream inertia;
    inertia.precision(17);
    inertia << "[[" << kMass * (kB * kB + kC * kC) / 12 << ", 0, 0], [0, " << kMass * (kA * kA + kC * kC) / 12
            << ", 0], [0, 0, " << kMass * (kA * kA + kB * kB) / 12 << "]]";
    test::write_text(dir / "model.json", R"({"gravity": [0, 0, -9.81],
      "bodies": [{"name": "bar", "type": "flexible", "sid": "bar.sid.h5"},
                 {"name": "box", "type": "rigid", "mass": 2, "com": [0.5, 0, -0.1], "inertia": )" + inertia.str() + R"(,
                  "position": [0.4, 0, 0]}],
      "joints": [{"name": "clamp", "type": "fixed", "body1": "ground", "body2": "bar", "node2": "root"},
                 {"name": "hinge", "type": "revolute", "body1": "ground", "body2": "box", "at": [0.4, 0, 0], "axis": [0, 1, 0]}],
      "solver": {"end": 0.02, "step": 0.001},
      "outputs": [{"name": "q", "type": "modal_coordinates", "body": "bar"},
                  {"name": "box_c", "type": "node_position", "body": "box", "at": [0.5, 0, -0.1]}]})");
  }
  test::RunResult sim() const {
    return test::run("cd " + dir.path().string() + " && " + test::bin("ffr-sim").string() +
                     " model.json -o run.h5 --vtk run.pvd --quiet");
  }
};

bool have_tools() {
  return std::system("command -v gmsh > /dev/null 2>&1") == 0 && std::filesystem::exists(test::bin("ffr-reduce")) &&
         std::filesystem::exists(test::bin("ffr-sim"));
}

}  // namespace

TEST(VtkSeries, FramesParseMoveAndMatchTheRun) {
  if (!have_tools()) GTEST_SKIP() << "gmsh, ffr-reduce or ffr-sim missing";
  Scene run(true);
  const auto r = run.sim();
  ASSERT_EQ(r.status, 0) << r.output;
  const formats::Results res = formats::read_results(run.dir / "run.h5");
  ASSERT_EQ(res.outputs.size(), 2u) << "the hidden outputs of --vtk must not reach the results file";

  const auto pvd = Parser(formats::read_text_file(run.dir / "run.pvd")).document();
  ASSERT_EQ(pvd->attrs.at("type"), "Collection");
  const auto sets = pvd->child("Collection")->all("DataSet");
  ASSERT_EQ(static_cast<Eigen::Index>(sets.size()), res.time.size());
  ASSERT_GT(sets.size(), 10u);
  const formats::Results::Output& box_c = *res.find("box_c");
  std::vector<Frame> frames;
  for (std::size_t k = 0; k < sets.size(); ++k) {
    EXPECT_DOUBLE_EQ(std::stod(sets[k]->attrs.at("timestep")), res.time(static_cast<Eigen::Index>(k)));
    frames.push_back(read_frame(run.dir / sets[k]->attrs.at("file")));
    const Frame& f = frames.back();
    // Cells of body 1 (the box) are its 12 triangles on 8 points: its centre is the run's centre
    // of mass, and its edges are the box's sides.
    std::vector<long long> box_points;
    for (long long c = 0; c < f.nc; ++c)
      if (f.body[static_cast<std::size_t>(c)] == 1)
        for (int j = 0; j < 3; ++j) box_points.push_back(static_cast<long long>(f.connectivity[static_cast<std::size_t>(3 * c + j)]));
    std::sort(box_points.begin(), box_points.end());
    box_points.erase(std::unique(box_points.begin(), box_points.end()), box_points.end());
    ASSERT_EQ(box_points.size(), 8u);
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    std::vector<Eigen::Vector3d> corners;
    for (long long p : box_points) corners.emplace_back(f.points[3 * p], f.points[3 * p + 1], f.points[3 * p + 2]);
    for (const auto& c : corners) centre += c / 8;
    EXPECT_LT((centre - box_c.values.row(static_cast<Eigen::Index>(k)).transpose()).norm(), 1e-8) << "frame " << k;
    // The 28 distances between corners, ascending: 4 each of c, b, the b-c face diagonal, a, ...
    std::vector<double> edges;
    for (std::size_t i = 0; i < 8; ++i)
      for (std::size_t j = i + 1; j < 8; ++j) edges.push_back((corners[i] - corners[j]).norm());
    std::sort(edges.begin(), edges.end());
    for (std::size_t e = 0; e < 4; ++e) {
      EXPECT_NEAR(edges[e], kC, 1e-8) << "frame " << k;
      EXPECT_NEAR(edges[4 + e], kB, 1e-8) << "frame " << k;
      EXPECT_NEAR(edges[12 + e], kA, 1e-8) << "frame " << k;
    }
  }
  // The bar (body 0) sags under gravity: its points move, by the displacement written with them
  // (its frame is held at the mesh frame by the fixed joint at the clamped root).
  const Frame &a = frames.front(), &b = frames.back();
  ASSERT_EQ(a.np, b.np);
  double moved = 0;
  for (long long c = 0; c < b.nc; ++c) {
    if (b.body[static_cast<std::size_t>(c)] != 0) continue;
    for (int j = 0; j < 3; ++j) {
      const auto p = static_cast<std::size_t>(b.connectivity[static_cast<std::size_t>(3 * c + j)]);
      for (int x = 0; x < 3; ++x) {
        const double dp = b.points[3 * p + x] - a.points[3 * p + x], du = b.displacement[3 * p + x] - a.displacement[3 * p + x];
        moved = std::max(moved, std::abs(dp));
        EXPECT_NEAR(dp, du, 1e-12 + 1e-6 * std::abs(du));
      }
      EXPECT_EQ(b.has_stress[p], 1.0);
    }
  }
  std::cout << "[ vtk ] " << frames.size() << " frames, " << b.np << " points; the bar's largest point motion " << moved
            << " m; peak von Mises " << *std::max_element(b.von_mises.begin(), b.von_mises.end()) << " Pa\n";
  EXPECT_GT(moved, 1e-8);
  EXPECT_GT(*std::max_element(b.von_mises.begin(), b.von_mises.end()), 0.0);
}

TEST(VtkSeries, SidWithoutSurfaceIsRefusedBeforeTheRun) {
  if (!have_tools()) GTEST_SKIP() << "gmsh, ffr-reduce or ffr-sim missing";
  Scene run(false);
  const auto r = run.sim();
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("bar.sid.h5: /visual: body 'bar': the SID has no surface"), std::string::npos) << r.output;
  for (const char* f : {"run.pvd", "run_frames", "run.h5"}) EXPECT_FALSE(std::filesystem::exists(run.dir / f)) << f;
  for (const auto& e : std::filesystem::directory_iterator(run.dir.path()))
    EXPECT_EQ(e.path().filename().string().find(".run"), std::string::npos) << e.path();
}

// The frames folder is replaced at the end of a run, so one holding anything but frames is
// refused before the run; a collection not named .pvd likewise.
TEST(VtkSeries, ForeignFramesFolderAndWrongNameAreRefused) {
  if (!have_tools()) GTEST_SKIP() << "gmsh, ffr-reduce or ffr-sim missing";
  Scene run(true);
  std::filesystem::create_directories(run.dir / "run_frames");
  test::write_text(run.dir / "run_frames" / "notes.txt", "mine");
  auto r = run.sim();
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("holds notes.txt, which is not a frame"), std::string::npos) << r.output;
  EXPECT_TRUE(std::filesystem::exists(run.dir / "run_frames" / "notes.txt"));
  EXPECT_FALSE(std::filesystem::exists(run.dir / "run.h5"));
  r = test::run("cd " + run.dir.path().string() + " && " + test::bin("ffr-sim").string() +
                " model.json -o run.h5 --vtk run.vtu --quiet");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("must end in .pvd"), std::string::npos) << r.output;
  // Frames of an earlier run are replaced.
  std::filesystem::remove(run.dir / "run_frames" / "notes.txt");
  test::write_text(run.dir / "run_frames" / "frame_000099.vtu", "old");
  r = run.sim();
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_FALSE(std::filesystem::exists(run.dir / "run_frames" / "frame_000099.vtu"));
  EXPECT_TRUE(std::filesystem::exists(run.dir / "run_frames" / "frame_000000.vtu"));
}

// ---- rigid bodies drawn by a given STL surface; stale temporary frames folders -------------
namespace {

// A tetrahedron with corners p + {0, 0.25 e_x, 0.125 e_y, 0.5 e_z} as an ASCII STL text
// (`corrupt` 1: cut inside a facet, 2: a facet of zero area).
std::string ascii_tetrahedron(const Eigen::Vector3d& p, int corrupt = 0) {
  const Eigen::Vector3d c[4] = {p, p + Eigen::Vector3d(0.25, 0, 0), p + Eigen::Vector3d(0, 0.125, 0), p + Eigen::Vector3d(0, 0, 0.5)};
  static const int kFacets[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  std::ostringstream o;
  o.precision(17);
  o << "solid tet\n";
  for (int f = 0; f < 4; ++f) {
    o << "  facet normal 0 0 0\n    outer loop\n";
    for (int j = 0; j < 3; ++j) {
      const Eigen::Vector3d& x = c[corrupt == 2 && f == 1 && j == 2 ? 1 : kFacets[f][j]];
      o << "      vertex " << x.x() << ' ' << x.y() << ' ' << x.z() << '\n';
      if (corrupt == 1 && f == 2 && j == 1) return o.str() + "      vertex 0 0";
    }
    o << "    endloop\n  endfacet\n";
  }
  return o.str() + "endsolid tet\n";
}

// The same as a binary STL (80-byte header, facet count, 50 bytes per facet: normal, corners
// as little-endian floats, attribute count), written here apart from the reader.
std::string binary_tetrahedron(const Eigen::Vector3f& p) {
  const Eigen::Vector3f c[4] = {p, p + Eigen::Vector3f(0.25f, 0, 0), p + Eigen::Vector3f(0, 0.125f, 0), p + Eigen::Vector3f(0, 0, 0.5f)};
  static const int kFacets[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  std::string b(80, ' ');
  b.replace(0, 5, "solid");  // a binary file may begin like an ASCII one: its size decides
  const std::uint32_t n = 4;
  b.append(reinterpret_cast<const char*>(&n), 4);
  for (const auto& f : kFacets) {
    const float normal[3] = {0, 0, 0};
    b.append(reinterpret_cast<const char*>(normal), 12);
    for (int j = 0; j < 3; ++j) b.append(reinterpret_cast<const char*>(c[f[j]].data()), 12);
    b.append(2, '\0');
  }
  return b;
}

// Two free rigid bodies without gravity: "spin" turns at 2 rad/s about its principal axis z
// through its centre of mass (0.4, 0, 0), drawn by the ASCII tetrahedron; "still" rests at
// (0, 0.5, 0), drawn by the binary one.
struct RigidScene {
  test::TempDir dir{"vtk_stl"};
  explicit RigidScene(const std::string& spin_visual = "tet.stl") {
    test::write_text(dir / "tet.stl", ascii_tetrahedron(Eigen::Vector3d(0.4, 0, 0)));
    std::ofstream(dir / "tet_binary.stl", std::ios::binary) << binary_tetrahedron(Eigen::Vector3f(0, 0.5f, 0));
    test::write_text(dir / "model.json", R"({"bodies": [
      {"name": "spin", "type": "rigid", "mass": 2, "com": [0.4, 0, 0], "inertia": [[0.01, 0, 0], [0, 0.02, 0], [0, 0, 0.025]],
       "angular_velocity": [0, 0, 2], "visual": ")" + spin_visual + R"("},
      {"name": "still", "type": "rigid", "mass": 1, "com": [0, 0.5, 0], "inertia": [[0.01, 0, 0], [0, 0.01, 0], [0, 0, 0.01]],
       "visual": "tet_binary.stl"}],
      "solver": {"end": 0.5, "step": 0.001, "output_every": 50},
      "outputs": [{"name": "w", "type": "body_angular_velocity", "body": "spin"}]})");
  }
  test::RunResult sim() const {
    return test::run("cd " + dir.path().string() + " && " + test::bin("ffr-sim").string() +
                     " model.json -o run.h5 --vtk run.pvd --quiet");
  }
};

// The largest distance from each expected point to the nearest point of body `b` in the frame,
// and the number of that body's points and cells.
double distance_to(const Frame& f, double b, const std::vector<Eigen::Vector3d>& expected, std::size_t& points, long long& cells) {
  std::vector<long long> mine;
  cells = 0;
  for (long long c = 0; c < f.nc; ++c)
    if (f.body[static_cast<std::size_t>(c)] == b) {
      ++cells;
      for (int j = 0; j < 3; ++j) mine.push_back(static_cast<long long>(f.connectivity[static_cast<std::size_t>(3 * c + j)]));
    }
  std::sort(mine.begin(), mine.end());
  mine.erase(std::unique(mine.begin(), mine.end()), mine.end());
  points = mine.size();
  double worst = 0;
  for (const auto& x : expected) {
    double best = 1e300;
    for (long long p : mine) best = std::min(best, (Eigen::Vector3d(f.points[3 * p], f.points[3 * p + 1], f.points[3 * p + 2]) - x).norm());
    worst = std::max(worst, best);
  }
  return worst;
}

std::string host_tag() {
  char buf[256] = {};
  if (::gethostname(buf, sizeof buf - 1) != 0 || !buf[0]) return "host";
  std::string h;
  for (const char* c = buf; *c && h.size() < 64; ++c) h += (std::isalnum(static_cast<unsigned char>(*c)) || *c == '.' || *c == '_') ? *c : '_';
  return h;
}

}  // namespace

// Reference: rigid rotation about a principal axis through the centre of mass, x(t) = c + R_z(w t)
// (x0 - c) for the free body turning at w = 2 rad/s (Euler's equations: a principal axis is a
// steady rotation); the resting body stays at its STL corners, read back through floats exactly.
TEST(VtkSeries, RigidBodiesDrawnByTheirStlSurfaces) {
  if (!std::filesystem::exists(test::bin("ffr-sim"))) GTEST_SKIP() << "ffr-sim missing";
  RigidScene run;
  const auto r = run.sim();
  ASSERT_EQ(r.status, 0) << r.output;
  const auto pvd = Parser(formats::read_text_file(run.dir / "run.pvd")).document();
  const auto sets = pvd->child("Collection")->all("DataSet");
  ASSERT_EQ(sets.size(), 11u);
  const Eigen::Vector3d c(0.4, 0, 0);
  const Eigen::Vector3d tet[4] = {Eigen::Vector3d::Zero(), Eigen::Vector3d(0.25, 0, 0), Eigen::Vector3d(0, 0.125, 0),
                                  Eigen::Vector3d(0, 0, 0.5)};
  double worst_spin = 0, worst_still = 0;
  for (const Element* set : sets) {
    const double t = std::stod(set->attrs.at("timestep"));
    const Frame f = read_frame(run.dir / set->attrs.at("file"));
    const Eigen::Matrix3d R = Eigen::AngleAxisd(2 * t, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    std::vector<Eigen::Vector3d> spin, still;
    for (const auto& x : tet) {
      spin.push_back(c + R * x);
      still.push_back(Eigen::Vector3d(0, 0.5, 0) + x);
    }
    std::size_t points = 0;
    long long cells = 0;
    worst_spin = std::max(worst_spin, distance_to(f, 0, spin, points, cells));
    EXPECT_EQ(points, 4u);  // the corners shared by the facets merged
    EXPECT_EQ(cells, 4);
    worst_still = std::max(worst_still, distance_to(f, 1, still, points, cells));
    EXPECT_EQ(points, 4u);
    EXPECT_EQ(cells, 4);
  }
  std::cout << "[ vtk ] STL surfaces: spinning body within " << worst_spin << " m of the rigid rotation, resting body within "
            << worst_still << " m\n";
  EXPECT_LT(worst_spin, 1e-6);
  EXPECT_LT(worst_still, 1e-12);
}

TEST(VtkSeries, BadStlIsRefusedBeforeTheRun) {
  if (!std::filesystem::exists(test::bin("ffr-sim"))) GTEST_SKIP() << "ffr-sim missing";
  const std::pair<std::string, std::string> cases[] = {{"missing.stl", "missing.stl: no such file"},
                                                       {"folder.stl", "folder.stl: is a directory, not a file"},
                                                       {"cut.stl", "cut.stl: facet 2: the file ends inside the facet"},
                                                       {"flat.stl", "flat.stl: facet 1: the facet has zero area"},
                                                       {"tet.obj", "must name an STL file"}};
  for (const auto& [file, message] : cases) {
    RigidScene run(file);
    test::write_text(run.dir / "cut.stl", ascii_tetrahedron(Eigen::Vector3d::Zero(), 1));
    test::write_text(run.dir / "flat.stl", ascii_tetrahedron(Eigen::Vector3d::Zero(), 2));
    std::filesystem::create_directory(run.dir / "folder.stl");
    const auto r = run.sim();
    EXPECT_EQ(r.status, 2) << r.output;
    EXPECT_NE(r.output.find(message), std::string::npos) << r.output;
    for (const char* f : {"run.pvd", "run_frames", "run.h5"}) EXPECT_FALSE(std::filesystem::exists(run.dir / f)) << f;
  }
}

// A run killed while writing its frames leaves `.run_frames.tmp-HOST-PID-HEX`; the next run of
// the same collection removes those whose process is gone, and keeps a live process's and
// another host's (formats' rule for temporary files, stale_temp.hpp).
TEST(VtkSeries, StaleFramesFoldersOfKilledRunsAreRemoved) {
  if (!std::filesystem::exists(test::bin("ffr-sim"))) GTEST_SKIP() << "ffr-sim missing";
  RigidScene run;
  const pid_t child = ::fork();  // a process id that is certainly gone
  if (child == 0) ::_exit(0);
  ASSERT_GT(child, 0);
  ::waitpid(child, nullptr, 0);
  const std::string host = host_tag(), dead = std::to_string(child), alive = std::to_string(::getpid());
  const std::vector<std::string> stale = {".run_frames.tmp-" + host + "-" + dead + "-1a2b"};
  const std::vector<std::string> kept = {".run_frames.tmp-" + host + "-" + alive + "-1a2b",
                                         ".run_frames.tmp-otherhost-" + dead + "-1a2b", ".other_frames.tmp-" + host + "-" + dead + "-1"};
  for (const auto& d : stale) {
    std::filesystem::create_directories(run.dir / d);
    test::write_text(run.dir / d / "frame_000000.vtu", "half a frame");
  }
  for (const auto& d : kept) std::filesystem::create_directories(run.dir / d);
  test::write_text(run.dir / (".run.pvd.tmp-" + host + "-" + dead + "-ff"), "half a collection");
  const auto r = run.sim();
  ASSERT_EQ(r.status, 0) << r.output;
  for (const auto& d : stale) EXPECT_FALSE(std::filesystem::exists(run.dir / d)) << d;
  EXPECT_FALSE(std::filesystem::exists(run.dir / (".run.pvd.tmp-" + host + "-" + dead + "-ff")));
  for (const auto& d : kept) EXPECT_TRUE(std::filesystem::exists(run.dir / d)) << d;
  EXPECT_TRUE(std::filesystem::exists(run.dir / "run_frames" / "frame_000010.vtu"));
  // Nothing of this run's own is left behind.
  for (const auto& e : std::filesystem::directory_iterator(run.dir.path())) {
    const std::string name = e.path().filename().string();
    if (name.rfind(".run", 0) == 0) EXPECT_NE(std::find(kept.begin(), kept.end(), name), kept.end()) << name;
  }
}

// A shell body: every vertex of its surface is a stress node with three layers (top, middle,
// bottom), and the frame shows the largest of their von Mises stresses, the same as
// `ffr-info --stress --json` gives for the run's last sample.
TEST(VtkSeries, ShellVerticesShowTheirLargestLayer) {
  if (!have_tools() || !std::filesystem::exists(test::bin("ffr-info"))) GTEST_SKIP() << "tools missing";
  test::TempDir dir("vtk_shell");
  test::write_text(dir / "s.geo", R"(SetFactory("OpenCASCADE");
Rectangle(1) = {0, 0, 0, 0.2, 0.02};
Physical Surface("strip") = {1};
Physical Curve("clamp") = Curve In BoundingBox{-1e-6, -1, -1, 1e-6, 1, 1};
Recombine Surface{1};
)");
  test::gmsh_mesh(dir / "s.geo", dir / "s.msh", 0.005, 1);
  test::write_text(dir / "s.json", R"({"geometry": "s.msh",
    "shells": [{"group": "strip", "thickness": 0.002, "E": 2.1e11, "nu": 0.3, "rho": 7850}],
    "interfaces": [{"name": "root", "group": "clamp"}],
    "reduction": {"method": "clamped", "interface": "root", "modes": 4}, "stress": {"surface": true}})");
  auto r = test::run(test::bin("ffr-reduce").string() + " " + (dir / "s.json").string() + " -o " +
                     (dir / "s.sid.h5").string() + " --quiet");
  ASSERT_EQ(r.status, 0) << r.output;
  test::write_text(dir / "model.json", R"({"gravity": [0, 0, -9.81],
    "bodies": [{"name": "strip", "type": "flexible", "sid": "s.sid.h5"}],
    "joints": [{"name": "clamp", "type": "fixed", "body1": "ground", "body2": "strip", "node2": "root"}],
    "solver": {"end": 0.01, "step": 0.001}, "outputs": [{"name": "q", "type": "modal_coordinates", "body": "strip"}]})");
  r = test::run("cd " + dir.path().string() + " && " + test::bin("ffr-sim").string() + " model.json -o run.h5 --vtk run.pvd --quiet");
  ASSERT_EQ(r.status, 0) << r.output;
  r = test::run("cd " + dir.path().string() + " && " + test::bin("ffr-info").string() + " run.h5 --stress strip --json");
  ASSERT_EQ(r.status, 0) << r.output;
  const auto j = nlohmann::json::parse(r.output);
  std::map<std::array<double, 3>, std::vector<double>> layers;  // position -> last-sample von Mises of its rows
  for (const auto& n : j["nodes"])
    layers[{n["position"][0].get<double>(), n["position"][1].get<double>(), n["position"][2].get<double>()}].push_back(
        n["von_mises"].back().get<double>());
  const formats::Sid sid = formats::read_sid(dir / "s.sid.h5");
  const auto pvd = Parser(formats::read_text_file(dir / "run.pvd")).document();
  const auto sets = pvd->child("Collection")->all("DataSet");
  ASSERT_FALSE(sets.empty());
  const Frame f = read_frame(dir / sets.back()->attrs.at("file"));
  ASSERT_EQ(f.np, sid.visual.vertices.rows());
  double worst = 0, peak = 0;
  for (long long p = 0; p < f.np; ++p) {
    const auto it = layers.find({sid.visual.vertices(p, 0), sid.visual.vertices(p, 1), sid.visual.vertices(p, 2)});
    ASSERT_NE(it, layers.end()) << "vertex " << p << " is not a stress node";
    ASSERT_EQ(it->second.size(), 3u);
    EXPECT_EQ(f.has_stress[static_cast<std::size_t>(p)], 1.0);
    const double want = *std::max_element(it->second.begin(), it->second.end());
    peak = std::max(peak, want);
    worst = std::max(worst, std::abs(f.von_mises[static_cast<std::size_t>(p)] - want));
  }
  std::cout << "[ vtk ] shell strip: " << f.np << " vertices, peak von Mises " << peak
            << " Pa, max |frame - max over layers| " << worst << " Pa\n";
  EXPECT_GT(peak, 1e5);
  EXPECT_LT(worst, 1e-6 * peak);
}
