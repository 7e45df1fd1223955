// diff's view of a SID: its datasets flattened as in the file, and its names and labels.
#include "flatten.hpp"

#include <map>
#include <set>

namespace ffr::formats::diff_detail {
namespace {

template <class M>
void append(std::vector<double>& out, const M& m) {
  for (Eigen::Index r = 0; r < m.rows(); ++r)
    for (Eigen::Index c = 0; c < m.cols(); ++c) out.push_back(m(r, c));
}

class Flattener {
 public:
  std::vector<Flat> out;
  template <class M>
  void add(const std::string& path, const M& m, std::vector<std::uint64_t> shape, double floor) {
    Flat f{path, std::move(shape), {}, floor};
    append(f.v, m);
    out.push_back(std::move(f));
  }
  template <class M>
  void add_stack(const std::string& path, const std::vector<M>& s, std::vector<std::uint64_t> shape, double floor) {
    Flat f{path, std::move(shape), {}, floor};
    for (const auto& m : s) append(f.v, m);
    out.push_back(std::move(f));
  }
};

}  // namespace

// Every numeric dataset; nodes in `order` (names of A), B's matched by name.
std::vector<Flat> flatten(const Sid& s, const std::vector<std::string>& node_order, const Size& z, bool modal) {
  using u = std::uint64_t;
  const u nq = static_cast<u>(s.nq());
  const double t1 = z.m * z.phi, r1 = z.m * z.phi * z.L, q2 = z.m * z.phi * z.phi;
  Flattener F;
  F.add("/refmod/mass", Eigen::Matrix<double, 1, 1>::Constant(s.refmod.mass), {}, z.m);
  F.add("/sid/mdCM/M0", s.mdCM.M0.transpose(), {3}, z.m * z.L);
  F.add("/sid/J/M0", s.J.M0, {3, 3}, z.m * z.L * z.L);
  F.add("/integrals/rdm", s.integrals.rdm.transpose(), {3}, z.m * z.L);
  F.add("/integrals/rrdm", s.integrals.rrdm, {3, 3}, z.m * z.L * z.L);
  F.add("/integrals/rotary/I", s.rotary.I, {3, 3}, z.m * z.L * z.L);
  std::vector<double> origin;
  for (const auto& name : node_order) append(origin, s.nodes[static_cast<std::size_t>(s.find_node(name))].origin.transpose());
  F.add("/nodes/origin", Eigen::Map<Eigen::RowVectorXd>(origin.data(), static_cast<Eigen::Index>(origin.size())),
        {node_order.size(), 3}, z.L);
  if (!modal) return F.out;

  F.add("/refmod/frequency_hz", s.refmod.frequency_hz.transpose(), {nq}, 0);
  F.add("/sid/mdCM/M1", s.mdCM.M1, {nq, 3}, t1);
  F.add_stack("/sid/J/M1", s.J.M1, {nq, 3, 3}, r1);
  F.add("/sid/Ct/M0", s.Ct.M0, {nq, 3}, t1);
  F.add("/sid/Cr/M0", s.Cr.M0, {nq, 3}, r1);
  F.add_stack("/sid/Cr/M1", s.Cr.M1, {nq, nq, 3}, q2);
  F.add("/sid/Me/M0", s.Me, {nq, nq}, q2);
  F.add("/sid/Ke/M0", s.Ke, {nq, nq}, 0);
  if (!s.KeM1.empty()) F.add_stack("/sid/Ke/M1", s.KeM1, {nq, nq, nq}, 0);
  F.add("/sid/De/M0", s.De, {nq, nq}, 0);
  F.add_stack("/sid/Gr/M0", s.Gr, {nq, 3, 3}, r1);
  F.add_stack("/sid/Ge/M0", s.Ge, {nq, nq, 3}, q2);
  F.add("/sid/Oe/M0", s.Oe.M0, {nq, 6}, r1);
  F.add_stack("/sid/Oe/M1", s.Oe.M1, {nq, nq, 6}, q2);
  F.add("/sid/ksigma/M0", s.ksigma.M0.transpose(), {nq}, 0);
  F.add("/sid/ksigma/M1", s.ksigma.M1, {nq, nq}, 0);
  F.add("/integrals/Pdm", s.integrals.Pdm, {3, nq}, t1);
  std::vector<Eigen::MatrixXd> rP(s.integrals.rPdm.begin(), s.integrals.rPdm.end());
  F.add_stack("/integrals/rPdm", rP, {3, 3, nq}, r1);
  std::vector<Eigen::MatrixXd> PP;
  for (const auto& row : s.integrals.PPdm) PP.insert(PP.end(), row.begin(), row.end());
  F.add_stack("/integrals/PPdm", PP, {3, 3, nq, nq}, q2);
  F.add("/integrals/rotary/PsiI", s.rotary.PsiI, {nq, 3}, r1);
  F.add("/integrals/rotary/PsiIPsi", s.rotary.PsiIPsi, {nq, nq}, q2);
  std::vector<Eigen::MatrixXd> phi, psi, ap0;
  for (const auto& name : node_order) {
    const auto& n = s.nodes[static_cast<std::size_t>(s.find_node(name))];
    phi.push_back(n.phi);
    psi.push_back(n.psi);
    ap0.push_back(n.AP0);
  }
  const u N = node_order.size();
  F.add_stack("/nodes/phi", phi, {N, 3, nq}, z.phi);
  F.add_stack("/nodes/psi", psi, {N, 3, nq}, z.phi / z.L);
  F.add_stack("/nodes/AP0", ap0, {N, 3, 3}, 1);
  if (s.stiffening) {
    // Natural sizes: K0 times the load (a, alpha, w_bar, F, M) is a modal stiffness ~ q2/s^2.
    F.add_stack("/stiffening/K0t", s.stiffening->K0t, {nq, nq, 3}, q2 / z.L);
    F.add_stack("/stiffening/K0r", s.stiffening->K0r, {nq, nq, 3}, q2);
    F.add_stack("/stiffening/K0om", s.stiffening->K0om, {nq, nq, 6}, q2);
    for (const auto& i : s.stiffening->interfaces) {
      F.add_stack("/stiffening/interfaces/" + i.name + "/K0F", i.K0F, {nq, nq, 3}, z.phi * z.phi / z.L);
      F.add_stack("/stiffening/interfaces/" + i.name + "/K0M", i.K0M, {nq, nq, 3}, z.phi * z.phi / (z.L * z.L));
    }
  }
  if (!s.visual.empty()) {
    const u nv = static_cast<u>(s.visual.vertices.rows());
    F.add("/visual/vertices", s.visual.vertices, {nv, 3}, z.L);
    F.add_stack("/visual/modes", s.visual.modes, {nq, nv, 3}, z.phi);
  }
  return F.out;
}


void structural(const Sid& a, const Sid& b, std::vector<std::string>& out) {
  auto differ = [&](const std::string& what, const std::string& va, const std::string& vb) {
    if (va != vb) out.push_back(what + ": '" + va + "' vs '" + vb + "'");
  };
  differ("nq (number of modes)", std::to_string(a.nq()), std::to_string(b.nq()));
  differ("units", a.units_length + " " + a.units_mass + " " + a.units_time, b.units_length + " " + b.units_mass + " " + b.units_time);
  differ("/refmod/reference", a.refmod.reference, b.refmod.reference);
  if (a.nq() == b.nq())
    for (Eigen::Index k = 0; k < a.nq(); ++k)
      differ("/refmod/mode_type[" + std::to_string(k) + "]", to_string(a.refmod.mode_type[k]), to_string(b.refmod.mode_type[k]));
  std::set<std::string> na, nb;
  for (const auto& n : a.nodes) na.insert(n.name);
  for (const auto& n : b.nodes) nb.insert(n.name);
  for (const auto& n : na)
    if (!nb.count(n)) out.push_back("/nodes/name: node '" + n + "' only in A");
  for (const auto& n : nb)
    if (!na.count(n)) out.push_back("/nodes/name: node '" + n + "' only in B");
  std::map<std::string, std::string> ia, ib;
  for (const auto& i : a.interfaces) ia[i.name] = a.nodes[static_cast<std::size_t>(i.node)].name + ", " + i.coupling + ", " + i.group;
  for (const auto& i : b.interfaces) ib[i.name] = b.nodes[static_cast<std::size_t>(i.node)].name + ", " + i.coupling + ", " + i.group;
  for (const auto& [name, v] : ia) differ("/interfaces '" + name + "'", v, ib.count(name) ? ib[name] : "(absent)");
  for (const auto& [name, v] : ib)
    if (!ia.count(name)) differ("/interfaces '" + name + "'", "(absent)", v);
  differ("/sid/Ke/M1", a.KeM1.empty() ? "absent" : "present", b.KeM1.empty() ? "absent" : "present");
  differ("/stiffening", a.stiffening ? "present" : "absent", b.stiffening ? "present" : "absent");
  if (a.stiffening && b.stiffening) {
    std::string sa, sb;
    for (const auto& i : a.stiffening->interfaces) sa += i.name + " ";
    for (const auto& i : b.stiffening->interfaces) sb += i.name + " ";
    differ("/stiffening/interface_names", sa, sb);
  }
  differ("/visual", a.visual.empty() ? "absent" : std::to_string(a.visual.vertices.rows()) + " vertices",
         b.visual.empty() ? "absent" : std::to_string(b.visual.vertices.rows()) + " vertices");
  if (!a.visual.empty() && !b.visual.empty() && a.visual.triangles != b.visual.triangles)
    out.push_back("/visual/triangles: the surfaces differ");
}

}  // namespace ffr::formats::diff_detail
