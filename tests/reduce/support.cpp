#include "support.hpp"

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

namespace {

// CalculiX element name and node order (Abaqus convention) from gmsh's order.
struct CcxType {
  const char* name;
  std::vector<int> order;  // ccx node i = gmsh node order[i]
};

CcxType ccx_type(preproc::ElementType t) {
  using preproc::ElementType;
  switch (t) {
    case ElementType::Tet4: return {"C3D4", {0, 1, 2, 3}};
    // gmsh: 4(0,1) 5(1,2) 6(2,0) 7(3,0) 8(3,2) 9(3,1); Abaqus: 5(1,2) 6(2,3) 7(3,1) 8(1,4) 9(2,4) 10(3,4)
    case ElementType::Tet10: return {"C3D10", {0, 1, 2, 3, 4, 5, 6, 7, 9, 8}};
    case ElementType::Hex8: return {"C3D8", {0, 1, 2, 3, 4, 5, 6, 7}};
    // gmsh edges: 8(0,1) 9(0,3) 10(0,4) 11(1,2) 12(1,5) 13(2,3) 14(2,6) 15(3,7) 16(4,5) 17(4,7) 18(5,6) 19(6,7)
    // Abaqus: 9(1,2) 10(2,3) 11(3,4) 12(4,1) 13(5,6) 14(6,7) 15(7,8) 16(8,5) 17(1,5) 18(2,6) 19(3,7) 20(4,8)
    case ElementType::Hex20: return {"C3D20", {0, 1, 2, 3, 4, 5, 6, 7, 8, 11, 13, 9, 16, 18, 19, 17, 10, 12, 14, 15}};
    default: throw std::invalid_argument(std::string("no CalculiX counterpart for ") + preproc::name(t));
  }
}

std::vector<std::vector<double>> table_after(const std::string& text, const std::string& title, int columns) {
  std::vector<std::vector<double>> rows;
  const auto pos = text.find(title);
  if (pos == std::string::npos) return rows;
  std::istringstream in(text.substr(pos + title.size()));
  std::string line;
  bool started = false;
  while (std::getline(in, line)) {
    std::istringstream ls(line);
    std::vector<double> v;
    double x;
    while (ls >> x) v.push_back(x);
    if (static_cast<int>(v.size()) == columns + 1) {
      started = true;
      rows.push_back(std::vector<double>(v.begin() + 1, v.end()));
    } else if (started) {
      break;
    }
  }
  return rows;
}

}  // namespace

CcxModes run_ccx(const std::filesystem::path& workdir);

void write_nodes(std::ostream& f, const preproc::Mesh& mesh) {
  f << "*NODE\n";
  for (preproc::Index n = 0; n < mesh.num_nodes(); ++n)
    f << n + 1 << ", " << mesh.x(n, 0) << ", " << mesh.x(n, 1) << ", " << mesh.x(n, 2) << "\n";
}

CcxModes calculix_frequency(const preproc::Mesh& mesh, const preproc::Material& mat, const std::string& group,
                            const std::string& fixed_group, int modes, const std::filesystem::path& workdir) {
  std::ofstream f(workdir / "job.inp");
  f.precision(17);
  write_nodes(f, mesh);
  std::size_t eid = 1;
  for (const auto& b : mesh.blocks) {
    if (preproc::dimension(b.type) != 3 || b.group != group) continue;  // each element once
    const auto t = ccx_type(b.type);
    f << "*ELEMENT, TYPE=" << t.name << ", ELSET=EALL\n";
    for (preproc::Index e = 0; e < b.size(); ++e) {
      f << eid++;
      for (std::size_t i = 0; i < t.order.size(); ++i) f << (i % 12 == 11 ? ",\n" : ", ") << b.element(e)[t.order[i]] + 1;
      f << "\n";
    }
  }
  if (!fixed_group.empty()) {
    f << "*NSET, NSET=FIX\n";
    int k = 0;
    for (auto n : mesh.node_groups.at(fixed_group)) f << n + 1 << (++k % 10 == 0 ? ",\n" : ", ");
    f << "\n*BOUNDARY\nFIX, 1, 3\n";
  }
  f << "*MATERIAL, NAME=MAT\n*ELASTIC\n" << mat.E << ", " << mat.nu << "\n*DENSITY\n" << mat.rho << "\n";
  f << "*SOLID SECTION, ELSET=EALL, MATERIAL=MAT\n*STEP\n*FREQUENCY\n" << modes << "\n*END STEP\n";
  f.close();
  return run_ccx(workdir);
}

CcxModes calculix_frequency_structural(const preproc::Mesh& mesh, const preproc::Material& mat, const std::string& group,
                                       const CcxSection& section, const std::string& fixed_group, int modes,
                                       const std::filesystem::path& workdir) {
  std::ofstream f(workdir / "job.inp");
  f.precision(17);
  write_nodes(f, mesh);
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
  std::ifstream dat(workdir / "job.dat");
  std::stringstream ss;
  ss << dat.rdbuf();
  const std::string text = ss.str();
  if (r.status != 0 || text.find("E I G E N V A L U E") == std::string::npos)
    throw std::runtime_error("ccx failed: " + r.output.substr(0, 2000));
  CcxModes out;
  for (const auto& row : table_after(text, "E I G E N V A L U E   O U T P U T", 4)) out.frequency_hz.push_back(row[2]);
  const auto pf = table_after(text, "P A R T I C I P A T I O N   F A C T O R S", 6);
  out.participation.resize(static_cast<Eigen::Index>(pf.size()), 6);
  for (std::size_t i = 0; i < pf.size(); ++i)
    for (int j = 0; j < 6; ++j) out.participation(static_cast<Eigen::Index>(i), j) = pf[i][static_cast<std::size_t>(j)];
  return out;
}

}  // namespace ffr::test
