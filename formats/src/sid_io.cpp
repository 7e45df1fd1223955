#include "ffr/formats/sid_io.hpp"

#include "ffr/version.hpp"

#include <set>
#include <sstream>
#include <stdexcept>

namespace ffr::formats {
namespace {

using h5::Shape;
using u64 = std::uint64_t;

// ---- C-order packing between Eigen objects and flat buffers ------------------------------

template <class M>
void append(std::vector<double>& out, const M& m) {
  for (Eigen::Index r = 0; r < m.rows(); ++r)
    for (Eigen::Index c = 0; c < m.cols(); ++c) out.push_back(m(r, c));
}

template <class M>
std::vector<double> flat(const M& m) {
  std::vector<double> out;
  out.reserve(static_cast<std::size_t>(m.size()));
  append(out, m);
  return out;
}

template <class M>
std::vector<double> flat(const std::vector<M>& v) {
  std::vector<double> out;
  for (const auto& m : v) append(out, m);
  return out;
}

template <class M>
void unflat(const double* p, M& m) {
  for (Eigen::Index r = 0; r < m.rows(); ++r)
    for (Eigen::Index c = 0; c < m.cols(); ++c) m(r, c) = *p++;
}

Shape S(std::initializer_list<u64> d) { return Shape(d); }

// ---- writing ---------------------------------------------------------------------------

void write_matrix(h5::Writer& w, const std::string& path, const Eigen::MatrixXd& m) {
  const auto v = flat(m);
  w.write(path, v.data(), S({u64(m.rows()), u64(m.cols())}));
}

template <class M>
void write_stack(h5::Writer& w, const std::string& path, const std::vector<M>& v, u64 rows, u64 cols) {
  const auto f = flat(v);
  w.write(path, f.data(), S({u64(v.size()), rows, cols}));
}

void write_provenance(h5::Writer& w, const Provenance& p) {
  w.ensure_group("/provenance");
  w.attr("/provenance", "generator", p.generator.empty() ? std::string(kGenerator) : p.generator);
  w.attr("/provenance", "part_sha256", p.part_sha256);
  w.attr("/provenance", "mesh_sha256", p.mesh_sha256);
  w.attr("/provenance", "reduction_method", p.reduction_method);
  w.attr("/provenance", "reduction_parameters", p.reduction_parameters);
  w.attr("/provenance", "damping_model", p.damping_model);
  w.ensure_group("/provenance/element_counts");
  for (const auto& [k, v] : p.element_counts) w.attr("/provenance/element_counts", k, static_cast<std::int64_t>(v));
  w.ensure_group("/provenance/mass_model");
  for (const auto& [k, v] : p.mass_model) w.attr("/provenance/mass_model", k, v);
  w.ensure_group("/provenance/extra");
  for (const auto& [k, v] : p.extra) w.attr("/provenance/extra", k, v);
}

void write_all(const Sid& s, h5::Writer& w) {
  const u64 nq = static_cast<u64>(s.nq());
  const u64 N = static_cast<u64>(s.nodes.size());

  w.attr("/", "format", std::string(kFormatName));
  w.attr("/", "format_version", static_cast<std::int64_t>(kFormatVersion));
  w.attr("/", "units_length", s.units_length);
  w.attr("/", "units_mass", s.units_mass);
  w.attr("/", "units_time", s.units_time);
  w.attr("/", "generator", s.provenance.generator.empty() ? std::string(kGenerator) : s.provenance.generator);

  // /refmod
  w.write_scalar("/refmod/mass", s.refmod.mass);
  w.write("/refmod/frequency_hz", s.refmod.frequency_hz.data(), S({nq}));
  std::vector<std::string> types;
  for (auto t : s.refmod.mode_type) types.emplace_back(to_string(t));
  w.write_strings("/refmod/mode_type", types);
  w.write_string("/refmod/reference", s.refmod.reference);

  // /sid members
  w.write("/sid/mdCM/M0", s.mdCM.M0.data(), S({3}));
  { const auto v = flat(s.mdCM.M1); w.write("/sid/mdCM/M1", v.data(), S({nq, 3})); }
  { const auto v = flat(s.J.M0); w.write("/sid/J/M0", v.data(), S({3, 3})); }
  write_stack(w, "/sid/J/M1", s.J.M1, 3, 3);
  { const auto v = flat(s.Ct.M0); w.write("/sid/Ct/M0", v.data(), S({nq, 3})); }
  { const auto v = flat(s.Cr.M0); w.write("/sid/Cr/M0", v.data(), S({nq, 3})); }
  write_stack(w, "/sid/Cr/M1", s.Cr.M1, nq, 3);
  write_matrix(w, "/sid/Me/M0", s.Me);
  write_matrix(w, "/sid/Ke/M0", s.Ke);
  if (!s.KeM1.empty()) write_stack(w, "/sid/Ke/M1", s.KeM1, nq, nq);
  write_matrix(w, "/sid/De/M0", s.De);
  write_stack(w, "/sid/Gr/M0", s.Gr, 3, 3);
  write_stack(w, "/sid/Ge/M0", s.Ge, nq, 3);
  { const auto v = flat(s.Oe.M0); w.write("/sid/Oe/M0", v.data(), S({nq, 6})); }
  write_stack(w, "/sid/Oe/M1", s.Oe.M1, nq, 6);
  w.write("/sid/ksigma/M0", s.ksigma.M0.data(), S({nq}));
  write_matrix(w, "/sid/ksigma/M1", s.ksigma.M1);
  w.attr("/sid/De", "model", s.provenance.damping_model);
  for (const auto& [group, model] : s.provenance.mass_model)
    if (group.rfind("/", 0) == 0) w.attr(group, "mass_model", model);

  // /integrals
  const auto& I = s.integrals;
  w.write("/integrals/rdm", I.rdm.data(), S({3}));
  { const auto v = flat(I.rrdm); w.write("/integrals/rrdm", v.data(), S({3, 3})); }
  { const auto v = flat(I.Pdm); w.write("/integrals/Pdm", v.data(), S({3, nq})); }
  { std::vector<double> v; for (const auto& m : I.rPdm) append(v, m);
    w.write("/integrals/rPdm", v.data(), S({3, 3, nq})); }
  { std::vector<double> v; for (const auto& row : I.PPdm) for (const auto& m : row) append(v, m);
    w.write("/integrals/PPdm", v.data(), S({3, 3, nq, nq})); }
  { const auto v = flat(s.rotary.I); w.write("/integrals/rotary/I", v.data(), S({3, 3})); }
  { const auto v = flat(s.rotary.PsiI); w.write("/integrals/rotary/PsiI", v.data(), S({nq, 3})); }
  write_matrix(w, "/integrals/rotary/PsiIPsi", s.rotary.PsiIPsi);

  // /stiffening (only when computed)
  if (s.stiffening) {
    const auto& st = *s.stiffening;
    write_stack(w, "/stiffening/K0t", st.K0t, nq, 3);
    write_stack(w, "/stiffening/K0r", st.K0r, nq, 3);
    write_stack(w, "/stiffening/K0om", st.K0om, nq, 6);
    std::vector<std::string> names;
    for (const auto& i : st.interfaces) {
      names.push_back(i.name);
      write_stack(w, "/stiffening/interfaces/" + i.name + "/K0F", i.K0F, nq, 3);
      write_stack(w, "/stiffening/interfaces/" + i.name + "/K0M", i.K0M, nq, 3);
    }
    w.write_strings("/stiffening/interface_names", names);
  }

  // /nodes
  std::vector<std::string> names;
  std::vector<double> origin, phi, psi, ap0;
  for (const auto& n : s.nodes) {
    names.push_back(n.name);
    append(origin, n.origin.transpose());
    append(phi, n.phi);
    append(psi, n.psi);
    append(ap0, n.AP0);
  }
  w.write_strings("/nodes/name", names);
  w.write("/nodes/origin", origin.data(), S({N, 3}));
  w.write("/nodes/phi", phi.data(), S({N, 3, nq}));
  w.write("/nodes/psi", psi.data(), S({N, 3, nq}));
  w.write("/nodes/AP0", ap0.data(), S({N, 3, 3}));

  // /interfaces
  std::vector<std::string> iname, icoupling, igroup;
  std::vector<std::int64_t> inode;
  for (const auto& i : s.interfaces) {
    iname.push_back(i.name);
    icoupling.push_back(i.coupling);
    igroup.push_back(i.group);
    inode.push_back(i.node);
  }
  w.write_strings("/interfaces/name", iname);
  w.write("/interfaces/node", inode.data(), S({u64(inode.size())}));
  w.write_strings("/interfaces/coupling", icoupling);
  w.write_strings("/interfaces/group", igroup);

  // /visual (optional)
  if (!s.visual.empty()) {
    const u64 nv = static_cast<u64>(s.visual.vertices.rows());
    w.write("/visual/vertices", s.visual.vertices.data(), S({nv, 3}));
    w.write("/visual/triangles", s.visual.triangles.data(), S({u64(s.visual.triangles.rows()), 3}));
    std::vector<double> modes;
    for (const auto& m : s.visual.modes) modes.insert(modes.end(), m.data(), m.data() + m.size());
    w.write("/visual/modes", modes.data(), S({nq, nv, 3}));
  }

  if (s.stress) write_modal_stress(w, *s.stress);

  write_provenance(w, s.provenance);
}

// ---- reading ---------------------------------------------------------------------------

template <class M>
void read_matrix(const h5::Reader& r, const std::string& path, M& m, u64 rows, u64 cols) {
  const auto v = r.read_array(path, S({rows, cols}));
  m.resize(static_cast<Eigen::Index>(rows), static_cast<Eigen::Index>(cols));
  unflat(v.data(), m);
}

template <class M>
void read_stack(const h5::Reader& r, const std::string& path, std::vector<M>& out, u64 n, u64 rows, u64 cols) {
  const auto v = r.read_array(path, S({n, rows, cols}));
  out.assign(static_cast<std::size_t>(n), M(static_cast<Eigen::Index>(rows), static_cast<Eigen::Index>(cols)));
  for (u64 k = 0; k < n; ++k) unflat(v.data() + k * rows * cols, out[k]);
}

u64 rank1_length(const h5::Reader& r, const std::string& path) {
  const Shape sh = r.shape(path);
  if (sh.size() != 1) r.fail(path, "wrong shape: expected rank 1, found " + h5::shape_string(sh));
  return sh[0];
}

Provenance read_provenance(const h5::Reader& r) {
  Provenance p;
  if (!r.exists("/provenance")) return p;
  for (const auto& [k, v] : r.attrs("/provenance")) {
    if (k == "generator") p.generator = v;
    else if (k == "part_sha256") p.part_sha256 = v;
    else if (k == "mesh_sha256") p.mesh_sha256 = v;
    else if (k == "reduction_method") p.reduction_method = v;
    else if (k == "reduction_parameters") p.reduction_parameters = v;
    else if (k == "damping_model") p.damping_model = v;
    else p.extra[k] = v;
  }
  for (const auto& [k, v] : r.attrs("/provenance/element_counts")) p.element_counts[k] = r.attr_int("/provenance/element_counts", k);
  for (const auto& [k, v] : r.attrs("/provenance/mass_model")) p.mass_model[k] = v;
  for (const auto& [k, v] : r.attrs("/provenance/extra")) p.extra[k] = v;
  return p;
}

}  // namespace

void check_sizes(const Sid& s) {
  const Eigen::Index nq = s.nq();
  const auto sn = static_cast<std::size_t>(nq);
  auto bad = [](const std::string& what) { throw std::invalid_argument("SID member " + what + " has the wrong size"); };
  if (static_cast<Eigen::Index>(s.refmod.mode_type.size()) != nq) bad("refmod.mode_type");
  if (s.mdCM.M1.rows() != nq) bad("mdCM.M1");
  if (s.J.M1.size() != sn) bad("J.M1");
  if (s.Ct.M0.rows() != nq) bad("Ct.M0");
  if (s.Cr.M0.rows() != nq) bad("Cr.M0");
  if (s.Cr.M1.size() != sn) bad("Cr.M1");
  for (const auto& m : s.Cr.M1) if (m.rows() != nq) bad("Cr.M1");
  if (s.Me.rows() != nq || s.Me.cols() != nq) bad("Me");
  if (s.Ke.rows() != nq || s.Ke.cols() != nq) bad("Ke");
  if (s.De.rows() != nq || s.De.cols() != nq) bad("De");
  if (!s.KeM1.empty()) {
    if (s.KeM1.size() != sn) bad("Ke.M1");
    for (const auto& m : s.KeM1) if (m.rows() != nq || m.cols() != nq) bad("Ke.M1");
  }
  if (s.Gr.size() != sn) bad("Gr");
  if (s.Ge.size() != sn) bad("Ge");
  for (const auto& m : s.Ge) if (m.rows() != nq) bad("Ge");
  if (s.Oe.M0.rows() != nq) bad("Oe.M0");
  if (s.Oe.M1.size() != sn) bad("Oe.M1");
  for (const auto& m : s.Oe.M1) if (m.rows() != nq) bad("Oe.M1");
  if (s.ksigma.M0.size() != nq) bad("ksigma.M0");
  if (s.ksigma.M1.rows() != nq || s.ksigma.M1.cols() != nq) bad("ksigma.M1");
  if (s.integrals.Pdm.cols() != nq) bad("integrals.Pdm");
  for (const auto& m : s.integrals.rPdm) if (m.cols() != nq) bad("integrals.rPdm");
  for (const auto& row : s.integrals.PPdm)
    for (const auto& m : row) if (m.rows() != nq || m.cols() != nq) bad("integrals.PPdm");
  if (s.rotary.PsiI.rows() != nq) bad("integrals.rotary.PsiI");
  if (s.rotary.PsiIPsi.rows() != nq || s.rotary.PsiIPsi.cols() != nq) bad("integrals.rotary.PsiIPsi");
  if (s.stiffening) {
    const auto& st = *s.stiffening;
    if (st.K0t.size() != sn || st.K0r.size() != sn || st.K0om.size() != sn) bad("stiffening");
    for (std::size_t k = 0; k < sn; ++k)
      if (st.K0t[k].rows() != nq || st.K0r[k].rows() != nq || st.K0om[k].rows() != nq) bad("stiffening");
    for (const auto& i : st.interfaces)
      if (i.K0F.size() != sn || i.K0M.size() != sn) bad("stiffening interface " + i.name);
  }
  for (const auto& n : s.nodes)
    if (n.phi.cols() != nq || n.psi.cols() != nq) bad("node " + n.name);
  for (const auto& i : s.interfaces)
    if (i.node < 0 || i.node >= static_cast<Index>(s.nodes.size())) bad("interface " + i.name + " node index");
  if (!s.visual.empty()) {
    if (s.visual.modes.size() != sn) bad("visual.modes");
    for (const auto& m : s.visual.modes) if (m.rows() != s.visual.vertices.rows()) bad("visual.modes");
    for (Eigen::Index t = 0; t < s.visual.triangles.size(); ++t)
      if (s.visual.triangles.data()[t] < 0 || s.visual.triangles.data()[t] >= s.visual.vertices.rows()) bad("visual.triangles");
  }
  if (s.stress) check_modal_stress(*s.stress, nq);
}

void write_sid(const Sid& sid, const std::filesystem::path& path) {
  check_sizes(sid);
  h5::AtomicFile out(path);
  {
    h5::Writer w(out.temp_path(), path.string());
    write_all(sid, w);
    w.close();
  }
  out.commit();
}

std::string no_checksums_warning(const std::string& file, std::int64_t version) {
  return file + ": format_version " + std::to_string(version) +
         " has no content checksums: damage that HDF5 does not detect (a chunk index) cannot be found; "
         "write the file again with this version";
}

Sid read_sid(const std::filesystem::path& path, std::vector<std::string>* warnings) {
  h5::Reader r(path);
  return read_sid(r, warnings);
}

Sid read_sid_image(const void* image, std::size_t size, const std::string& display_name,
                   std::vector<std::string>* warnings) {
  h5::Reader r(image, size, display_name);
  return read_sid(r, warnings);
}

Sid read_sid(h5::Reader& r, std::vector<std::string>* warnings) {
  r.set_max_magnitude(kMaxInputMagnitude);
  Sid s;

  // Identity and version first: nothing else is read from a file we do not understand.
  if (!r.has_attr("/", "format")) r.fail("/@format", "missing attribute: not a SID file");
  const std::string fmt = r.attr_string("/", "format");
  if (fmt != kFormatName) r.fail("/@format", "not a SID file (format = '" + fmt + "')");
  const auto version = r.attr_int("/", "format_version");
  if (version < 1 || version > kFormatVersion)
    r.fail("/@format_version", "unsupported format_version " + std::to_string(version) +
                                   " (this build reads 1.." + std::to_string(kFormatVersion) + ")");
  if (version >= 2)
    r.require_checksums();
  else if (warnings)
    warnings->push_back(no_checksums_warning(r.name(), version));
  s.units_length = r.attr_string("/", "units_length");
  s.units_mass = r.attr_string("/", "units_mass");
  s.units_time = r.attr_string("/", "units_time");

  // Sizes: nq from the frequencies, N from the node names. Everything else must agree.
  const u64 nq = rank1_length(r, "/refmod/frequency_hz");
  const u64 N = rank1_length(r, "/nodes/name");
  if (nq > 100000) r.fail("/refmod/frequency_hz", "implausible number of modes " + std::to_string(nq));
  const Eigen::Index q = static_cast<Eigen::Index>(nq);

  s.refmod.mass = r.read_scalar("/refmod/mass");
  if (!(s.refmod.mass > 0)) r.fail("/refmod/mass", "mass must be positive");
  {
    const auto f = r.read_array("/refmod/frequency_hz", S({nq}));
    s.refmod.frequency_hz = Eigen::Map<const Eigen::VectorXd>(f.data(), q);
  }
  for (const auto& t : r.read_strings("/refmod/mode_type", nq)) {
    try {
      s.refmod.mode_type.push_back(mode_type_from_string(t));
    } catch (const std::invalid_argument& e) {
      r.fail("/refmod/mode_type", e.what());
    }
  }
  s.refmod.reference = r.read_string("/refmod/reference");

  {
    const auto v = r.read_array("/sid/mdCM/M0", S({3}));
    s.mdCM.M0 = Eigen::Vector3d(v[0], v[1], v[2]);
  }
  read_matrix(r, "/sid/mdCM/M1", s.mdCM.M1, nq, 3);
  read_matrix(r, "/sid/J/M0", s.J.M0, 3, 3);
  read_stack(r, "/sid/J/M1", s.J.M1, nq, 3, 3);
  read_matrix(r, "/sid/Ct/M0", s.Ct.M0, nq, 3);
  read_matrix(r, "/sid/Cr/M0", s.Cr.M0, nq, 3);
  read_stack(r, "/sid/Cr/M1", s.Cr.M1, nq, nq, 3);
  read_matrix(r, "/sid/Me/M0", s.Me, nq, nq);
  read_matrix(r, "/sid/Ke/M0", s.Ke, nq, nq);
  if (r.exists("/sid/Ke/M1")) read_stack(r, "/sid/Ke/M1", s.KeM1, nq, nq, nq);
  read_matrix(r, "/sid/De/M0", s.De, nq, nq);
  read_stack(r, "/sid/Gr/M0", s.Gr, nq, 3, 3);
  read_stack(r, "/sid/Ge/M0", s.Ge, nq, nq, 3);
  read_matrix(r, "/sid/Oe/M0", s.Oe.M0, nq, 6);
  read_stack(r, "/sid/Oe/M1", s.Oe.M1, nq, nq, 6);
  {
    const auto v = r.read_array("/sid/ksigma/M0", S({nq}));
    s.ksigma.M0 = Eigen::Map<const Eigen::VectorXd>(v.data(), q);
  }
  read_matrix(r, "/sid/ksigma/M1", s.ksigma.M1, nq, nq);

  auto& I = s.integrals;
  {
    const auto v = r.read_array("/integrals/rdm", S({3}));
    I.rdm = Eigen::Vector3d(v[0], v[1], v[2]);
  }
  read_matrix(r, "/integrals/rrdm", I.rrdm, 3, 3);
  read_matrix(r, "/integrals/Pdm", I.Pdm, 3, nq);
  {
    const auto v = r.read_array("/integrals/rPdm", S({3, 3, nq}));
    for (int a = 0; a < 3; ++a) {
      I.rPdm[a].resize(3, q);
      unflat(v.data() + a * 3 * nq, I.rPdm[a]);
    }
  }
  {
    const auto v = r.read_array("/integrals/PPdm", S({3, 3, nq, nq}));
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) {
        I.PPdm[a][b].resize(q, q);
        unflat(v.data() + (a * 3 + b) * nq * nq, I.PPdm[a][b]);
      }
  }
  read_matrix(r, "/integrals/rotary/I", s.rotary.I, 3, 3);
  read_matrix(r, "/integrals/rotary/PsiI", s.rotary.PsiI, nq, 3);
  read_matrix(r, "/integrals/rotary/PsiIPsi", s.rotary.PsiIPsi, nq, nq);

  if (r.exists("/stiffening")) {
    Stiffening st;
    read_stack(r, "/stiffening/K0t", st.K0t, nq, nq, 3);
    read_stack(r, "/stiffening/K0r", st.K0r, nq, nq, 3);
    read_stack(r, "/stiffening/K0om", st.K0om, nq, nq, 6);
    const u64 ni = r.exists("/stiffening/interface_names") ? rank1_length(r, "/stiffening/interface_names") : 0;
    for (const auto& name : ni ? r.read_strings("/stiffening/interface_names", ni) : std::vector<std::string>{}) {
      Stiffening::Interface i;
      i.name = name;
      read_stack(r, "/stiffening/interfaces/" + name + "/K0F", i.K0F, nq, nq, 3);
      read_stack(r, "/stiffening/interfaces/" + name + "/K0M", i.K0M, nq, nq, 3);
      st.interfaces.push_back(std::move(i));
    }
    s.stiffening = std::move(st);
  }

  {
    const auto names = r.read_strings("/nodes/name", N);
    const auto origin = r.read_array("/nodes/origin", S({N, 3}));
    const auto phi = r.read_array("/nodes/phi", S({N, 3, nq}));
    const auto psi = r.read_array("/nodes/psi", S({N, 3, nq}));
    const auto ap0 = r.read_array("/nodes/AP0", S({N, 3, 3}));
    s.nodes.resize(N);
    std::set<std::string> seen;
    for (u64 p = 0; p < N; ++p) {
      auto& n = s.nodes[p];
      n.name = names[p];
      // Model files refer to nodes by name: an empty or repeated one would bind silently.
      if (n.name.empty()) r.fail("/nodes/name", "node " + std::to_string(p) + " has an empty name");
      if (!seen.insert(n.name).second) r.fail("/nodes/name", "node name '" + n.name + "' appears twice");
      n.origin = Eigen::Vector3d(origin[3 * p], origin[3 * p + 1], origin[3 * p + 2]);
      n.phi.resize(3, q);
      n.psi.resize(3, q);
      unflat(phi.data() + p * 3 * nq, n.phi);
      unflat(psi.data() + p * 3 * nq, n.psi);
      unflat(ap0.data() + p * 9, n.AP0);
    }
  }

  {
    const u64 ni = rank1_length(r, "/interfaces/name");
    const auto names = r.read_strings("/interfaces/name", ni);
    std::vector<std::int64_t> node(ni);
    r.read("/interfaces/node", S({ni}), node.data());
    const auto coupling = r.read_strings("/interfaces/coupling", ni);
    const auto group = r.read_strings("/interfaces/group", ni);
    for (u64 i = 0; i < ni; ++i) {
      if (node[i] < 0 || static_cast<u64>(node[i]) >= N)
        r.fail("/interfaces/node", "interface '" + names[i] + "' refers to node " + std::to_string(node[i]) +
                                       " but there are " + std::to_string(N) + " nodes");
      if (coupling[i] != "rigid" && coupling[i] != "averaged")
        r.fail("/interfaces/coupling", "interface '" + names[i] + "' has coupling '" + coupling[i] + "' (rigid or averaged)");
      s.interfaces.push_back({names[i], node[i], coupling[i], group[i]});
    }
  }

  if (r.exists("/visual")) {
    const Shape vs = r.shape("/visual/vertices");
    const Shape ts = r.shape("/visual/triangles");
    if (vs.size() != 2 || vs[1] != 3) r.fail("/visual/vertices", "wrong shape: expected [Nv,3], found " + h5::shape_string(vs));
    if (ts.size() != 2 || ts[1] != 3) r.fail("/visual/triangles", "wrong shape: expected [Nt,3], found " + h5::shape_string(ts));
    const auto v = r.read_array("/visual/vertices", vs);
    if (ts[0] * 3 * 8 > r.file_bytes()) r.fail("/visual/triangles", "dataset larger than the file");
    s.visual.vertices.resize(static_cast<Eigen::Index>(vs[0]), 3);
    std::copy(v.begin(), v.end(), s.visual.vertices.data());
    s.visual.triangles.resize(static_cast<Eigen::Index>(ts[0]), 3);
    r.read("/visual/triangles", ts, s.visual.triangles.data());
    for (Eigen::Index t = 0; t < s.visual.triangles.size(); ++t)
      if (s.visual.triangles.data()[t] < 0 || static_cast<u64>(s.visual.triangles.data()[t]) >= vs[0])
        r.fail("/visual/triangles", "vertex index out of range");
    const auto m = r.read_array("/visual/modes", S({nq, vs[0], 3}));
    s.visual.modes.resize(nq);
    for (u64 k = 0; k < nq; ++k) {
      s.visual.modes[k].resize(static_cast<Eigen::Index>(vs[0]), 3);
      std::copy(m.begin() + k * vs[0] * 3, m.begin() + (k + 1) * vs[0] * 3, s.visual.modes[k].data());
    }
  }

  s.provenance = read_provenance(r);
  if (s.provenance.generator.empty()) s.provenance.generator = r.attr_string("/", "generator");
  if (r.exists("/sid/De") && r.has_attr("/sid/De", "model") && s.provenance.damping_model.empty())
    s.provenance.damping_model = r.attr_string("/sid/De", "model");
  // Last: a file edited by hand keeps the refusal of what is wrong with its content.
  if (version >= 2) r.verify_content();
  return s;
}

}  // namespace ffr::formats
