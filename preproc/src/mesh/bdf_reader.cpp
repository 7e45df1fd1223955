#include "bdf_reader.hpp"

#include "bdf_beam.hpp"
#include "bdf_cards.hpp"

#include "ffr/formats/h5.hpp"
#include "ffr/formats/text_file.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <chrono>
#include <cmath>
#include <map>
#include <optional>
#include <set>
#include <string_view>
#include <unordered_map>

namespace ffr::preproc::detail {
namespace {

using formats::FormatError;

struct ElementCard {
  const char* name;
  ElementType linear, quadratic;  // by node count: 4/10, 8/20, or one type
  int nodes_linear, nodes_quadratic;
  std::vector<int> order;         // gmsh node k = Nastran node order[k], quadratic type
  DeckSection::Kind kind;
};

// Nastran's node orders (Quick Reference Guide, CTETRA and CHEXA) in terms of gmsh's: the
// corners agree; CTETRA's edges G5..G10 are (1,2) (2,3) (3,1) (1,4) (2,4) (3,4), gmsh's 4..9
// (0,1) (1,2) (2,0) (3,0) (3,2) (3,1); CHEXA's G9..G20 run round the bottom face, up the
// vertical edges, round the top face, gmsh's 8..19 by first corner (0,1) (0,3) (0,4) (1,2)
// (1,5) (2,3) (2,6) (3,7) (4,5) (4,7) (5,6) (6,7).
const std::vector<ElementCard>& element_cards() {
  static const std::vector<ElementCard> cards = {
      {"CTETRA", ElementType::Tet4, ElementType::Tet10, 4, 10, {0, 1, 2, 3, 4, 5, 6, 7, 9, 8}, DeckSection::Kind::Solid},
      {"CHEXA", ElementType::Hex8, ElementType::Hex20, 8, 20,
       {0, 1, 2, 3, 4, 5, 6, 7, 8, 11, 12, 9, 13, 10, 14, 15, 16, 19, 17, 18}, DeckSection::Kind::Solid},
      {"CTRIA3", ElementType::Tri3, ElementType::Tri3, 3, 3, {0, 1, 2}, DeckSection::Kind::Shell},
      {"CQUAD4", ElementType::Quad4, ElementType::Quad4, 4, 4, {0, 1, 2, 3}, DeckSection::Kind::Shell},
      {"CBAR", ElementType::Line2, ElementType::Line2, 2, 2, {0, 1}, DeckSection::Kind::Beam},
      {"CBEAM", ElementType::Line2, ElementType::Line2, 2, 2, {0, 1}, DeckSection::Kind::Beam},
  };
  return cards;
}

struct Property {
  DeckSection::Kind kind;
  const Card* card;
  std::size_t mid;
  double thickness = 0;
  BeamProps beam;
  Hex8Formulation hex8 = Hex8Formulation::Incompatible;  // PSOLID: its 8-grid CHEXAs
};

struct Bar {
  std::size_t ga;
  Eigen::Vector3d v = Eigen::Vector3d::Zero();
  std::size_t g0 = 0;  // orientation by a grid instead of v
};

struct Bulk {
  DeckMesh mesh;
  std::vector<std::size_t> element_pid;  // per mesh.elements
  std::vector<const Card*> element_card;
  std::map<std::size_t, Bar> bars;       // by element index
  std::map<std::size_t, Property> properties;
  std::map<std::size_t, const Card*> materials;
  std::vector<const Card*> conm2;
  std::vector<Card> cards;
};

// The grid ids of a SET1/SPC1 list from field `first` on: ids and "id1 THRU id2". Every id must
// be one of the deck's `grids` GRID cards, so a longer THRU is refused before it fills memory;
// `members` counts the ids of all lists against kMaxDeckSetMembers.
std::vector<std::size_t> grid_list(const Fields& f, std::size_t first, std::size_t grids, std::size_t& members) {
  std::vector<std::size_t> ids;
  const auto add = [&](std::size_t count, std::size_t k) {
    if (count > kMaxDeckSetMembers - members)
      f.fail(Fields::at(k) + ": the deck's SET1 and SPC1 cards would list more than " + std::to_string(kMaxDeckSetMembers) +
             " grids in all");
    members += count;
  };
  for (std::size_t k = first; k <= f.size(); ++k) {
    if (f.blank(k)) continue;
    if (f.raw(k) == "THRU") {
      if (ids.empty() || k + 1 > f.size()) f.fail(Fields::at(k) + ": THRU needs an id before and after it");
      const std::size_t a = ids.back(), b = f.id(k + 1, "the last id of THRU");
      if (b < a) f.fail(Fields::at(k + 1) + ": THRU ends below its start");
      if (b - a >= grids)
        f.fail(Fields::at(k + 1) + ": " + std::to_string(a) + " THRU " + std::to_string(b) + " names " +
               std::to_string(b - a + 1) + " grids, more than the deck's " + std::to_string(grids) +
               (grids == 1 ? " GRID card" : " GRID cards"));
      add(b - a, k + 1);
      for (std::size_t i = a + 1; i <= b; ++i) ids.push_back(i);
      ++k;
    } else {
      add(1, k);
      ids.push_back(f.id(k, "a grid id"));
    }
  }
  return ids;
}

Bulk parse(const std::string& file) {
  Bulk b;
  b.mesh.file = file;
  b.cards = read_cards(file, formats::read_text_file(file));
  const auto grids = static_cast<std::size_t>(std::count_if(b.cards.begin(), b.cards.end(), [](const Card& c) { return c.name == "GRID"; }));
  std::size_t set_members = 0;
  std::map<std::string, std::size_t> set_index;  // node set name -> index in mesh.node_sets
  std::map<std::size_t, std::size_t> pid_set;    // pid -> index in mesh.element_sets
  const std::set<std::string> passed_over = {"EIGRL", "EIGR", "SPC", "SPCADD", "FORCE", "MOMENT", "GRAV", "LOAD"};
  // Parameters of output and of the solution's bookkeeping; every other PARAM is refused.
  const std::set<std::string> harmless_params = {"POST", "PRGPST", "OGEOM", "AUTOSPC", "GRDPNT", "NOCOMPS", "MAXRATIO"};
  for (const Card& c : b.cards) {
    const Fields f(file, c);
    const auto element = std::find_if(element_cards().begin(), element_cards().end(),
                                      [&](const ElementCard& e) { return c.name == e.name; });
    if (c.name == "GRID") {
      const std::size_t id = f.id(2, "ID");
      if (f.integer_or(3, "CP", 0) != 0) f.fail("field 3 (CP): coordinate systems are not supported (CP = 0 or blank)");
      if (f.integer_or(7, "CD", 0) != 0) f.fail("field 7 (CD): coordinate systems are not supported (CD = 0 or blank)");
      f.require_blank(8, 8, "permanent constraints (PS): hold nodes through an interface of the part file");
      b.mesh.node_ids.push_back(id);
      for (std::size_t k = 4; k <= 6; ++k) b.mesh.xyz.push_back(f.real_or(k, "X", 0.0));
      b.mesh.node_lines.push_back(c.line);
      f.require_blank(10, f.size(), "GRID has 9 fields");
    } else if (element != element_cards().end()) {
      const std::size_t eid = f.id(2, "EID"), pid = f.id(3, "PID");
      const std::size_t first = 4;
      int n = 0;
      std::vector<std::size_t> g;
      if (element->kind == DeckSection::Kind::Solid) {
        // Grids up to the last non-blank field; the linear or the complete quadratic element.
        for (std::size_t k = first; k < first + static_cast<std::size_t>(element->nodes_quadratic); ++k)
          if (!f.blank(k)) n = static_cast<int>(k - first + 1);
        if (n != element->nodes_linear && n != element->nodes_quadratic)
          f.fail(std::string(element->name) + " with " + std::to_string(n) + " grids: ffr takes " +
                 std::to_string(element->nodes_linear) + " or all " + std::to_string(element->nodes_quadratic));
        f.require_blank(first + static_cast<std::size_t>(element->nodes_quadratic), f.size(), "beyond the element's grids");
      } else {
        n = element->nodes_linear;
      }
      for (int i = 0; i < n; ++i) g.push_back(f.id(first + static_cast<std::size_t>(i), "a grid id"));
      if (c.name == "CTRIA3") {
        f.require_zero(8, "ZOFFS");
        f.require_blank(9, f.size(), "varying thickness (TFLAG, T1..T3)");
      } else if (c.name == "CQUAD4") {
        f.require_zero(9, "ZOFFS");
        f.require_blank(10, f.size(), "varying thickness (TFLAG, T1..T4)");
      } else if (c.name == "CBAR" || c.name == "CBEAM") {
        // CBAR and CBEAM share fields 2-17 (Quick Reference Guide): the orientation as X1..X3
        // or G0, OFFT (CBEAM: OFFT/BIT, BIT only for p-elements), pin flags, offsets.
        Bar bar{g[0]};
        if (f.raw(6).find('.') == std::string::npos && f.blank(7) && f.blank(8) && !f.blank(6)) {
          bar.g0 = f.id(6, "G0");
        } else {
          bar.v = Eigen::Vector3d(f.real_or(6, "X1", 0), f.real_or(7, "X2", 0), f.real_or(8, "X3", 0));
          if (bar.v.norm() == 0) f.fail("fields 6-8 (X1, X2, X3): the orientation vector is zero");
        }
        const std::string offt = f.raw(9);
        if (!offt.empty() && offt != "GGG")
          f.fail(c.name == "CBAR" ? "field 9 (OFFT): only GGG (or blank) is supported"
                                  : "field 9 (OFFT/BIT): only OFFT = GGG (or blank) is supported");
        f.require_blank(10, 11, "pin flags (PA, PB)");
        for (std::size_t k = 12; k <= 17; ++k) f.require_zero(k, "an offset");
        if (c.name == "CBEAM") {
          f.require_blank(18, 19, "warping scalar points (SA, SB): ffr's beams do not warp");
          f.require_blank(20, f.size(), "CBEAM has 19 fields");
        } else {
          f.require_blank(18, f.size(), "CBAR has 17 fields");
        }
        b.bars[b.mesh.elements.size()] = bar;
      }
      const ElementType type = n == element->nodes_linear ? element->linear : element->quadratic;
      b.mesh.elements.push_back(DeckMesh::Element{eid, type, b.mesh.conn.size(), c.line});
      for (int k = 0; k < n; ++k)
        b.mesh.conn.push_back(g[static_cast<std::size_t>(n == element->nodes_quadratic ? element->order[static_cast<std::size_t>(k)] : k)]);
      b.element_pid.push_back(pid);
      b.element_card.push_back(&c);
      auto [it, fresh] = pid_set.try_emplace(pid, b.mesh.element_sets.size());
      if (fresh) b.mesh.element_sets.push_back({"pid" + std::to_string(pid), {}, "property " + std::to_string(pid)});
      b.mesh.element_sets[it->second].ids.push_back(eid);
    } else if (c.name == "MAT1") {
      const std::size_t mid = f.id(2, "MID");
      if (!b.materials.emplace(mid, &c).second) f.fail("MAT1 " + std::to_string(mid) + " defined twice");
    } else if (c.name == "PSOLID" || c.name == "PSHELL" || c.name == "PBAR" || c.name == "PBEAM") {
      Property pr{};
      pr.card = &c;
      const std::size_t pid = f.id(2, "PID");
      pr.mid = f.id(3, "MID");
      if (c.name == "PSOLID") {
        pr.kind = DeckSection::Kind::Solid;
        // IN and ISOP choose the 8-grid CHEXA's formulation (Quick Reference Guide, PSOLID):
        // blank (or BUBBLE, REDUCED), Nastran's default, the bubble-function brick, which ffr
        // takes as its incompatible-mode HEX8; IN = 2 (TWO) with ISOP = FULL (1), the plain
        // isoparametric brick with 2x2x2 Gauss points, ffr's full-integration HEX8 (C3D8).
        const std::string in = f.raw(5), isop = f.raw(7);
        if ((in == "2" || in == "TWO") && (isop == "FULL" || isop == "1")) {
          pr.hex8 = Hex8Formulation::FullIntegration;
        } else if (!((in.empty() || in == "BUBBLE" || in == "0") && (isop.empty() || isop == "REDUCED" || isop == "0"))) {
          f.fail("fields 5, 7 (IN, ISOP) = '" + in + "', '" + isop +
                 "': ffr takes both blank (Nastran's default bubble-function CHEXA, ffr's incompatible-mode HEX8; "
                 "also IN = BUBBLE, ISOP = REDUCED) or IN = 2 with ISOP = FULL (the full-integration CHEXA)");
        }
        if (!f.blank(8) && f.raw(8) != "SMECH") f.fail("field 8 (FCTN): only SMECH (structural) is supported");
        f.require_blank(9, f.size(), "PSOLID has 8 fields");
      } else if (c.name == "PSHELL") {
        pr.kind = DeckSection::Kind::Shell;
        pr.thickness = f.real(4, "T");
        if (!(pr.thickness > 0)) f.fail("field 4 (T): the thickness must be positive");
        // ffr's shell: one isotropic material in membrane, bending and transverse shear,
        // bending stiffness t^3/12, shear factor 5/6.
        if (f.blank(5) || f.id(5, "MID2") != pr.mid) f.fail("field 5 (MID2): ffr's shells bend with the membrane's material (MID2 = MID1)");
        if (std::abs(f.real_or(6, "12I/T**3", 1.0) - 1.0) > 1e-6) f.fail("field 6 (12I/T**3): only 1.0 (or blank) is supported");
        if (!f.blank(7) && f.id(7, "MID3") != pr.mid) f.fail("field 7 (MID3): only MID1 (or blank) is supported");
        if (std::abs(f.real_or(8, "TS/T", 5.0 / 6.0) - 5.0 / 6.0) > 1e-5)
          f.fail("field 8 (TS/T): ffr's shells have the shear factor 5/6 (0.833333 or blank)");
        f.require_zero(9, "NSM");
        f.require_blank(12, f.size(), "a coupling material (MID4)");
      } else if (c.name == "PBEAM") {
        pr.kind = DeckSection::Kind::Beam;
        pr.beam = read_pbeam(f);
      } else {
        pr.kind = DeckSection::Kind::Beam;
        BeamProps& bp = pr.beam;
        bp.A = f.real(4, "A");
        // Nastran's I1 bends in plane 1 (the element's x-y plane): integral of y^2 dA, ffr's Iz.
        bp.Iz = f.real(5, "I1");
        bp.Iy = f.real(6, "I2");
        bp.J = f.real(7, "J");
        if (!(bp.A > 0 && bp.Iy > 0 && bp.Iz > 0 && bp.J > 0)) f.fail("A, I1, I2 and J must be positive");
        f.require_zero(8, "NSM");
        f.require_blank(9, 9, "");
        // Fields 10-17: stress recovery points (output only).
        if (auto k1 = f.real_opt(18, "K1")) bp.ky = *k1;
        if (auto k2 = f.real_opt(19, "K2")) bp.kz = *k2;
        if ((bp.ky && !(*bp.ky > 0)) || (bp.kz && !(*bp.kz > 0))) f.fail("continuation 2, fields 2, 3 (K1, K2): must be positive or blank");
        f.require_zero(20, "I12");
        f.require_blank(21, f.size(), "PBAR has 20 fields");
      }
      if (!b.properties.emplace(pid, pr).second) f.fail("property " + std::to_string(pid) + " defined twice");
    } else if (c.name == "SET1" || c.name == "SPC1") {
      const std::size_t sid = f.id(2, "SID");
      const std::string name = (c.name == "SET1" ? "set" : "spc") + std::to_string(sid);
      auto [it, fresh] = set_index.try_emplace(name, b.mesh.node_sets.size());
      if (fresh) b.mesh.node_sets.push_back({name, {}, "line " + std::to_string(c.line) + " (" + c.name + " " + std::to_string(sid) + ")"});
      const auto ids = grid_list(f, c.name == "SET1" ? 3 : 4, grids, set_members);
      auto& set = b.mesh.node_sets[it->second].ids;
      set.insert(set.end(), ids.begin(), ids.end());
    } else if (passed_over.count(c.name)) {
      continue;
    } else if (c.name == "PARAM") {
      if (!harmless_params.count(f.raw(2)))
        f.fail("PARAM " + f.raw(2) + " is not taken (ffr passes over only PARAM POST, PRGPST, OGEOM, AUTOSPC, GRDPNT, "
                                      "NOCOMPS, MAXRATIO)");
    } else if (c.name == "CONM2") {
      b.conm2.push_back(&c);
    } else if (c.name == "CONM1") {
      f.fail("CONM1 (a 6 x 6 mass matrix) is not supported: give the mass as CONM2 or in the part file's \"point_masses\"");
    } else if (c.name == "RBE2" || c.name == "RBE3" || c.name == "RBAR") {
      f.fail(c.name + " is not supported: give the coupling as an interface of the part file (rigid or averaged)");
    } else if (c.name.rfind("CORD", 0) == 0) {
      f.fail(c.name + ": coordinate systems are not supported");
    } else if (c.name == "INCLUDE") {
      f.fail("INCLUDE is not supported: give the included file's cards in the deck itself");
    } else {
      f.fail("card " + c.name + " is not supported (ffr reads GRID, CTETRA, CHEXA, CTRIA3, CQUAD4, CBAR, CBEAM, MAT1, "
                                "PSOLID, PSHELL, PBAR, PBEAM, SET1, SPC1, CONM2; it passes over EIGRL, EIGR, SPC, "
                                "SPCADD, FORCE, MOMENT, GRAV, LOAD and some PARAMs)");
    }
  }
  return b;
}

std::vector<DeckSection> sections(const Bulk& b) {
  const std::string& file = b.mesh.file;
  std::unordered_map<std::size_t, std::size_t> node_line;
  for (std::size_t i = 0; i < b.mesh.node_ids.size(); ++i) node_line.emplace(b.mesh.node_ids[i], i);
  std::vector<DeckSection> out;
  std::set<std::size_t> done, failed;
  for (std::size_t e = 0; e < b.element_pid.size(); ++e) {
    const std::size_t pid = b.element_pid[e];
    if (failed.count(pid)) continue;
    try {
      const Fields ef(file, *b.element_card[e]);
      const auto p = b.properties.find(pid);
      const auto kind = std::find_if(element_cards().begin(), element_cards().end(),
                                     [&](const ElementCard& c) { return b.element_card[e]->name == c.name; })->kind;
      const std::string& card = b.element_card[e]->name;
      const std::string wanted = kind == DeckSection::Kind::Solid ? "PSOLID"
                                 : kind == DeckSection::Kind::Shell ? "PSHELL"
                                 : card == "CBEAM"                  ? "PBEAM"
                                                                    : "PBAR";
      if (p == b.properties.end()) ef.fail("field 3 (PID): no property " + std::to_string(pid) + " (" + wanted + ") in the deck");
      if (p->second.card->name != wanted) ef.fail("field 3 (PID): property " + std::to_string(pid) + " is a " + p->second.card->name + ", expected a " + wanted);
      if (!done.insert(pid).second && kind != DeckSection::Kind::Beam) continue;
      const Property& pr = p->second;
      const Fields pf(file, *pr.card);
      DeckSection ds;
      ds.kind = kind;
      ds.group = "pid" + std::to_string(pid);
      ds.where = "line " + std::to_string(pr.card->line) + " (" + pr.card->name + " " + std::to_string(pid) + ")";
      if (kind == DeckSection::Kind::Beam) {
        // One y axis per beam group: every bar of the property must point its v the same way.
        const Bar& bar = b.bars.at(e);
        Eigen::Vector3d v = bar.v;
        if (bar.g0) {
          const auto a = node_line.find(bar.ga), g = node_line.find(bar.g0);
          if (a == node_line.end() || g == node_line.end()) ef.fail("fields 4, 6 (GA, G0): grid not defined");
          v = Eigen::Map<const Eigen::Vector3d>(&b.mesh.xyz[3 * g->second]) - Eigen::Map<const Eigen::Vector3d>(&b.mesh.xyz[3 * a->second]);
          if (v.norm() == 0) ef.fail("field 6 (G0): the orientation grid lies on GA");
        }
        v.normalize();
        auto it = std::find_if(out.begin(), out.end(), [&](const DeckSection& s) { return s.group == ds.group; });
        if (it != out.end()) {
          if ((it->beam.y_axis - v).norm() > 1e-9)
            ef.fail("the orientation vector differs from the first " + card + " of property " + std::to_string(pid) +
                    ": ffr takes one y axis per beam group (give " + card + "s of other orientations another " + wanted + ")");
          continue;
        }
        ds.beam = pr.beam;
        ds.beam.y_axis = v;
      }
      const auto m = b.materials.find(pr.mid);
      if (m == b.materials.end()) pf.fail("field 3 (MID): no MAT1 " + std::to_string(pr.mid) + " in the deck");
      const Fields mf(file, *m->second);
      const std::optional<double> E = mf.real_opt(3, "E"), G = mf.real_opt(4, "G"), nu = mf.real_opt(5, "NU");
      // Two of E, G, NU give the third (E = 2 G (1 + NU)).
      if (!!E + !!G + !!nu < 2) mf.fail("give two of E, G and NU");
      ds.mat.E = E ? *E : 2 * *G * (1 + *nu);
      ds.mat.nu = nu ? *nu : *E / (2 * *G) - 1;
      if (E && G && nu && std::abs(*E - 2 * *G * (1 + *nu)) > 1e-6 * std::abs(*E))
        mf.fail("E, G and NU disagree (E != 2 G (1 + NU)): give two of them");
      const std::optional<double> rho = mf.real_opt(6, "RHO");
      if (!rho) mf.fail("field 6 (RHO): no density (the reduction needs mass)");
      ds.mat.rho = *rho;
      mf.require_zero(9, "GE, structural damping: give damping in the part file");
      ds.beam.group = ds.group;
      ds.beam.mat = ds.mat;
      ds.thickness = pr.thickness;
      out.push_back(ds);
    } catch (const FormatError& error) {
      // The part file may give the property of this group itself: only then is it no error.
      DeckSection ds;
      ds.group = "pid" + std::to_string(pid);
      ds.where = error.object();
      ds.problem = error.detail();
      out.erase(std::remove_if(out.begin(), out.end(), [&](const DeckSection& s) { return s.group == ds.group; }), out.end());
      out.push_back(ds);
      failed.insert(pid);
    }
  }
  return out;
}

}  // namespace

bool is_bdf(const std::filesystem::path& file) {
  const std::string e = bdf_upper(file.extension().string());
  return e == ".BDF" || e == ".DAT" || e == ".NAS";
}

std::vector<DeckSection> read_bdf_sections(const std::string& file) { return sections(parse(file)); }

std::vector<DeckPointMass> read_bdf_point_masses(const std::string& file) {
  const Bulk b = parse(file);
  std::map<std::size_t, std::size_t> grid;  // id -> index
  for (std::size_t i = 0; i < b.mesh.node_ids.size(); ++i) grid.emplace(b.mesh.node_ids[i], i);
  std::vector<DeckPointMass> out;
  for (const Card* c : b.conm2) {
    const Fields f(file, *c);
    DeckPointMass m;
    m.eid = f.id(2, "EID");
    m.grid = f.id(3, "G");
    const auto g = grid.find(m.grid);
    if (g == grid.end()) f.fail(Fields::at(3) + " (G): grid " + std::to_string(m.grid) + " is not defined");
    const Eigen::Vector3d x(b.mesh.xyz[3 * g->second], b.mesh.xyz[3 * g->second + 1], b.mesh.xyz[3 * g->second + 2]);
    m.at = x;
    const long long cid = f.integer_or(4, "CID", 0);
    if (cid != 0 && cid != -1) f.fail(Fields::at(4) + " (CID): coordinate systems are not supported (0, blank or -1)");
    m.mass = f.real(5, "M");
    if (!(m.mass > 0)) f.fail(Fields::at(5) + " (M): a positive mass is expected");
    const Eigen::Vector3d X(f.real_or(6, "X1", 0.0), f.real_or(7, "X2", 0.0), f.real_or(8, "X3", 0.0));
    // CID = -1: X is the centre in the basic system; otherwise its offset from the grid.
    m.offset = cid == -1 ? Eigen::Vector3d(X - x) : X;
    f.require_blank(9, 9, "field 9 of CONM2 is blank");
    // Quick Reference Guide, CONM2: the inertia about the centre is
    // [I11 -I21 -I31; -I21 I22 -I32; -I31 -I32 I33].
    const double I11 = f.real_or(10, "I11", 0), I21 = f.real_or(11, "I21", 0), I22 = f.real_or(12, "I22", 0),
                 I31 = f.real_or(13, "I31", 0), I32 = f.real_or(14, "I32", 0), I33 = f.real_or(15, "I33", 0);
    m.inertia << I11, -I21, -I31, -I21, I22, -I32, -I31, -I32, I33;
    {
      const Eigen::Vector3d ev = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(m.inertia).eigenvalues();
      const double tol = 1e-12 * std::max(1.0, ev.cwiseAbs().maxCoeff());
      if (ev.minCoeff() < -tol) f.fail("continuation 1 (I11 ... I33): the inertia must be positive semi-definite");
      if (ev(0) + ev(1) < ev(2) - tol)
        f.fail("continuation 1 (I11 ... I33): the principal moments violate the triangle inequality (not a physical body)");
    }
    f.require_blank(16, f.size(), "CONM2 has 15 fields");
    m.where = "line " + std::to_string(c->line) + " (CONM2 " + std::to_string(m.eid) + ")";
    out.push_back(m);
  }
  return out;
}

Mesh read_bdf(const std::string& file, MeshReport* report) {
  const auto t0 = std::chrono::steady_clock::now();
  // The properties are load_part's (read_bdf_sections): the part file may replace them. The
  // formulation of an 8-grid CHEXA is the element's, so it stays with the deck's PSOLID.
  Bulk b = parse(file);
  for (std::size_t e = 0; e < b.mesh.elements.size(); ++e) {
    const auto p = b.properties.find(b.element_pid[e]);
    if (p == b.properties.end() || p->second.kind != DeckSection::Kind::Solid ||
        p->second.hex8 != Hex8Formulation::FullIntegration)
      continue;
    DeckMesh::Element& el = b.mesh.elements[e];
    if (dimension(el.type) != 3) continue;  // a bar or shell on a PSOLID: sections() names it
    if (el.type != ElementType::Hex8)
      Fields(file, *b.element_card[e])
          .fail("field 3 (PID): PSOLID " + std::to_string(b.element_pid[e]) + " (line " +
                std::to_string(p->second.card->line) +
                ") has IN = 2, ISOP = FULL, which chooses the 8-grid CHEXA's integration; ffr integrates " +
                b.element_card[e]->name + " with " + std::to_string(num_nodes(el.type)) +
                " grids by its own rule: give it a PSOLID with IN and ISOP blank");
    el.hex8 = Hex8Formulation::FullIntegration;
  }
  return build_deck_mesh(b.mesh, report, t0);
}

}  // namespace ffr::preproc::detail
