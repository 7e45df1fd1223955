#pragma once
// The mesh of an FE input deck (Abaqus/CalculiX .inp, Nastran bulk data), as its reader
// collects it, made into the Mesh gmsh_import gives: the readers share the numbering of the
// nodes, the blocks per group and element type, the group "all" and the checks of ids.
#include "ffr/preproc/mesh/gmsh_import.hpp"

#include <chrono>
#include <string>
#include <vector>

namespace ffr::preproc::detail {

/// A property of an element set of the deck (an Abaqus *SOLID/*SHELL SECTION, a Nastran
/// PSOLID/PSHELL/PBAR) resolved to its material: the part file's materials/shells/beams entry
/// it stands for where the part file gives none for the set.
struct DeckSection {
  enum class Kind { Solid, Shell, Beam };
  Kind kind = Kind::Solid;
  std::string group;      ///< the element set, as the mesh names its group
  Material mat;
  double thickness = 0;   ///< shells
  BeamProps beam;         ///< beams (group and mat as above)
  std::string where;      ///< "line N (...)" for messages
  std::string problem;    ///< why the deck's property cannot be taken (then only `where` is set)
};

/// The most members the sets of one deck may hold in all (ids as listed, repeats and the
/// members a set takes from another set counted). Each range (GENERATE, THRU) is bounded by the
/// ids the deck can define, but lists may repeat them, and a set named in another's data lines
/// adds all its members each time (a line can double a set), so a few kilobytes could otherwise
/// ask for more memory than the machine has. 5e7 is 400 MB of ids, far beyond a 1M-DOF mesh's sets.
inline constexpr std::size_t kMaxDeckSetMembers = 50'000'000;

struct DeckMesh {
  std::string file;
  std::vector<std::size_t> node_ids;
  std::vector<double> xyz;  ///< 3 per node
  std::vector<int> node_lines;

  struct Element {
    std::size_t id;
    ElementType type;
    std::size_t first;  ///< into conn: the element's node ids, gmsh order
    int line;
    Hex8Formulation hex8 = Hex8Formulation::Incompatible;  ///< HEX8: C3D8I or C3D8
  };
  std::vector<Element> elements;
  std::vector<std::size_t> conn;

  struct Set {
    std::string name;   ///< the group's name
    std::vector<std::size_t> ids;
    std::string where;  ///< "line N (...)" for messages
  };
  std::vector<Set> element_sets, node_sets;  ///< in definition order
  /// Whether a set named "all" (any case) exists: then no group "all" is added.
  bool has_all = false;
};

/// The Mesh of the deck: nodes numbered as gmsh_import numbers them (node_order.hpp), one
/// block per element set and element type (in the order the types first occur in the set; the
/// two HEX8 formulations are two types here),
/// then the group "all" of every element of the highest dimension unless has_all, and a node
/// group per element set (its elements' nodes) and node set (joined with a group of the same
/// name). Throws formats::FormatError naming the file and line of an id defined twice or used
/// but not defined, and of a deck without nodes or elements.
Mesh build_deck_mesh(const DeckMesh& deck, MeshReport* report, std::chrono::steady_clock::time_point start);

}  // namespace ffr::preproc::detail
