#include "msh41_reader.hpp"

#include "node_order.hpp"
#include "../stopwatch.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <chrono>
#include <fstream>
#include <map>
#include <sstream>
#include <string_view>
#include <unordered_map>

namespace ffr::preproc::detail {
namespace {

// Whitespace-separated tokens of the file, one line at a time where the format needs it.
class Cursor {
 public:
  explicit Cursor(std::string_view s) : p_(s.data()), end_(s.data() + s.size()) {}
  bool token(std::string_view& t) {
    while (p_ < end_ && is_space(*p_)) ++p_;
    const char* b = p_;
    while (p_ < end_ && !is_space(*p_)) ++p_;
    t = std::string_view(b, static_cast<std::size_t>(p_ - b));
    return !t.empty();
  }
  template <class T>
  bool num(T& v) {
    std::string_view t;
    if (!token(t)) return false;
    const auto r = std::from_chars(t.data(), t.data() + t.size(), v);
    return r.ec == std::errc() && r.ptr == t.data() + t.size();
  }
  // The rest of the current line (after what was read), without its end.
  std::string_view rest_of_line() {
    const char* b = p_;
    while (p_ < end_ && *p_ != '\n') ++p_;
    std::string_view l(b, static_cast<std::size_t>(p_ - b));
    if (p_ < end_) ++p_;
    return l;
  }
  // Skips to the line after `end_marker` (a section this reader does not need).
  bool skip_past(std::string_view end_marker) {
    std::string_view t;
    while (token(t))
      if (t == end_marker) return true;
    return false;
  }
  std::size_t left() const { return static_cast<std::size_t>(end_ - p_); }

 private:
  static bool is_space(char c) { return c == ' ' || c == '\n' || c == '\r' || c == '\t'; }
  const char* p_;
  const char* end_;
};

// The element families of gmsh's entities (GRegion's tetrahedra, hexahedra, ...), for the types
// ffr knows: gmsh lists an entity's elements by the type of each family's first element.
int family(int gmsh_type) {
  switch (gmsh_type) {
    case 15: return 0;            // point
    case 1: case 8: return 1;     // line
    case 2: case 9: return 2;     // triangle
    case 3: case 10: case 16: return 3;   // quadrangle
    case 4: case 11: return 4;    // tetrahedron
    case 5: case 12: case 17: return 5;   // hexahedron
    case 6: case 13: case 18: return 6;   // prism
    case 7: case 14: case 19: return 7;   // pyramid
    default: return -1;
  }
}

struct EntityKey {
  int dim, tag;
  bool operator<(const EntityKey& o) const { return dim != o.dim ? dim < o.dim : tag < o.tag; }
};

// An entity's elements by family: the family's type (its first element's) and, in file order,
// the tags and node tags of its elements.
struct FamilyElements {
  int type = 0;
  std::vector<std::size_t> tags, nodes;
};

struct EntityData {
  std::vector<int> physicals;
  std::vector<std::size_t> node_tags;  // the entity's nodes, in file order
  std::vector<double> xyz;
  std::map<int, FamilyElements> families;  // by family
  bool mixed = false;                      // two types of one family, or one ffr does not know
};

using Entities = std::map<EntityKey, EntityData>;

bool read_format(Cursor& c) {
  std::string_view version, end;
  int file_type = -1, data_size = 0;
  return c.token(version) && version == "4.1" && c.num(file_type) && file_type == 0 && c.num(data_size) &&
         data_size == 8 && c.token(end) && end == "$EndMeshFormat";
}

bool read_names(Cursor& c, std::map<std::pair<int, int>, std::string>& names) {
  long long n = 0;
  if (!c.num(n) || n < 0) return false;
  c.rest_of_line();
  for (long long k = 0; k < n; ++k) {
    int dim = 0, tag = 0;
    if (!c.num(dim) || !c.num(tag)) return false;
    const std::string_view line = c.rest_of_line();
    const auto q0 = line.find('"'), q1 = line.rfind('"');
    if (q0 == std::string_view::npos || q1 == q0) return false;
    names[{dim, tag}] = std::string(line.substr(q0 + 1, q1 - q0 - 1));
  }
  std::string_view end;
  return c.token(end) && end == "$EndPhysicalNames";
}

bool read_entities(Cursor& c, Entities& ents, int& top_dim) {
  std::array<long long, 4> count{};
  for (auto& n : count)
    if (!c.num(n) || n < 0 || static_cast<std::size_t>(n) > c.left()) return false;
  top_dim = -1;
  for (int dim = 0; dim < 4; ++dim) {
    if (count[static_cast<std::size_t>(dim)] > 0) top_dim = dim;
    for (long long k = 0; k < count[static_cast<std::size_t>(dim)]; ++k) {
      int tag = 0;
      double box = 0;
      if (!c.num(tag)) return false;
      for (int i = 0; i < (dim == 0 ? 3 : 6); ++i)
        if (!c.num(box)) return false;
      long long np = 0;
      if (!c.num(np) || np < 0 || static_cast<std::size_t>(np) > c.left()) return false;
      auto [it, fresh] = ents.try_emplace(EntityKey{dim, tag});
      if (!fresh) return false;
      for (long long i = 0; i < np; ++i) {
        int phys = 0;
        if (!c.num(phys)) return false;
        it->second.physicals.push_back(phys);
      }
      if (dim > 0) {
        long long nb = 0;
        if (!c.num(nb) || nb < 0 || static_cast<std::size_t>(nb) > c.left()) return false;
        for (long long i = 0; i < nb; ++i)
          if (!c.num(tag)) return false;
      }
    }
  }
  std::string_view end;
  return c.token(end) && end == "$EndEntities";
}

bool read_nodes(Cursor& c, Entities& ents, std::size_t& total) {
  long long blocks = 0, nodes = 0, min_tag = 0, max_tag = 0;
  if (!c.num(blocks) || !c.num(nodes) || !c.num(min_tag) || !c.num(max_tag) || blocks < 0 || nodes < 0 ||
      static_cast<std::size_t>(nodes) > c.left())
    return false;
  total = 0;
  for (long long b = 0; b < blocks; ++b) {
    int dim = 0, tag = 0, parametric = 0;
    long long n = 0;
    if (!c.num(dim) || !c.num(tag) || !c.num(parametric) || !c.num(n) || parametric != 0 || n < 0 ||
        static_cast<std::size_t>(n) > c.left())
      return false;
    const auto it = ents.find(EntityKey{dim, tag});
    if (it == ents.end()) return false;  // an entity $Entities did not declare: gmsh's business
    EntityData& e = it->second;
    const std::size_t first = e.node_tags.size();
    e.node_tags.resize(first + static_cast<std::size_t>(n));
    e.xyz.resize(3 * (first + static_cast<std::size_t>(n)));
    for (long long i = 0; i < n; ++i)
      if (!c.num(e.node_tags[first + static_cast<std::size_t>(i)])) return false;
    for (long long i = 0; i < 3 * n; ++i)
      if (!c.num(e.xyz[3 * first + static_cast<std::size_t>(i)])) return false;
    total += static_cast<std::size_t>(n);
  }
  std::string_view end;
  return total == static_cast<std::size_t>(nodes) && c.token(end) && end == "$EndNodes";
}

bool read_elements(Cursor& c, Entities& ents) {
  long long blocks = 0, count = 0, min_tag = 0, max_tag = 0;
  if (!c.num(blocks) || !c.num(count) || !c.num(min_tag) || !c.num(max_tag) || blocks < 0 || count < 0 ||
      static_cast<std::size_t>(count) > c.left())
    return false;
  for (long long b = 0; b < blocks; ++b) {
    int dim = 0, tag = 0, type = 0;
    long long n = 0;
    if (!c.num(dim) || !c.num(tag) || !c.num(type) || !c.num(n) || n < 0 || static_cast<std::size_t>(n) > c.left())
      return false;
    const auto it = ents.find(EntityKey{dim, tag});
    if (it == ents.end()) return false;
    EntityData& e = it->second;
    const int fam = family(type);
    int nn = 0;
    if (fam >= 0) {
      try {
        nn = fam == 0 ? 1 : num_nodes(from_gmsh(type));
      } catch (const std::invalid_argument&) {
        return false;
      }
    }
    FamilyElements* f = nullptr;
    if (fam < 0) {
      e.mixed = true;  // a type ffr does not know: only an error if the entity is used
    } else {
      auto [fit, fresh] = e.families.try_emplace(fam);
      if (fresh) fit->second.type = type;
      if (fit->second.type != type) e.mixed = true;
      else f = &fit->second;
    }
    c.rest_of_line();
    for (long long k = 0; k < n; ++k) {
      const std::string_view line = c.rest_of_line();
      if (!f) continue;
      Cursor l(line);
      std::size_t v = 0;
      if (!l.num(v)) return false;
      f->tags.push_back(v);
      for (int i = 0; i < nn; ++i) {
        if (!l.num(v)) return false;
        f->nodes.push_back(v);
      }
      std::string_view extra;
      if (l.token(extra)) return false;
    }
  }
  std::string_view end;
  return c.token(end) && end == "$EndElements";
}

}  // namespace

std::optional<Mesh> read_msh41(const std::string& file, MeshReport* report) {
  const auto t0 = std::chrono::steady_clock::now();
  std::string text;
  {
    std::ifstream in(file, std::ios::binary);
    if (!in) return std::nullopt;
    std::ostringstream s;
    s << in.rdbuf();
    text = std::move(s).str();
  }
  Cursor c(text);
  std::map<std::pair<int, int>, std::string> names;
  Entities ents;
  int top_dim = -1;
  std::size_t total_nodes = 0;
  bool format = false, entities = false, nodes = false, elements = false;
  std::string_view section;
  while (c.token(section)) {
    if (section == "$MeshFormat") {
      if (!(format = read_format(c))) return std::nullopt;
    } else if (!format) {
      return std::nullopt;
    } else if (section == "$PhysicalNames") {
      if (!read_names(c, names)) return std::nullopt;
    } else if (section == "$Entities") {
      if (!(entities = read_entities(c, ents, top_dim))) return std::nullopt;
    } else if (section == "$Nodes") {
      if (!entities || !(nodes = read_nodes(c, ents, total_nodes))) return std::nullopt;
    } else if (section == "$Elements") {
      if (!entities || !(elements = read_elements(c, ents))) return std::nullopt;
    } else if (section == "$PartitionedEntities" || section.size() < 2 || section[0] != '$') {
      return std::nullopt;
    } else if (!c.skip_past("$End" + std::string(section.substr(1)))) {
      return std::nullopt;
    }
  }
  if (!nodes || !elements || total_nodes == 0 || top_dim < 1) return std::nullopt;

  // Nodes in gmsh's order (entities by dimension, then tag; an entity's in file order), then
  // numbered along the space-filling curve as gmsh_import does.
  Mesh mesh;
  std::vector<std::size_t> tags;
  std::vector<double> coord;
  tags.reserve(total_nodes);
  coord.reserve(3 * total_nodes);
  for (const auto& [key, e] : ents) {
    tags.insert(tags.end(), e.node_tags.begin(), e.node_tags.end());
    coord.insert(coord.end(), e.xyz.begin(), e.xyz.end());
  }
  std::unordered_map<std::size_t, Index> index;
  if (!number_nodes(tags, coord, mesh, index)) return std::nullopt;  // a tag twice

  // Physical groups by dimension and tag, each with its entities by tag; then "all" (every
  // entity of the highest dimension) unless a group has that name, last, as gmsh_import adds it.
  struct Group {
    int dim;
    std::string name;
    std::vector<const EntityData*> members;
  };
  std::vector<Group> groups;
  {
    std::map<std::pair<int, int>, std::vector<const EntityData*>> by_tag;
    for (const auto& [key, e] : ents)
      for (const int p : e.physicals) by_tag[{key.dim, p}].push_back(&e);
    bool has_all = false;
    for (auto& [dt, members] : by_tag) {
      const auto n = names.find(dt);
      std::string name = n != names.end() ? n->second : std::string();
      has_all = has_all || name == "all";
      if (name.empty()) name = std::to_string(dt.second);
      groups.push_back(Group{dt.first, std::move(name), std::move(members)});
    }
    if (!has_all) {
      Group all{top_dim, "all", {}};
      for (const auto& [key, e] : ents)
        if (key.dim == top_dim) all.members.push_back(&e);
      groups.push_back(std::move(all));
    }
  }
  for (const Group& g : groups) {
    auto& set = mesh.node_groups[g.name];
    const auto node_index = [&index](std::size_t tag, Index& i) {
      const auto it = index.find(tag);
      if (it == index.end()) return false;
      i = it->second;
      return true;
    };
    if (g.dim == 0) {
      for (const EntityData* e : g.members)
        for (const std::size_t t : e->node_tags) {
          Index i = 0;
          if (!node_index(t, i)) return std::nullopt;
          set.push_back(i);
        }
    } else {
      std::map<int, std::size_t> block_of_type;
      for (const EntityData* e : g.members) {
        if (e->mixed) return std::nullopt;
        // gmsh lists an entity's elements by type number (its families' first types).
        std::map<int, const FamilyElements*> by_type;
        for (const auto& [fam, f] : e->families) by_type[f.type] = &f;
        for (const auto& [type, f] : by_type) {
          const ElementType t = from_gmsh(type);
          auto [it, fresh] = block_of_type.try_emplace(type, mesh.blocks.size());
          if (fresh) mesh.blocks.push_back(ElementBlock{t, g.name, {}, {}});
          ElementBlock& block = mesh.blocks[it->second];
          block.tags.insert(block.tags.end(), f->tags.begin(), f->tags.end());
          const std::size_t first = block.conn.size();
          block.conn.resize(first + f->nodes.size());
          for (std::size_t k = 0; k < f->nodes.size(); ++k)
            if (!node_index(f->nodes[k], block.conn[first + k])) return std::nullopt;
          set.insert(set.end(), block.conn.begin() + static_cast<std::ptrdiff_t>(first), block.conn.end());
        }
      }
    }
    std::sort(set.begin(), set.end());
    set.erase(std::unique(set.begin(), set.end()), set.end());
    set.shrink_to_fit();
  }
  if (mesh.blocks.empty()) return std::nullopt;  // gmsh's import names that error

  if (report) {
    report->element_counts = element_counts(mesh);
    report->nodes = mesh.num_nodes();
    report->meshed = false;
    report->gmsh_log.clear();
    report->seconds = seconds_since(t0);
  }
  return mesh;
}

}  // namespace ffr::preproc::detail
