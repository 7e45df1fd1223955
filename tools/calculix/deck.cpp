#include "ffr/calculix/deck.hpp"

#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace ffr::calculix {
namespace {

struct DeckType {
  const char* name;
  std::vector<int> order;  // ccx node i = gmsh node order[i]
};

// Abaqus/CalculiX node order from gmsh's (both documented in their manuals' element tables).
DeckType deck_type(preproc::ElementType t) {
  using preproc::ElementType;
  switch (t) {
    case ElementType::Tet4: return {"C3D4", {0, 1, 2, 3}};
    // The two codes agree on the corners and the base edges; the edges to the apex differ:
    // gmsh 8 = (3,2), 9 = (3,1) but Abaqus 9 = (2,4), 10 = (3,4) (1-based).
    case ElementType::Tet10: return {"C3D10", {0, 1, 2, 3, 4, 5, 6, 7, 9, 8}};
    case ElementType::Hex8: return {"C3D8", {0, 1, 2, 3, 4, 5, 6, 7}};
    // gmsh numbers the edges by their first corner, Abaqus runs round the bottom face, the
    // top face, then the vertical edges.
    case ElementType::Hex20: return {"C3D20", {0, 1, 2, 3, 4, 5, 6, 7, 8, 11, 13, 9, 16, 18, 19, 17, 10, 12, 14, 15}};
    default: throw std::invalid_argument(std::string("no CalculiX element for ") + preproc::name(t));
  }
}

}  // namespace

void write_frequency_deck(const preproc::Mesh& mesh, const std::string& group, const std::string& fixed_group,
                          const IsoMaterial& mat, int modes, const std::filesystem::path& inp) {
  std::FILE* f = std::fopen(inp.c_str(), "w");
  if (!f) throw std::runtime_error("cannot write " + inp.string());
  std::fprintf(f, "** written by ffr (tools/calculix) from the mesh ffr-reduce reads\n*NODE, NSET=NALL\n");
  for (preproc::Index n = 0; n < mesh.num_nodes(); ++n)
    std::fprintf(f, "%lld, %.17g, %.17g, %.17g\n", static_cast<long long>(n + 1), mesh.x(n, 0), mesh.x(n, 1), mesh.x(n, 2));
  long long eid = 1;
  for (const auto& b : mesh.blocks) {
    if (preproc::dimension(b.type) != 3 || b.group != group) continue;
    const DeckType t = deck_type(b.type);
    std::fprintf(f, "*ELEMENT, TYPE=%s, ELSET=EALL\n", t.name);
    for (preproc::Index e = 0; e < b.size(); ++e) {
      std::fprintf(f, "%lld", eid++);
      for (std::size_t i = 0; i < t.order.size(); ++i)
        std::fprintf(f, "%s%lld", i % 12 == 11 ? ",\n" : ", ", static_cast<long long>(b.element(e)[t.order[i]] + 1));
      std::fprintf(f, "\n");
    }
  }
  if (eid == 1) {
    std::fclose(f);
    throw std::runtime_error("CalculiX deck: no 3D elements in group '" + group + "'");
  }
  if (!fixed_group.empty()) {
    const auto it = mesh.node_groups.find(fixed_group);
    if (it == mesh.node_groups.end() || it->second.empty()) {
      std::fclose(f);
      throw std::runtime_error("CalculiX deck: no node group '" + fixed_group + "'");
    }
    std::fprintf(f, "*NSET, NSET=FIX\n");
    int k = 0;
    for (const auto n : it->second) std::fprintf(f, "%lld%s", static_cast<long long>(n + 1), ++k % 10 == 0 ? ",\n" : ", ");
    std::fprintf(f, "\n*BOUNDARY\nFIX, 1, 3\n");
  }
  std::fprintf(f, "*MATERIAL, NAME=MAT\n*ELASTIC\n%.17g, %.17g\n*DENSITY\n%.17g\n", mat.E, mat.nu, mat.rho);
  std::fprintf(f, "*SOLID SECTION, ELSET=EALL, MATERIAL=MAT\n*STEP\n*FREQUENCY\n%d\n*END STEP\n", modes);
  if (std::fclose(f) != 0) throw std::runtime_error("cannot write " + inp.string());
}

std::vector<std::vector<double>> read_table(const std::string& text, const std::string& title, int columns) {
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

std::vector<double> read_frequencies(const std::filesystem::path& dat) {
  std::ifstream f(dat);
  std::stringstream text;
  text << f.rdbuf();
  // Rows: mode, eigenvalue, omega [rad/time], frequency [cycles/time], imaginary part.
  std::vector<double> hz;
  for (const auto& row : read_table(text.str(), kEigenvalueTable, 4)) hz.push_back(row[2]);
  return hz;
}

}  // namespace ffr::calculix
