#include "support.hpp"

#include "ffr/calculix/deck.hpp"
#include "ffr/formats/text_file.hpp"

#include <array>
#include <cstdio>
#include <fstream>
#include <random>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <unistd.h>

namespace ffr::test {

TempDir::TempDir(const std::string& tag) {
  std::random_device rd;
  path_ = std::filesystem::temp_directory_path() / ("ffr_" + tag + "_" + std::to_string(::getpid()) + "_" + std::to_string(rd() % 100000));
  std::filesystem::create_directories(path_);
}

TempDir::~TempDir() {
  std::error_code ec;
  if (!std::getenv("FFR_KEEP_TEST_FILES")) std::filesystem::remove_all(path_, ec);
}

RunResult run(const std::string& command) {
  RunResult r;
  std::FILE* p = ::popen((command + " 2>&1").c_str(), "r");
  if (!p) return r;
  std::array<char, 4096> buf;
  while (std::fgets(buf.data(), buf.size(), p)) r.output += buf.data();
  const int st = ::pclose(p);
  r.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  return r;
}

std::filesystem::path bin(const std::string& tool) { return std::filesystem::path(FFR_BINARY_DIR) / "bin" / tool; }
std::filesystem::path source(const std::string& rel) { return std::filesystem::path(FFR_SOURCE_DIR) / rel; }

preproc::ReductionSpec clamped_spec(const std::string& interface, int modes) {
  preproc::ReductionSpec s;
  s.method = preproc::ReductionSpec::Method::Clamped;
  s.interface = interface;
  s.modes = modes;
  return s;
}

preproc::ReductionSpec free_free_spec(int modes) {
  preproc::ReductionSpec s;
  s.method = preproc::ReductionSpec::Method::Free;
  s.modes = modes;
  return s;
}

preproc::ReductionSpec craig_bampton_spec(int modes) {
  preproc::ReductionSpec s;
  s.method = preproc::ReductionSpec::Method::CraigBampton;
  s.interfaces = {"L", "R"};
  s.frame = "L";
  s.modes = modes;
  return s;
}

HexGrid::HexGrid(int nx, int ny, int nz) {
  using preproc::Index;
  auto id = [&](int i, int j, int k) { return (k * (ny + 1) + j) * (nx + 1) + i; };
  mesh.x.resize((nx + 1) * (ny + 1) * (nz + 1), 3);
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) mesh.x.row(id(i, j, k)) << i + 0.1 * j, j + 0.05 * k, k + 0.02 * i;
  preproc::ElementBlock b{preproc::ElementType::Hex8, "body", {}, {}};
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        for (int v : {id(i, j, k), id(i + 1, j, k), id(i + 1, j + 1, k), id(i, j + 1, k), id(i, j, k + 1),
                      id(i + 1, j, k + 1), id(i + 1, j + 1, k + 1), id(i, j + 1, k + 1)})
          b.conn.push_back(v);
  mesh.blocks.push_back(b);
  std::vector<Index> all, left, right;
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j) {
      left.push_back(id(0, j, k));
      right.push_back(id(nx, j, k));
    }
  for (Index n = 0; n < mesh.x.rows(); ++n) all.push_back(n);
  mesh.node_groups["body"] = all;
  mesh.node_groups["left"] = left;
  mesh.node_groups["right"] = right;
  part.file = "grid.json";
  part.materials.push_back({"body", {2.1e11, 0.3, 7850.0}});
  part.interfaces.push_back({"L", "left", "rigid", {}});
  part.interfaces.push_back({"R", "right", "averaged", {}});
}

void write_text(const std::filesystem::path& p, const std::string& text) {
  std::ofstream f(p);
  f << text;
  if (!f) throw std::runtime_error("cannot write " + p.string());
}

void gmsh_mesh(const std::filesystem::path& geo, const std::filesystem::path& msh, double size, int order) {
  std::ostringstream cmd;
  cmd << "gmsh -3 -order " << order << " -setnumber Mesh.SecondOrderIncomplete 1 -clmax " << size << " -format msh41 "
      << geo << " -o " << msh;
  const auto r = run(cmd.str());
  if (r.status != 0 || !std::filesystem::exists(msh)) throw std::runtime_error("gmsh failed: " + r.output);
}

CcxModes run_ccx(const std::filesystem::path& workdir);

CcxModes calculix_frequency(const preproc::Mesh& mesh, const preproc::Material& mat, const std::string& group,
                            const std::string& fixed_group, int modes, const std::filesystem::path& workdir) {
  calculix::write_frequency_deck(mesh, group, fixed_group, {mat.E, mat.nu, mat.rho}, modes, workdir / "job.inp");
  return run_ccx(workdir);
}

CcxModes calculix_frequency_structural(const preproc::Mesh& mesh, const preproc::Material& mat, const std::string& group,
                                       const CcxSection& section, const std::string& fixed_group, int modes,
                                       const std::filesystem::path& workdir) {
  std::ofstream f(workdir / "job.inp");
  calculix::write_nodes(f, mesh);
  std::size_t eid = 1;
  for (const auto& b : mesh.blocks) {
    if (b.group != group) continue;
    const char* type = b.type == preproc::ElementType::Quad4 ? "S4"
                       : b.type == preproc::ElementType::Tri3 ? "S3"
                       : b.type == preproc::ElementType::Line2 ? "B31" : nullptr;
    if (!type) throw std::invalid_argument(std::string("no CalculiX counterpart for ") + preproc::name(b.type));
    f << "*ELEMENT, TYPE=" << type << ", ELSET=EALL\n";
    for (preproc::Index e = 0; e < b.size(); ++e) {
      f << eid++;
      for (int i = 0; i < preproc::num_nodes(b.type); ++i) f << ", " << b.element(e)[i] + 1;
      f << "\n";
    }
  }
  f << "*NSET, NSET=FIX\n";
  int k = 0;
  for (auto n : mesh.node_groups.at(fixed_group)) f << n + 1 << (++k % 10 == 0 ? ",\n" : ", ");
  f << "\n*BOUNDARY\nFIX, 1, 6\n";
  f << "*MATERIAL, NAME=MAT\n*ELASTIC\n" << mat.E << ", " << mat.nu << "\n*DENSITY\n" << mat.rho << "\n";
  if (section.kind == "shell") {
    f << "*SHELL SECTION, ELSET=EALL, MATERIAL=MAT\n" << section.thickness << "\n";
  } else {
    f << "*BEAM SECTION, ELSET=EALL, MATERIAL=MAT, SECTION=RECT\n" << section.b << ", " << section.h << "\n"
      << section.n1.x() << ", " << section.n1.y() << ", " << section.n1.z() << "\n";
  }
  f << "*STEP\n*FREQUENCY\n" << modes << "\n*END STEP\n";
  f.close();
  return run_ccx(workdir);
}

CcxModes run_ccx(const std::filesystem::path& workdir) {
  const auto r = run("cd " + workdir.string() + " && OMP_NUM_THREADS=1 ccx -i job");
  const std::string text = std::filesystem::exists(workdir / "job.dat") ? formats::read_text_file(workdir / "job.dat") : "";
  if (r.status != 0 || text.find("E I G E N V A L U E") == std::string::npos)
    throw std::runtime_error("ccx failed: " + r.output.substr(0, 2000));
  CcxModes out;
  out.frequency_hz = calculix::frequencies(text);
  const auto pf = calculix::read_table(text, calculix::kParticipationTable, 6);
  out.participation.resize(static_cast<Eigen::Index>(pf.size()), 6);
  for (std::size_t i = 0; i < pf.size(); ++i)
    for (int j = 0; j < 6; ++j) out.participation(static_cast<Eigen::Index>(i), j) = pf[i][static_cast<std::size_t>(j)];
  return out;
}

}  // namespace ffr::test
