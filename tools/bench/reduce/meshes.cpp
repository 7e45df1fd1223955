#include "meshes.hpp"

#include "child_process.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

namespace ffr::bench {
namespace fs = std::filesystem;
namespace {

constexpr const char* kPlateGeo = R"(// Thick steel plate with four through holes, clamped on the face x = 0 (reduce_bench).
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 0.24, 0.12, 0.03};
Cylinder(2) = {0.07, 0.06, -0.01, 0, 0, 0.05, 0.025};
Cylinder(3) = {0.15, 0.04, -0.01, 0, 0, 0.05, 0.015};
Cylinder(4) = {0.15, 0.09, -0.01, 0, 0, 0.05, 0.012};
Cylinder(5) = {0.21, 0.06, -0.01, 0, 0, 0.05, 0.01};
BooleanDifference(10) = { Volume{1}; Delete; }{ Volume{2, 3, 4, 5}; Delete; };
Physical Volume("body") = {10};
Physical Surface("clamp") = Surface In BoundingBox{-1e-6, -1, -1, 1e-6, 1, 1};
)";

// Tube along x: four quarter circles extruded in nl layers, recombined into quads.
std::string tube_geo(int nc, int nl) {
  std::ostringstream g;
  g << "// Thin-walled tube R = 0.1 m, L = 1 m, structured QUAD4 grid, clamped ring at x = 0 (reduce_bench).\n"
    << "R = 0.1; L = 1.0; nc = " << nc << "; nl = " << nl << ";\n"
    << R"(Point(1) = {0, 0, 0};
Point(2) = {0, R, 0}; Point(3) = {0, 0, R}; Point(4) = {0, -R, 0}; Point(5) = {0, 0, -R};
Circle(1) = {2, 1, 3}; Circle(2) = {3, 1, 4}; Circle(3) = {4, 1, 5}; Circle(4) = {5, 1, 2};
Transfinite Curve{1, 2, 3, 4} = nc + 1;
out[] = Extrude{L, 0, 0}{ Curve{1, 2, 3, 4}; Layers{nl}; Recombine; };
Physical Surface("skin") = {out[1], out[5], out[9], out[13]};
Physical Curve("clamp") = {1, 2, 3, 4};
)";
  return g.str();
}

void write_file(const fs::path& p, const std::string& text) {
  std::ofstream f(p);
  f << text;
  if (!f) throw std::runtime_error("cannot write " + p.string());
}

// Runs the gmsh command line; returns its wall time.
double gmsh(const std::vector<std::string>& args, const fs::path& workdir, const fs::path& msh) {
  ChildSpec s;
  s.argv = {"gmsh"};
  s.argv.insert(s.argv.end(), args.begin(), args.end());
  s.cwd = workdir;
  s.out = workdir / "gmsh.log";
  s.err = workdir / "gmsh.err";
  fs::remove(workdir / msh);
  const ChildResult r = run_child(s);
  if (!r.ok() || !fs::exists(workdir / msh))
    throw std::runtime_error("gmsh failed (see " + (workdir / "gmsh.log").string() + ")");
  return r.wall_s;
}

std::string tag_of(std::int64_t dof) {
  return dof % 1000 == 0 ? std::to_string(dof / 1000) + "k" : std::to_string(dof);
}

}  // namespace

std::int64_t msh_node_count(const fs::path& msh) {
  std::ifstream f(msh);
  std::string line;
  while (std::getline(f, line))
    if (line == "$Nodes") {
      std::int64_t blocks = 0, nodes = 0;
      f >> blocks >> nodes;
      return nodes;
    }
  throw std::runtime_error(msh.string() + ": no $Nodes section");
}

MeshCase plate_mesh(const fs::path& workdir, std::int64_t target_dof) {
  MeshCase m;
  const std::string stem = "plate_" + tag_of(target_dof);
  m.msh = workdir / (stem + ".msh");
  const fs::path sizefile = workdir / (stem + ".size");
  if (fs::exists(m.msh) && fs::exists(sizefile)) {
    std::ifstream(sizefile) >> m.size;
    m.nodes = msh_node_count(m.msh);
    m.dof = 3 * m.nodes;
    m.reused = true;
    return m;
  }
  write_file(workdir / "plate.geo", kPlateGeo);
  // DOF ~ 99e3 (5.8 mm / h)^2.77, fitted on this geometry (gmsh 4.8, default algorithms);
  // then corrected from the measured count with the same exponent.
  constexpr double kExp = 2.77;
  double h = 0.0058 * std::pow(99.0e3 / static_cast<double>(target_dof), 1.0 / kExp);
  for (int attempt = 0; attempt < 4; ++attempt) {
    std::ostringstream hs;
    hs.precision(6);
    hs << h;
    m.mesh_seconds += gmsh({"-3", "-order", "2", "-clmax", hs.str(), "-format", "msh41", "plate.geo", "-o",
                            m.msh.filename().string()},
                           workdir, m.msh.filename());
    m.nodes = msh_node_count(m.msh);
    m.dof = 3 * m.nodes;
    m.size = h;
    const double ratio = static_cast<double>(m.dof) / static_cast<double>(target_dof);
    if (std::abs(ratio - 1.0) < 0.04) break;
    h *= std::pow(ratio, 1.0 / kExp);
  }
  std::ofstream(sizefile) << m.size << "\n";
  return m;
}

MeshCase tube_mesh(const fs::path& workdir, std::int64_t target_dof) {
  MeshCase m;
  // nodes = 4 nc (nl + 1) with square elements: nl = 4 nc L / (2 pi R).
  const double nodes = static_cast<double>(target_dof) / 6.0;
  const double ratio = 1.0 / (2 * M_PI * 0.1);
  const int nc = std::max(2, static_cast<int>(std::lround(std::sqrt(nodes / (16 * ratio)))));
  const int nl = std::max(2, static_cast<int>(std::lround(nodes / (4.0 * nc)) - 1));
  const std::string stem = "tube_" + std::to_string(4 * nc) + "x" + std::to_string(nl);
  m.msh = workdir / (stem + ".msh");
  m.size = 4 * nc;
  if (fs::exists(m.msh)) {
    m.reused = true;
  } else {
    write_file(workdir / (stem + ".geo"), tube_geo(nc, nl));
    m.mesh_seconds = gmsh({"-2", "-format", "msh41", stem + ".geo", "-o", m.msh.filename().string()}, workdir,
                          m.msh.filename());
  }
  m.nodes = msh_node_count(m.msh);
  m.dof = 6 * m.nodes;
  return m;
}

}  // namespace ffr::bench
