// ffr-sim --vtk RUN.pvd: every file parses as XML (a strict parser written here, apart from the
// writer) with the VTK structure ParaView reads (sizes, index ranges, one frame per output
// sample at its time); the flexible body's points move, by exactly the displacement written
// with them; a rigid body is drawn as its inertia box, checked against the box formula
// I_xx = m (b^2 + c^2) / 12 (a box of sides 0.3 x 0.1 x 0.05 m given by its inertia comes back
// with those sides, centred on the centre of mass the run reports); a SID without a surface is
// refused before the run with nothing written.
#include "ffr/formats/results_io.hpp"
#include "ffr/formats/text_file.hpp"
#include "support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
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
