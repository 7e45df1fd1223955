#include "ffr/formats/json_input.hpp"
#include "ffr/preproc/part/part.hpp"
#include "ffr/preproc/solver/parallel_session.hpp"
#include "ffr/preproc/solver/dense_kernel_choice.hpp"

#include "../mesh/bdf_reader.hpp"
#include "../mesh/inp_reader.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>

namespace ffr::preproc {
namespace {

using formats::FormatError;
using formats::JsonNode;

// A group, interface, node or mass name: the SID names nodes by it and the model file refers
// to it, so an empty one is refused here, with its field, not later by the SID's validation.
std::string name_of(const JsonNode& n) {
  const std::string name = n.at("name").string();
  if (name.empty()) n.at("name").fail("must not be empty");
  return name;
}

// Bounds on sqrt(E / rho), the bar wave speed, in m/s. Solids run from about 20 m/s (soft
// rubber) to 18 km/s (diamond); a value out of [10, 1e5] m/s is a unit mistake, not a material.
// Metals are near 5 km/s, and the usual mistakes move them by a factor 1000 or more: SI values
// in a part declared in mm and t, or E in MPa in SI (5 m/s), E in MPa with rho in kg/m^3 in mm
// (5 mm/s), E in Pa with rho in t/mm^3 (5e6 m/s), E in GPa (0.16 m/s), rho in t/m^3 (1.6e5 m/s).
constexpr double kSlowestWave = 10.0, kFastestWave = 1e5;

double length_in_m(const std::string& u) { return u == "mm" ? 1e-3 : u == "cm" ? 1e-2 : 1.0; }
double time_in_s(const std::string& u) { return u == "ms" ? 1e-3 : 1.0; }

// Why the material is not one of a solid in the part's units, or empty.
std::string unit_problem(const Material& m, const Units& u) {
  if (m.rho > 0) {
    const double c = std::sqrt(m.E / m.rho);  // length / time of the part's units
    const double c_si = c * length_in_m(u.length) / time_in_s(u.time);
    if (!(c_si >= kSlowestWave && c_si <= kFastestWave)) {
      char buf[160];
      std::snprintf(buf, sizeof buf, "sqrt(E / rho) = %.3g %s/%s (%.3g m/s), where solids have 20 m/s to 18 km/s", c,
                    u.length.c_str(), u.time.c_str(), c_si);
      return std::string(buf) + ": E and rho are not in the part's units (length " + u.length + ", mass " + u.mass +
             ", time " + u.time + "; E in MPa goes with lengths in mm and rho in t/mm^3)";
    }
  }
  return {};
}

Material read_material(const JsonNode& n, const Units& u) {
  Material m;
  m.E = n.at("E").positive();
  m.nu = n.at("nu").number();
  if (!(m.nu > -1.0 && m.nu < 0.5)) n.at("nu").fail("Poisson's ratio must lie in (-1, 0.5)");
  m.rho = n.at("rho").non_negative();
  if (const std::string p = unit_problem(m, u); !p.empty()) n.fail(p);
  return m;
}

// The deck's solid and shell sections for the element sets the part file gives no property
// for, checked as the part file's own materials are.
void add_deck_sections(PartSpec& p) {
  std::set<std::string> given;
  for (const auto& m : p.materials) given.insert(m.group);
  for (const auto& s : p.shells) given.insert(s.group);
  for (const auto& b : p.beams) given.insert(b.group);
  const std::string deck = p.geometry.string();
  const std::vector<detail::DeckSection> sections =
      detail::is_inp(p.geometry) ? detail::read_inp_sections(deck) : detail::read_bdf_sections(deck);
  for (const auto& s : sections) {
    if (given.count(s.group)) continue;
    if (!s.problem.empty()) throw FormatError(deck, s.where, s.problem);
    if (!(s.mat.E > 0)) throw FormatError(deck, s.where, "Young's modulus must be positive");
    if (!(s.mat.nu > -1.0 && s.mat.nu < 0.5)) throw FormatError(deck, s.where, "Poisson's ratio must lie in (-1, 0.5)");
    if (!(s.mat.rho >= 0)) throw FormatError(deck, s.where, "the density must not be negative");
    if (const std::string why = unit_problem(s.mat, p.units); !why.empty()) throw FormatError(deck, s.where, why);
    if (s.kind == detail::DeckSection::Kind::Shell) p.shells.push_back({s.group, s.thickness, s.mat});
    else if (s.kind == detail::DeckSection::Kind::Beam) p.beams.push_back(s.beam);
    else p.materials.push_back({s.group, s.mat});
  }
  // Nastran's CONM2: attached masses on their grids (named conm2_<EID>), as "point_masses".
  if (detail::is_bdf(p.geometry))
    for (const auto& m : detail::read_bdf_point_masses(deck)) {
      PointMassSpec s;
      s.name = "conm2_" + std::to_string(m.eid);
      s.at = m.at;
      s.mass = m.mass;
      s.com_offset = m.offset;
      s.inertia = m.inertia;
      p.point_masses.push_back(s);
    }
}

Units read_units(const JsonNode& n) {
  n.allow_only({"length", "mass", "time"});
  Units u;
  u.length = n.string_or("length", "m");
  u.mass = n.string_or("mass", "kg");
  u.time = n.string_or("time", "s");
  const std::set<std::string> L{"m", "mm", "cm"}, M{"kg", "t", "g"}, T{"s", "ms"};
  if (!L.count(u.length)) n.at("length").fail("unknown length unit '" + u.length + "' (m, mm, cm)");
  if (!M.count(u.mass)) n.at("mass").fail("unknown mass unit '" + u.mass + "' (kg, t, g)");
  if (!T.count(u.time)) n.at("time").fail("unknown time unit '" + u.time + "' (s, ms)");
  return u;
}

MeshSpec read_mesh(const JsonNode& n) {
  n.allow_only({"size", "order", "optimize", "time_limit_s"});
  MeshSpec m;
  if (auto s = n.find("size")) m.size = s->positive();
  if (auto o = n.find("order")) {
    m.order = o->small_integer();
    if (m.order != 1 && m.order != 2) o->fail("mesh order must be 1 or 2");
  }
  m.optimize = n.boolean_or("optimize", true);
  if (auto t = n.find("time_limit_s")) m.time_limit_s = t->positive();
  return m;
}

GroupDef read_group(const JsonNode& n) {
  n.allow_only({"name", "dim", "entities", "box"});
  GroupDef g;
  g.name = name_of(n);
  g.dim = n.at("dim").small_integer();
  if (g.dim < 0 || g.dim > 3) n.at("dim").fail("dimension must be 0, 1, 2 or 3");
  if (auto e = n.find("entities"))
    for (const auto& t : e->items()) g.entities.push_back(t.small_integer());
  if (auto b = n.find("box")) {
    const auto v = b->numbers();
    if (v.size() != 6) b->fail("expected [xmin, ymin, zmin, xmax, ymax, zmax]");
    g.box = std::array<double, 6>{v[0], v[1], v[2], v[3], v[4], v[5]};
    if (v[0] > v[3] || v[1] > v[4] || v[2] > v[5]) b->fail("box minimum exceeds maximum");
  }
  if (g.entities.empty() && !g.box) n.fail("a group needs \"entities\" or \"box\"");
  return g;
}

BeamProps read_beam(const JsonNode& n, const Units& u) {
  n.allow_only({"group", "E", "nu", "rho", "section", "y_axis"});
  BeamProps b;
  b.group = n.at("group").string();
  b.mat = read_material(n, u);
  const JsonNode s = n.at("section");
  s.allow_only({"A", "Iy", "Iz", "J", "ky", "kz"});
  b.A = s.at("A").positive();
  b.Iy = s.at("Iy").positive();
  b.Iz = s.at("Iz").positive();
  b.J = s.at("J").positive();
  if (auto k = s.find("ky")) b.ky = k->positive();
  if (auto k = s.find("kz")) b.kz = k->positive();
  if (auto y = n.find("y_axis")) {
    b.y_axis = y->vec3();
    // Only its direction counts: where a later norm would underflow, scaled to a largest
    // component of 1 (only there, so that ordinary inputs give the same bits as before).
    const double largest = b.y_axis.cwiseAbs().maxCoeff();
    if (!(largest > 0)) y->fail("y_axis must not be zero");
    if (largest < 1e-150) b.y_axis /= largest;
  }
  return b;
}

PointMassSpec read_point_mass(const JsonNode& n) {
  n.allow_only({"name", "at", "mass", "com_offset", "inertia", "interface"});
  PointMassSpec p;
  p.name = name_of(n);
  p.mass = n.at("mass").positive();
  if (auto i = n.find("interface")) p.interface = i->string();
  if (auto a = n.find("at")) p.at = a->vec3();
  else if (p.interface.empty()) n.fail("a point mass needs \"at\" or \"interface\"");
  if (auto c = n.find("com_offset")) p.com_offset = c->vec3();
  if (auto i = n.find("inertia")) {
    p.inertia = i->mat3();
    if ((p.inertia - p.inertia.transpose()).norm() > 1e-12 * p.inertia.norm()) i->fail("inertia tensor must be symmetric");
    const Eigen::Vector3d ev = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(p.inertia).eigenvalues();
    const double tol = 1e-12 * ev.cwiseAbs().maxCoeff();
    if (ev.minCoeff() < -tol) i->fail("inertia tensor must be positive semi-definite");
    // Principal moments of a physical body satisfy the triangle inequality.
    if (ev(0) + ev(1) < ev(2) - tol) i->fail("principal moments violate the triangle inequality (not a physical body)");
  }
  return p;
}

InterfaceSpec read_interface(const JsonNode& n) {
  n.allow_only({"name", "group", "coupling", "at"});
  InterfaceSpec i;
  i.name = name_of(n);
  i.group = n.at("group").string();
  i.coupling = n.string_or("coupling", "rigid");
  if (i.coupling != "rigid" && i.coupling != "averaged") n.at("coupling").fail("coupling must be \"rigid\" or \"averaged\"");
  if (auto a = n.find("at")) i.at = a->vec3();
  return i;
}

ReductionSpec read_reduction(const JsonNode& n) {
  n.allow_only({"method", "interface", "interfaces", "frame", "modes", "max_frequency_hz", "orthonormalize", "backend", "factorization",
                "dense_kernels", "mumps_ordering", "out_of_core", "out_of_core_dir"});
  ReductionSpec r;
  const std::string m = n.at("method").string();
  if (m == "free") r.method = ReductionSpec::Method::Free;
  else if (m == "clamped") r.method = ReductionSpec::Method::Clamped;
  else if (m == "craig-bampton") r.method = ReductionSpec::Method::CraigBampton;
  else n.at("method").fail("unknown method '" + m + "' (free, clamped, craig-bampton)");
  if (auto k = n.find("modes")) {
    const long long v = k->integer();
    if (v < 0 || v > 10000) k->fail("number of modes must lie in 0..10000");
    r.modes = static_cast<int>(v);
  }
  if (auto f = n.find("max_frequency_hz")) {
    // Two stopping rules for one eigen-solve: which one holds is not the user's to guess.
    if (n.has("modes")) f->fail("give either \"modes\" (a count) or \"max_frequency_hz\", not both");
    r.max_frequency_hz = f->positive();
  }
  // Keys of another method would be ignored without a word: refused, so that a part file
  // says what it computes.
  const auto foreign = [&](const char* key, const char* methods) {
    if (n.has(key)) n.at(key).fail(std::string("not a key of method \"") + m + "\" (it belongs to " + methods + ")");
  };
  if (r.method != ReductionSpec::Method::Clamped) foreign("interface", "\"clamped\"");
  if (r.method != ReductionSpec::Method::CraigBampton) {
    foreign("interfaces", "\"craig-bampton\"");
    foreign("frame", "\"craig-bampton\"");
    foreign("orthonormalize", "\"craig-bampton\"");
  }
  if (r.modes == 0 && !r.max_frequency_hz && r.method != ReductionSpec::Method::CraigBampton)
    n.fail("give \"modes\" (a count) or \"max_frequency_hz\"");
  r.orthonormalize = n.boolean_or("orthonormalize", false);
  r.backend = n.string_or("backend", "block");
  if (r.backend != "spectra" && r.backend != "arpack" && r.backend != "block" && r.backend != "slepc")
    n.at("backend").fail("backend must be \"block\", \"spectra\", \"arpack\" or \"slepc\"");
  if (r.backend == "slepc" && !slepc_available())
    n.at("backend").fail("backend \"slepc\" is not built into this program (configure with -DFFR_SLEPC=ON and "
                         "Debian's slepc-dev, petsc-dev and libopenmpi-dev)");
  // MUMPS's choices: the slepc backend's only (the serial path orders and factorizes itself).
  for (const char* key : {"mumps_ordering", "out_of_core", "out_of_core_dir"}) {
    if (!n.has(key)) continue;
    if (r.backend != "slepc") n.at(key).fail("only for backend \"slepc\" (MUMPS's factorization); the serial path has its own");
    r.mumps.keys_given.emplace_back(key);
  }
  if (auto o = n.find("mumps_ordering")) {
    r.mumps.ordering = o->string();
    if (mumps_ordering_code(r.mumps.ordering) < 0)
      o->fail("unknown MUMPS ordering '" + r.mumps.ordering + "' (" + mumps_ordering_names() + ")");
  }
  r.mumps.out_of_core = n.boolean_or("out_of_core", false);
  if (auto d = n.find("out_of_core_dir")) {
    if (!r.mumps.out_of_core) d->fail("a directory for out-of-core factors needs \"out_of_core\": true");
    r.mumps.out_of_core_dir = d->string();  // made absolute and checked by load_part
    if (r.mumps.out_of_core_dir.empty()) d->fail("an empty directory name");
  }
  r.factorization = n.string_or("factorization", "supernodal");
  if (r.factorization != "supernodal" && r.factorization != "cholmod")
    n.at("factorization").fail("factorization must be \"supernodal\" or \"cholmod\"");
  r.dense_kernels = n.string_or("dense_kernels", "auto");
  if (!dense_kernel_choice_from_string(r.dense_kernels))
    n.at("dense_kernels").fail("dense_kernels must be \"auto\", \"blas\" or \"eigen\"");
  if (r.factorization == "cholmod" && r.dense_kernels != "auto")
    n.at("dense_kernels").fail("only for factorization \"supernodal\" (CHOLMOD's factorization calls the BLAS itself)");
  if (r.method == ReductionSpec::Method::Clamped) r.interface = n.at("interface").string();
  if (r.method == ReductionSpec::Method::CraigBampton) {
    for (const auto& i : n.at("interfaces").items()) r.interfaces.push_back(i.string());
    if (r.interfaces.empty()) n.at("interfaces").fail("craig-bampton needs at least one interface");
    r.frame = n.has("frame") ? n.at("frame").string() : r.interfaces.front();
  }
  return r;
}

DampingSpec read_damping(const JsonNode& n) {
  n.allow_only({"ratio", "rayleigh"});
  DampingSpec d;
  if (auto r = n.find("ratio")) {
    d.kind = DampingSpec::Kind::Ratio;
    d.ratio = r->non_negative();
    if (d.ratio >= 1) r->fail("damping ratio must be below 1");
  } else if (auto r = n.find("rayleigh")) {
    r->allow_only({"alpha", "beta"});
    d.kind = DampingSpec::Kind::Rayleigh;
    d.alpha = r->number_or("alpha", 0);
    d.beta = r->number_or("beta", 0);
    if (d.alpha < 0 || d.beta < 0) r->fail("Rayleigh coefficients must be >= 0");
  }
  return d;
}

PreloadSpec read_preload(const JsonNode& n) {
  n.allow_only({"gravity", "loads"});
  PreloadSpec p;
  if (auto g = n.find("gravity")) p.gravity = g->vec3();
  if (auto ls = n.find("loads"))
    for (const auto& l : ls->items()) {
      l.allow_only({"interface", "force", "moment"});
      PreloadSpec::Load load;
      load.interface = l.at("interface").string();
      if (auto f = l.find("force")) load.force = f->vec3();
      if (auto m = l.find("moment")) load.moment = m->vec3();
      p.loads.push_back(load);
    }
  return p;
}

}  // namespace

const InterfaceSpec* PartSpec::find_interface(const std::string& name) const {
  for (const auto& i : interfaces)
    if (i.name == name) return &i;
  return nullptr;
}

// "matrices": K and M from another FE code. What needs element stresses or ffr's element
// kernels is refused here, by the field that asks for it.
MatrixInputSpec read_matrices(const JsonNode& n, const PartSpec& p) {
  n.allow_only({"K", "M", "format", "dofs", "K_name", "M_name"});
  MatrixInputSpec m;
  const std::string f = n.at("format").string();
  if (f == "matrix_market") m.format = MatrixInputSpec::Format::MatrixMarket;
  else if (f == "calculix") m.format = MatrixInputSpec::Format::Calculix;
  else if (f == "abaqus") m.format = MatrixInputSpec::Format::Abaqus;
  else if (f == "dmig") m.format = MatrixInputSpec::Format::Dmig;
  else n.at("format").fail("unknown matrix format '" + f + "' (matrix_market, calculix, abaqus, dmig)");
  // Abaqus and DMIG entries name their node and DOF: no DOF map.
  const bool by_node = m.format == MatrixInputSpec::Format::Abaqus || m.format == MatrixInputSpec::Format::Dmig;
  if (by_node && n.has("dofs")) n.at("dofs").fail("not used with format '" + f + "': its entries name their nodes and DOFs");
  for (const char* key : {"K_name", "M_name"})
    if (n.has(key)) {
      if (m.format != MatrixInputSpec::Format::Dmig) n.at(key).fail("only for format 'dmig' (the DMIG matrix's name)");
      const std::string v = n.at(key).string();
      if (v.empty() || v.size() > 8) n.at(key).fail("a DMIG name of 1 to 8 characters is expected");
      (key[0] == 'K' ? m.K_name : m.M_name) = v;
    }
  const auto dir = p.file.parent_path();
  auto file = [&](const char* key, std::filesystem::path& out) {
    const JsonNode k = n.at(key);
    out = dir / k.string();
    std::error_code ec;
    if (!std::filesystem::is_regular_file(out, ec)) k.fail("file not found: " + out.string());
  };
  file("K", m.K);
  file("M", m.M);
  if (n.has("dofs")) file("dofs", m.dofs);
  else if (m.format == MatrixInputSpec::Format::Calculix) {
    // ccx's *MATRIX STORAGE writes job.sti, job.mas and job.dof side by side.
    m.dofs = m.K;
    m.dofs.replace_extension(".dof");
    std::error_code ec;
    if (!std::filesystem::is_regular_file(m.dofs, ec))
      n.fail("no \"dofs\" given and no " + m.dofs.string() + " beside K (CalculiX writes job.dof with job.sti)");
  } else if (!by_node) n.at("dofs");  // required: fails naming the field
  if (!detail::is_inp(p.geometry) && !detail::is_bdf(p.geometry))
    n.fail("assembled matrices need the nodes of an FE deck as \"geometry\" (.inp, .bdf/.dat/.nas)");
  if (p.stiffening)
    n.fail("\"stiffening\": true needs element stresses, which assembled matrices do not have; drop it or give "
           "the elements");
  if (!p.preload.empty()) n.fail("a \"preload\" needs element stresses, which assembled matrices do not have");
  if (p.stress) n.fail("\"stress\" recovery needs ffr's own elements and material, which assembled matrices do not have");
  for (const auto& pm : p.point_masses)
    if (pm.name.rfind("conm2_", 0) == 0 && detail::is_bdf(p.geometry))
      n.fail("the deck's CONM2 " + pm.name.substr(6) + " cannot be added to assembled matrices; the mass matrix must " +
             "hold it (drop the CONM2 cards from the deck given as \"geometry\")");
  if (!p.point_masses.empty())
    n.fail("\"point_masses\" cannot be added to assembled matrices; put them into the mass matrix");
  return m;
}

PartSpec load_part(const std::filesystem::path& path) {
  const auto doc = formats::JsonDocument::load(path);
  const JsonNode root = doc.root();
  if (!root.is_object()) root.fail("a part file is a JSON object");
  root.allow_only({"geometry", "mesh", "units", "groups", "materials", "shells", "beams", "point_masses",
                   "interfaces", "reduction", "stiffening", "preload", "output_nodes", "damping", "visual", "stress", "comment",
                   "matrices"});
  PartSpec p;
  p.file = path;
  const JsonNode g = root.at("geometry");
  p.geometry = path.parent_path() / g.string();
  {
    const auto ext = p.geometry.extension().string();
    if (ext != ".geo" && ext != ".step" && ext != ".stp" && ext != ".brep" && ext != ".msh" && ext != ".STEP" &&
        ext != ".STP" && !detail::is_inp(p.geometry) && !detail::is_bdf(p.geometry))
      g.fail("unsupported geometry '" + ext + "' (.geo, .step/.stp, .brep, .msh, .inp, or .bdf/.dat/.nas)");
    std::error_code ec;
    if (!std::filesystem::exists(p.geometry, ec)) g.fail("file not found: " + p.geometry.string());
    // gmsh and the readers take the geometry whole: a directory, device or pipe (a link to
    // /dev/zero read until memory ran out) is refused here.
    if (!std::filesystem::is_regular_file(p.geometry, ec)) g.fail("not a regular file: " + p.geometry.string());
  }
  if (auto u = root.find("units")) p.units = read_units(*u);
  if (auto m = root.find("mesh")) p.mesh = read_mesh(*m);
  if (auto gs = root.find("groups"))
    for (const auto& n : gs->items()) p.groups.push_back(read_group(n));
  if (auto ms = root.find("materials"))
    for (const auto& n : ms->items()) {
      n.allow_only({"group", "E", "nu", "rho"});
      p.materials.push_back({n.at("group").string(), read_material(n, p.units)});
    }
  if (auto ss = root.find("shells"))
    for (const auto& n : ss->items()) {
      n.allow_only({"group", "thickness", "E", "nu", "rho"});
      p.shells.push_back({n.at("group").string(), n.at("thickness").positive(), read_material(n, p.units)});
    }
  if (auto bs = root.find("beams"))
    for (const auto& n : bs->items()) p.beams.push_back(read_beam(n, p.units));
  if (detail::is_inp(p.geometry) || detail::is_bdf(p.geometry)) {
    if (root.has("groups")) root.at("groups").fail("\"groups\" are made from CAD entities; a deck's groups are its sets");
    add_deck_sections(p);
  }
  if (p.materials.empty() && p.shells.empty() && p.beams.empty())
    root.fail("the part has no material: give \"materials\", \"shells\" or \"beams\" (or sections in its deck)");
  if (auto pm = root.find("point_masses"))
    for (const auto& n : pm->items()) p.point_masses.push_back(read_point_mass(n));
  if (auto is = root.find("interfaces"))
    for (const auto& n : is->items()) p.interfaces.push_back(read_interface(n));
  p.reduction = read_reduction(root.at("reduction"));
  if (!p.reduction.mumps.out_of_core_dir.empty()) {
    // Relative to the part file, as the geometry; it must exist and take files on every rank.
    const JsonNode d = root.at("reduction").at("out_of_core_dir");
    const std::filesystem::path dir = std::filesystem::absolute(path.parent_path() / p.reduction.mumps.out_of_core_dir);
    std::error_code ec;
    if (!std::filesystem::is_directory(dir, ec)) d.fail("not a directory: " + dir.string());
    p.reduction.mumps.out_of_core_dir = dir.string();
  }
  if (auto d = root.find("damping")) p.damping = read_damping(*d);
  p.stiffening = root.boolean_or("stiffening", false);
  if (auto pl = root.find("preload")) p.preload = read_preload(*pl);
  p.visual = root.boolean_or("visual", true);
  if (auto os = root.find("output_nodes"))
    for (const auto& n : os->items()) {
      n.allow_only({"name", "at"});
      p.output_nodes.push_back({name_of(n), n.at("at").vec3()});
    }
  if (auto st = root.find("stress")) {
    if (!st->is_object()) st->fail("expected an object: {\"group\": NAME} or {\"surface\": true}");
    st->allow_only({"group", "surface"});
    StressSpec s;
    if (auto g = st->find("group")) {
      s.group = g->string();
      if (s.group.empty()) g->fail("empty group name");
    }
    s.surface = st->boolean_or("surface", false);
    if (s.surface == !s.group.empty())
      st->fail(s.surface ? "give either \"group\" or \"surface\": true, not both"
                         : "give \"group\": NAME or \"surface\": true");
    p.stress = s;
  }

  if (auto mx = root.find("matrices")) p.matrices = read_matrices(*mx, p);

  // Cross-references that need no mesh.
  std::set<std::string> names;
  for (std::size_t i = 0; i < p.interfaces.size(); ++i)
    if (!names.insert(p.interfaces[i].name).second)
      root.at("interfaces").items()[i].at("name").fail("duplicate interface name '" + p.interfaces[i].name + "'");
  for (std::size_t i = 0; i < p.output_nodes.size(); ++i)
    if (!names.insert(p.output_nodes[i].name).second)
      root.at("output_nodes").items()[i].at("name").fail("duplicate node name '" + p.output_nodes[i].name + "'");
  const JsonNode red = root.at("reduction");
  if (p.reduction.method == ReductionSpec::Method::Clamped && !p.find_interface(p.reduction.interface))
    red.at("interface").fail("no interface named '" + p.reduction.interface + "' in \"interfaces\"");
  if (p.reduction.method == ReductionSpec::Method::CraigBampton) {
    for (std::size_t i = 0; i < p.reduction.interfaces.size(); ++i)
      if (!p.find_interface(p.reduction.interfaces[i]))
        red.at("interfaces").items()[i].fail("no interface named '" + p.reduction.interfaces[i] + "' in \"interfaces\"");
    if (std::find(p.reduction.interfaces.begin(), p.reduction.interfaces.end(), p.reduction.frame) ==
        p.reduction.interfaces.end())
      red.at("frame").fail("the frame interface must be one of \"interfaces\"");
  }
  for (std::size_t i = 0; i < p.point_masses.size(); ++i)
    if (!p.point_masses[i].interface.empty() && !p.find_interface(p.point_masses[i].interface))
      root.at("point_masses").items()[i].at("interface").fail("no interface named '" + p.point_masses[i].interface + "'");
  for (std::size_t i = 0; i < p.preload.loads.size(); ++i)
    if (!p.find_interface(p.preload.loads[i].interface))
      root.at("preload").at("loads").items()[i].at("interface").fail("no interface named '" + p.preload.loads[i].interface + "'");
  return p;
}

}  // namespace ffr::preproc
