#include "inp_reader.hpp"

#include "deck_mesh.hpp"
#include "ffr/formats/h5.hpp"
#include "ffr/formats/text_file.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <chrono>
#include <cmath>
#include <map>
#include <optional>
#include <string_view>

namespace ffr::preproc::detail {
namespace {

using formats::FormatError;

// An element type of the deck: ffr's type and the order of its nodes, gmsh node k = deck
// node order[k] (both from the element tables of the Abaqus manual, "Three-dimensional solid
// element library", and the gmsh reference manual, "Node ordering").
struct DeckType {
  const char* name;
  ElementType type;
  std::vector<int> order;
  Hex8Formulation hex8 = Hex8Formulation::Incompatible;
};

const std::vector<DeckType>& deck_types() {
  static const std::vector<DeckType> types = {
      {"C3D4", ElementType::Tet4, {0, 1, 2, 3}},
      // Corners and the base edges agree; the edges to the apex differ: gmsh 8 = (2,3) and
      // 9 = (1,3), Abaqus 9 = (1,3) and 10 = (2,3) (0-based corners, 1-based Abaqus nodes).
      {"C3D10", ElementType::Tet10, {0, 1, 2, 3, 4, 5, 6, 7, 9, 8}},
      // The two trilinear bricks, one node order: C3D8I with incompatible modes (ffr's default
      // HEX8), C3D8 fully integrated with 2x2x2 Gauss points (CalculiX manual, "Eight-node brick
      // element (C3D8)"), each kept in blocks of its own.
      {"C3D8I", ElementType::Hex8, {0, 1, 2, 3, 4, 5, 6, 7}},
      {"C3D8", ElementType::Hex8, {0, 1, 2, 3, 4, 5, 6, 7}, Hex8Formulation::FullIntegration},
      // gmsh's edge nodes 8..19 are the edges (0,1) (0,3) (0,4) (1,2) (1,5) (2,3) (2,6) (3,7)
      // (4,5) (4,7) (5,6) (6,7); Abaqus's 9..20 run (1,2) (2,3) (3,4) (4,1) (5,6) (6,7) (7,8)
      // (8,5) (1,5) (2,6) (3,7) (4,8).
      {"C3D20", ElementType::Hex20, {0, 1, 2, 3, 4, 5, 6, 7, 8, 11, 16, 9, 17, 10, 18, 19, 12, 15, 13, 14}},
      {"S3", ElementType::Tri3, {0, 1, 2}},
      {"S4", ElementType::Quad4, {0, 1, 2, 3}},
      {"B31", ElementType::Line2, {0, 1}},
  };
  return types;
}

// Why a known element type of the Abaqus library is not taken, where a reason is more useful
// than the list of types.
std::string refusal(const std::string& type) {
  if (type == "C3D8R" || type == "C3D20R" || type == "S4R" || type == "C3D10M" || type == "C3D10T")
    return type + " (reduced or modified integration) is not in ffr's element library";
  return "element type " + type + " is not in ffr's element library";
}

std::string upper(std::string_view s) {
  std::string u(s);
  for (char& c : u) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return u;
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

// The comma-separated fields of a line (an empty last field after a trailing comma dropped).
std::vector<std::string_view> fields(std::string_view line) {
  std::vector<std::string_view> f;
  std::size_t b = 0;
  for (;;) {
    const std::size_t c = line.find(',', b);
    f.push_back(trim(line.substr(b, c == std::string_view::npos ? std::string_view::npos : c - b)));
    if (c == std::string_view::npos) break;
    b = c + 1;
  }
  if (f.size() > 1 && f.back().empty()) f.pop_back();
  return f;
}

// The lines of a text, the last one counted whether or not it ends in a newline.
std::size_t line_count(std::string_view text) {
  return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n')) + (!text.empty() && text.back() != '\n');
}

struct Keyword {
  std::string name;                            // upper case, single spaces
  std::map<std::string, std::string> params;   // upper-case name -> value as written
  std::vector<std::string> flags;              // parameters without a value, upper case
  int line = 0;
  std::string text;                            // the keyword line as written, for messages
};

struct Set {
  std::string name;               // as written where it is first defined
  std::vector<std::size_t> ids;   // element or node ids, first occurrence order
  int line = 0;
};

struct MaterialDef {
  std::string name;
  std::optional<double> E, nu, rho;
  int line = 0;
};

struct SectionDef {
  bool shell = false;
  std::string elset, material;
  double thickness = 0;
  int line = 0;
  std::string text;
};

struct Deck {
  DeckMesh mesh;  // nodes, elements; its sets are filled at the end from the maps below
  std::vector<std::string> elset_order, nset_order;  // upper-case names in definition order
  std::map<std::string, Set> elsets, nsets;          // by upper-case name
  std::map<std::string, MaterialDef> materials;
  std::vector<SectionDef> sections;
};

class Parser {
 public:
  Parser(std::string file, std::string_view text, bool mesh) : text_(text), mesh_(mesh), lines_(line_count(text)) {
    deck_.mesh.file = std::move(file);
  }

  Deck parse() {
    std::string_view line;
    bool have = next(line);
    while (have) {
      if (line.size() < 1 || line[0] != '*') fail(line_, "a data line where a keyword (*...) was expected");
      const Keyword kw = keyword(line);
      have = dispatch(kw, line);
    }
    return std::move(deck_);
  }

 private:
  [[noreturn]] void fail(int line, const std::string& what) const {
    throw FormatError(deck_.mesh.file, "line " + std::to_string(line), what);
  }
  [[noreturn]] void fail(const Keyword& kw, const std::string& what) const {
    throw FormatError(deck_.mesh.file, "line " + std::to_string(kw.line) + " (" + kw.text + ")", what);
  }

  // The next line that is neither a comment (**) nor blank; false at the end.
  bool next(std::string_view& line) {
    while (pos_ < text_.size()) {
      const std::size_t e = text_.find('\n', pos_);
      std::string_view l = text_.substr(pos_, e == std::string_view::npos ? std::string_view::npos : e - pos_);
      pos_ = e == std::string_view::npos ? text_.size() : e + 1;
      ++line_;
      l = trim(l);
      if (l.empty() || (l.size() >= 2 && l[0] == '*' && l[1] == '*')) continue;
      line = l;
      return true;
    }
    return false;
  }

  Keyword keyword(std::string_view line) {
    Keyword kw;
    kw.line = line_;
    std::string joined(line);
    // A keyword line ending in a comma continues on the next line.
    while (!joined.empty() && joined.back() == ',') {
      std::string_view more;
      if (!next(more)) break;
      joined += std::string(more);
    }
    kw.text = joined.size() > 80 ? joined.substr(0, 77) + "..." : joined;
    const auto f = fields(std::string_view(joined).substr(1));
    std::string name;
    for (char c : upper(f[0]))
      if (!(c == ' ' && (name.empty() || name.back() == ' '))) name += c;
    kw.name = name;
    for (std::size_t i = 1; i < f.size(); ++i) {
      if (f[i].empty()) continue;
      const auto eq = f[i].find('=');
      if (eq == std::string_view::npos) {
        kw.flags.push_back(upper(f[i]));
      } else {
        std::string key = upper(trim(f[i].substr(0, eq)));
        std::string value(trim(f[i].substr(eq + 1)));
        if (value.size() >= 2 && value.front() == '"' && value.back() == '"') value = value.substr(1, value.size() - 2);
        if (!kw.params.emplace(key, value).second) fail(kw, "parameter " + key + " given twice");
      }
    }
    return kw;
  }

  std::string param(const Keyword& kw, const std::string& key) const {
    const auto it = kw.params.find(key);
    if (it == kw.params.end() || it->second.empty()) fail(kw, "missing parameter " + key + "=");
    return it->second;
  }

  // Only the listed parameters (and flags) are understood; any other would change what the
  // keyword means, so it is refused rather than ignored.
  void allow(const Keyword& kw, std::initializer_list<const char*> params, std::initializer_list<const char*> flags = {}) const {
    for (const auto& entry : kw.params) {
      const std::string& k = entry.first;  // not a structured binding: clang 14 cannot capture one
      if (std::none_of(params.begin(), params.end(), [&](const char* p) { return k == p; }))
        fail(kw, "parameter " + k + "= of *" + kw.name + " is not supported");
    }
    for (const auto& k : kw.flags)
      if (std::none_of(flags.begin(), flags.end(), [&](const char* p) { return k == p; }))
        fail(kw, "parameter " + k + " of *" + kw.name + " is not supported");
  }

  double number(std::string_view s, int line, const char* what) const {
    double v = 0;
    std::string t(s);
    // Fortran exponents (1.0D+03) as Abaqus accepts them.
    for (char& c : t)
      if (c == 'd' || c == 'D') c = 'e';
    const char* b = t.data();
    if (!t.empty() && t[0] == '+') ++b;
    const auto r = std::from_chars(b, t.data() + t.size(), v);
    if (t.empty() || r.ec != std::errc() || r.ptr != t.data() + t.size() || !std::isfinite(v))
      fail(line, std::string("expected ") + what + ", found '" + std::string(s) + "'");
    return v;
  }

  std::size_t id(std::string_view s, int line, const char* what) const {
    long long v = 0;
    const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
    if (s.empty() || r.ec != std::errc() || r.ptr != s.data() + s.size() || v < 1)
      fail(line, std::string("expected ") + what + " (a positive integer), found '" + std::string(s) + "'");
    return static_cast<std::size_t>(v);
  }

  // Reads data lines until the next keyword; calls f(fields, line) for each. Returns whether
  // a keyword line follows (in `line`).
  template <class F>
  bool data(std::string_view& line, F&& f) {
    while (next(line)) {
      if (line[0] == '*') return true;
      f(fields(line), line_);
    }
    return false;
  }

  bool skip_data(std::string_view& line) {
    return data(line, [](const std::vector<std::string_view>&, int) {});
  }

  bool dispatch(const Keyword& kw, std::string_view& line) {
    const std::string& k = kw.name;
    // Material data belongs to the *MATERIAL right before it.
    if (k != "ELASTIC" && k != "DENSITY" && k != "EXPANSION" && k != "CONDUCTIVITY" && k != "SPECIFIC HEAT")
      material_ = nullptr;
    if (k == "HEADING" || k == "PREPRINT") return skip_data(line);
    if (k == "NODE") return read_node(kw, line);
    if (k == "ELEMENT") return read_element(kw, line);
    if (k == "NSET" || k == "ELSET") return read_set(kw, line, k == "ELSET");
    if (k == "MATERIAL") {
      allow(kw, {"NAME"});
      const std::string name = param(kw, "NAME");
      auto [it, fresh] = deck_.materials.try_emplace(upper(name), MaterialDef{name, {}, {}, {}, kw.line});
      if (!fresh) fail(kw, "material " + name + " defined twice (first at line " + std::to_string(it->second.line) + ")");
      material_ = &it->second;
      return skip_data(line);
    }
    if (k == "ELASTIC" || k == "DENSITY") return read_material_data(kw, line);
    // Thermal material data: no part of a mechanical reduction (no temperature field).
    if (k == "EXPANSION" || k == "CONDUCTIVITY" || k == "SPECIFIC HEAT") {
      if (!material_) fail(kw, "*" + k + " outside a *MATERIAL");
      return skip_data(line);
    }
    if (k == "SOLID SECTION" || k == "SHELL SECTION") return read_section(kw, line, k == "SHELL SECTION");
    if (k == "STEP") return skip_step(kw, line);
    if (k == "BOUNDARY")
      fail(kw, "*BOUNDARY in the model data is not taken: ffr-reduce holds nodes through an interface of the part "
               "file and a \"clamped\" or \"craig-bampton\" reduction");
    if (k == "BEAM SECTION" || k == "BEAM GENERAL SECTION")
      fail(kw, "*" + k + " is not taken: give the beam's section in the part file's \"beams\" for its element set");
    if (k == "INCLUDE") fail(kw, "*INCLUDE is not supported: give the included file's lines in the deck itself");
    if (k == "PART" || k == "INSTANCE" || k == "ASSEMBLY")
      fail(kw, "*" + k + " is not supported: give a flat deck (nodes and elements at the top level, as CalculiX writes)");
    fail(kw, "keyword *" + k +
                 " is not supported (ffr reads *NODE, *ELEMENT, *NSET, *ELSET, *MATERIAL, *ELASTIC, *DENSITY, "
                 "*SOLID SECTION, *SHELL SECTION; it passes over *HEADING, *PREPRINT, *EXPANSION, *CONDUCTIVITY, "
                 "*SPECIFIC HEAT and *STEP ... *END STEP)");
  }

  bool read_node(const Keyword& kw, std::string_view& line) {
    allow(kw, {"NSET", "SYSTEM"});
    if (kw.params.count("SYSTEM") && upper(kw.params.at("SYSTEM")) != "R")
      fail(kw, "SYSTEM=" + kw.params.at("SYSTEM") + " is not supported (only rectangular coordinates, SYSTEM=R)");
    Set* set = kw.params.count("NSET") ? &define_set(kw, kw.params.at("NSET"), false) : nullptr;
    return data(line, [&](const std::vector<std::string_view>& f, int ln) {
      if (f.size() < 2 || f.size() > 4) fail(ln, "expected a node line 'id, x, y, z'");
      const std::size_t n = id(f[0], ln, "a node id");
      double x[3] = {0, 0, 0};
      for (std::size_t a = 1; a < f.size(); ++a) x[a - 1] = f[a].empty() ? 0.0 : number(f[a], ln, "a coordinate");
      if (mesh_) {
        deck_.mesh.node_ids.push_back(n);
        deck_.mesh.xyz.insert(deck_.mesh.xyz.end(), x, x + 3);
        deck_.mesh.node_lines.push_back(ln);
      }
      if (set) set->ids.push_back(n);
    });
  }

  bool read_element(const Keyword& kw, std::string_view& line) {
    allow(kw, {"TYPE", "ELSET"});
    const std::string type = upper(param(kw, "TYPE"));
    const auto& types = deck_types();
    const auto t = std::find_if(types.begin(), types.end(), [&](const DeckType& d) { return type == d.name; });
    if (t == types.end()) {
      std::string known;
      for (const auto& d : types) known += (known.empty() ? "" : ", ") + std::string(d.name);
      fail(kw, refusal(type) + " (ffr reads " + known + ")");
    }
    const std::size_t nn = t->order.size();
    Set* set = kw.params.count("ELSET") ? &define_set(kw, kw.params.at("ELSET"), true) : nullptr;
    // An element's entries may run over several lines; each line ends with a comma then.
    std::vector<std::size_t> entries;
    int first_line = 0;
    const auto finish = [&]() {
      std::vector<std::size_t> deck_nodes(entries.begin() + 1, entries.end());
      if (mesh_) {
        deck_.mesh.elements.push_back(DeckMesh::Element{entries[0], t->type, deck_.mesh.conn.size(), first_line, t->hex8});
        for (std::size_t i = 0; i < nn; ++i) deck_.mesh.conn.push_back(deck_nodes[static_cast<std::size_t>(t->order[i])]);
      }
      if (set) set->ids.push_back(entries[0]);
      entries.clear();
    };
    const bool more = data(line, [&](const std::vector<std::string_view>& f, int ln) {
      if (entries.empty()) first_line = ln;
      for (const auto& s : f) {
        if (s.empty()) fail(ln, "an empty field in the element's entries");
        entries.push_back(id(s, ln, entries.empty() ? "an element id" : "a node id"));
      }
      if (entries.size() > nn + 1)
        fail(first_line, "element " + std::to_string(entries[0]) + ": " + type + " has " + std::to_string(nn) +
                             " nodes, found " + std::to_string(entries.size() - 1));
      if (entries.size() == nn + 1) finish();
    });
    if (!entries.empty())
      fail(first_line, "element " + std::to_string(entries[0]) + ": " + type + " has " + std::to_string(nn) +
                           " nodes, found " + std::to_string(entries.size() - 1));
    return more;
  }

  Set& define_set(const Keyword& kw, const std::string& name, bool elements) {
    auto& sets = elements ? deck_.elsets : deck_.nsets;
    auto& order = elements ? deck_.elset_order : deck_.nset_order;
    const std::string key = upper(name);
    auto [it, fresh] = sets.try_emplace(key, Set{name, {}, kw.line});
    if (fresh) order.push_back(key);
    return it->second;
  }

  bool read_set(const Keyword& kw, std::string_view& line, bool elements) {
    const char* key = elements ? "ELSET" : "NSET";
    allow(kw, {key}, {"GENERATE", "UNSORTED"});
    const bool generate = std::find(kw.flags.begin(), kw.flags.end(), "GENERATE") != kw.flags.end();
    Set& set = define_set(kw, param(kw, key), elements);
    auto& sets = elements ? deck_.elsets : deck_.nsets;
    return data(line, [&](const std::vector<std::string_view>& f, int ln) {
      if (generate) {
        if (f.size() < 2 || f.size() > 3) fail(ln, "expected 'first, last[, increment]' of GENERATE");
        const std::size_t a = id(f[0], ln, "the first id"), b = id(f[1], ln, "the last id");
        const std::size_t inc = f.size() == 3 ? id(f[2], ln, "the increment") : 1;
        if (b < a) fail(ln, "GENERATE: the last id is below the first");
        // Each node and element is defined on a line of its own: a range of more ids than the
        // deck has lines names ids that are not defined (refused here, before it fills memory).
        const std::size_t count = (b - a) / inc + 1;
        if (count > lines_)
          fail(ln, "GENERATE " + std::to_string(a) + ", " + std::to_string(b) + ", " + std::to_string(inc) + " names " +
                       std::to_string(count) + " ids, more than the deck's " + std::to_string(lines_) +
                       " lines define (one node or element a line)");
        add_members(set, count, ln);
        for (std::size_t i = a; i <= b; i += inc) set.ids.push_back(i);
        return;
      }
      for (const auto& s : f) {
        if (s.empty()) continue;
        if (std::isdigit(static_cast<unsigned char>(s[0]))) {
          add_members(set, 1, ln);
          set.ids.push_back(id(s, ln, elements ? "an element id" : "a node id"));
        } else {
          // A set named in a set's data lines contributes its members.
          const auto other = sets.find(upper(s));
          if (other == sets.end() || &other->second == &set)
            fail(ln, std::string("no ") + (elements ? "element" : "node") + " set '" + std::string(s) +
                         "' defined before this line");
          add_members(set, other->second.ids.size(), ln);
          set.ids.insert(set.ids.end(), other->second.ids.begin(), other->second.ids.end());
        }
      }
    });
  }

  // Counts `count` more members of `set` against the deck's bound (kMaxDeckSetMembers).
  void add_members(const Set& set, std::size_t count, int ln) {
    if (count > kMaxDeckSetMembers - set_members_)
      fail(ln, "set " + set.name + ": the deck's sets would hold more than " + std::to_string(kMaxDeckSetMembers) +
                   " members in all (ids as listed, a set named in a set's lines counted with its members each time)");
    set_members_ += count;
  }

  bool read_material_data(const Keyword& kw, std::string_view& line) {
    if (!material_) fail(kw, "*" + kw.name + " outside a *MATERIAL");
    const bool elastic = kw.name == "ELASTIC";
    if (elastic) {
      allow(kw, {"TYPE"});
      if (kw.params.count("TYPE") && upper(kw.params.at("TYPE")) != "ISO" && upper(kw.params.at("TYPE")) != "ISOTROPIC")
        fail(kw, "TYPE=" + kw.params.at("TYPE") + " is not supported (ffr's materials are isotropic: TYPE=ISO)");
    } else {
      allow(kw, {});
    }
    int lines = 0;
    const bool more = data(line, [&](const std::vector<std::string_view>& f, int ln) {
      if (++lines > 1) fail(ln, "a second data line of *" + kw.name + " (temperature-dependent data) is not supported");
      if (elastic) {
        if (f.size() < 2 || f.size() > 3) fail(ln, "expected 'E, nu' of *ELASTIC");
        if (f.size() == 3 && !f[2].empty()) fail(ln, "a temperature on *ELASTIC is not supported");
        material_->E = number(f[0], ln, "Young's modulus E");
        material_->nu = number(f[1], ln, "Poisson's ratio nu");
      } else {
        if (f.size() > 2 || (f.size() == 2 && !f[1].empty())) fail(ln, "expected 'rho' of *DENSITY");
        material_->rho = number(f[0], ln, "the density");
      }
    });
    if (lines == 0) fail(kw, "*" + kw.name + " without its data line");
    return more;
  }

  bool read_section(const Keyword& kw, std::string_view& line, bool shell) {
    // ORIENTATION changes nothing for an isotropic material; OFFSET would move a shell's
    // mid-surface, which ffr's shells do not do.
    if (shell) allow(kw, {"ELSET", "MATERIAL", "ORIENTATION", "OFFSET"});
    else allow(kw, {"ELSET", "MATERIAL", "ORIENTATION"});
    if (shell && kw.params.count("OFFSET") && number(kw.params.at("OFFSET"), kw.line, "an offset") != 0.0)
      fail(kw, "OFFSET is not supported (ffr's shells lie on their mid-surface, OFFSET=0)");
    SectionDef s{shell, param(kw, "ELSET"), param(kw, "MATERIAL"), 0, kw.line, kw.text};
    int lines = 0;
    const bool more = data(line, [&](const std::vector<std::string_view>& f, int ln) {
      if (++lines > 1) fail(ln, "a second data line of *" + kw.name + " is not supported");
      if (shell) {
        s.thickness = number(f[0], ln, "the shell thickness");
        if (!(s.thickness > 0)) fail(ln, "the shell thickness must be positive");
      }
    });
    if (shell && lines == 0) fail(kw, "*SHELL SECTION without its thickness line");
    deck_.sections.push_back(s);
    return more;
  }

  // The history data: the analysis steps of the deck (procedures, loads, boundary conditions,
  // output requests). ffr-reduce runs its own analysis from the part file.
  bool skip_step(const Keyword& kw, std::string_view& line) {
    while (next(line))
      if (line[0] == '*' && upper(trim(line.substr(1))).rfind("END STEP", 0) == 0) return next(line);
    fail(kw, "*STEP without *END STEP");
  }

  std::string_view text_;
  bool mesh_;
  std::size_t lines_;            // of the deck, the most nodes or elements it can define
  std::size_t set_members_ = 0;  // in all sets so far
  std::size_t pos_ = 0;
  int line_ = 0;
  Deck deck_;
  MaterialDef* material_ = nullptr;
};

Deck parse(const std::string& file, bool mesh) {
  const std::string text = formats::read_text_file(file);
  return Parser(file, text, mesh).parse();
}

std::vector<DeckSection> sections(const Deck& d) {
  const std::string& file = d.mesh.file;
  std::vector<DeckSection> out;
  for (const auto& s : d.sections) {
    const std::string where = "line " + std::to_string(s.line) + " (" + s.text + ")";
    const auto set = d.elsets.find(upper(s.elset));
    if (set == d.elsets.end()) throw FormatError(file, where, "no element set '" + s.elset + "' in the deck");
    const auto m = d.materials.find(upper(s.material));
    if (m == d.materials.end()) throw FormatError(file, where, "no material '" + s.material + "' in the deck");
    const MaterialDef& md = m->second;
    const std::string mwhere = "line " + std::to_string(md.line) + " (*MATERIAL, NAME=" + md.name + ")";
    if (!md.E || !md.nu) throw FormatError(file, mwhere, "material " + md.name + " has no *ELASTIC");
    if (!md.rho) throw FormatError(file, mwhere, "material " + md.name + " has no *DENSITY (the reduction needs mass)");
    DeckSection ds;
    ds.kind = s.shell ? DeckSection::Kind::Shell : DeckSection::Kind::Solid;
    ds.group = set->second.name;
    ds.mat = Material{*md.E, *md.nu, *md.rho};
    ds.thickness = s.thickness;
    ds.where = where;
    out.push_back(ds);
  }
  return out;
}

}  // namespace

bool is_inp(const std::filesystem::path& file) { return upper(file.extension().string()) == ".INP"; }

std::vector<DeckSection> read_inp_sections(const std::string& file) { return sections(parse(file, false)); }

Mesh read_inp(const std::string& file, MeshReport* report) {
  const auto t0 = std::chrono::steady_clock::now();
  Deck d = parse(file, true);
  // The sections' sets and materials, checked here as well: a deck is refused the same way
  // whichever reader meets the problem first.
  (void)sections(d);
  for (const std::string& key : d.elset_order) {
    const Set& s = d.elsets.at(key);
    d.mesh.element_sets.push_back({s.name, s.ids, "line " + std::to_string(s.line) + " (element set " + s.name + ")"});
  }
  for (const std::string& key : d.nset_order) {
    const Set& s = d.nsets.at(key);
    // A node set joins the element set of the same name, under that set's spelling.
    const auto es = d.elsets.find(key);
    d.mesh.node_sets.push_back({es != d.elsets.end() ? es->second.name : s.name, s.ids,
                                "line " + std::to_string(s.line) + " (node set " + s.name + ")"});
  }
  d.mesh.has_all = d.elsets.count("ALL") || d.nsets.count("ALL");
  return build_deck_mesh(d.mesh, report, t0);
}

}  // namespace ffr::preproc::detail
