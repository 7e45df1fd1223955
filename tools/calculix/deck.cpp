#include "ffr/calculix/deck.hpp"

#include "ffr/formats/text_file.hpp"

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

void write_nodes(std::ostream& f, const preproc::Mesh& mesh) {
  f.precision(17);
  f << "*NODE, NSET=NALL\n";
  for (preproc::Index n = 0; n < mesh.num_nodes(); ++n)
    f << n + 1 << ", " << mesh.x(n, 0) << ", " << mesh.x(n, 1) << ", " << mesh.x(n, 2) << "\n";
}

void write_frequency_deck(const preproc::Mesh& mesh, const std::string& group, const std::string& fixed_group,
                          const IsoMaterial& mat, int modes, const std::filesystem::path& inp) {
  // Checked first, so that no deck is left behind for a run that cannot be set up.
  bool any = false;
  for (const auto& b : mesh.blocks) any = any || (preproc::dimension(b.type) == 3 && b.group == group && b.size() > 0);
  if (!any) throw std::runtime_error("CalculiX deck: no 3D elements in group '" + group + "'");
  const auto fixed = fixed_group.empty() ? mesh.node_groups.end() : mesh.node_groups.find(fixed_group);
  if (!fixed_group.empty() && (fixed == mesh.node_groups.end() || fixed->second.empty()))
    throw std::runtime_error("CalculiX deck: no node group '" + fixed_group + "'");

  std::ofstream f(inp);
  if (!f) throw std::runtime_error("cannot write " + inp.string());
  f << "** written by ffr (tools/calculix) from the mesh ffr-reduce reads\n";
  write_nodes(f, mesh);
  long long eid = 1;
  for (const auto& b : mesh.blocks) {
    if (preproc::dimension(b.type) != 3 || b.group != group) continue;
    const DeckType t = deck_type(b.type);
    f << "*ELEMENT, TYPE=" << t.name << ", ELSET=EALL\n";
    for (preproc::Index e = 0; e < b.size(); ++e) {
      f << eid++;
      for (std::size_t i = 0; i < t.order.size(); ++i) f << (i % 12 == 11 ? ",\n" : ", ") << b.element(e)[t.order[i]] + 1;
      f << "\n";
    }
  }
  if (fixed != mesh.node_groups.end()) {
    f << "*NSET, NSET=FIX\n";
    int k = 0;
    for (const auto n : fixed->second) f << n + 1 << (++k % 10 == 0 ? ",\n" : ", ");
    f << "\n*BOUNDARY\nFIX, 1, 3\n";
  }
  f << "*MATERIAL, NAME=MAT\n*ELASTIC\n" << mat.E << ", " << mat.nu << "\n*DENSITY\n" << mat.rho << "\n";
  f << "*SOLID SECTION, ELSET=EALL, MATERIAL=MAT\n*STEP\n*FREQUENCY\n" << modes << "\n*END STEP\n";
  f.close();
  if (!f) throw std::runtime_error("cannot write " + inp.string());
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

std::vector<double> frequencies(const std::string& dat_text) {
  // Rows: mode, eigenvalue, omega [rad/time], frequency [cycles/time], imaginary part.
  std::vector<double> hz;
  for (const auto& row : read_table(dat_text, kEigenvalueTable, 4)) hz.push_back(row[2]);
  return hz;
}

std::vector<double> read_frequencies(const std::filesystem::path& dat) {
  std::error_code ec;
  if (!std::filesystem::exists(dat, ec)) return {};
  return frequencies(formats::read_text_file(dat));
}

}  // namespace ffr::calculix
