#include "ffr/preproc/reduce/invariants.hpp"

#include <mutex>
#include <thread>

namespace ffr::preproc {
namespace {

struct Accum {
  Eigen::Matrix3Xd Pdm;
  std::array<Eigen::Matrix3Xd, 3> rPdm;
  std::array<std::array<Eigen::MatrixXd, 3>, 3> PPdm;
  formats::MatX3 PsiI;
  Eigen::MatrixXd PsiIPsi;
  explicit Accum(Index nq) {
    Pdm = Eigen::Matrix3Xd::Zero(3, nq);
    for (auto& m : rPdm) m = Eigen::Matrix3Xd::Zero(3, nq);
    for (auto& r : PPdm)
      for (auto& m : r) m = Eigen::MatrixXd::Zero(nq, nq);
    PsiI = formats::MatX3::Zero(nq, 3);
    PsiIPsi = Eigen::MatrixXd::Zero(nq, nq);
  }
  void add(const Accum& o) {
    Pdm += o.Pdm;
    for (int a = 0; a < 3; ++a) {
      rPdm[a] += o.rPdm[a];
      for (int b = 0; b < 3; ++b) PPdm[a][b] += o.PPdm[a][b];
    }
    PsiI += o.PsiI;
    PsiIPsi += o.PsiIPsi;
  }
};

// Solid elements: their consistent mass is Ms (x) I3 and c = sum N_i x_i, so every integral
// is a product with the scalar mass matrix Ms over mesh nodes.
void solid_part(const FeModel& model, const Assembled& fe, const Eigen::MatrixXd& Phi, Accum& acc) {
  const Index N = model.mesh->num_nodes(), nq = Phi.cols();
  if (fe.Ms.nonZeros() == 0) return;
  std::array<Eigen::MatrixXd, 3> Phi_a, Z;
  for (int a = 0; a < 3; ++a) {
    Phi_a[a] = Eigen::MatrixXd::Zero(N, nq);
    for (Index n = 0; n < N; ++n)
      if (model.node_ndof[static_cast<std::size_t>(n)] > 0) Phi_a[a].row(n) = Phi.row(model.dof(n, a));
    Z[a] = fe.Ms * Phi_a[a];
  }
  const Eigen::VectorXd ones = Eigen::VectorXd::Ones(N);
  for (int b = 0; b < 3; ++b) {
    acc.Pdm.row(b) += ones.transpose() * Z[b];
    for (int a = 0; a < 3; ++a) acc.rPdm[a].row(b) += model.mesh->x.col(a).transpose() * Z[b];
    acc.PPdm[b][b] += Phi_a[b].transpose() * Z[b];
  }
}

// Shells, beams and attached masses: exact sums over their mass samples, plus the rotary part.
void structural_part(const FeModel& model, const Eigen::MatrixXd& Phi, const std::vector<ElementRef>& refs,
                     std::size_t begin, std::size_t end, Accum& acc) {
  const Index nq = Phi.cols();
  Eigen::Matrix3Xd U(3, nq);
  for (std::size_t r = begin; r < end; ++r) {
    const auto& ref = refs[r];
    const ElementMatrices em = element_matrices(model, ref);
    const auto dofs = element_dofs(model, ref);
    Eigen::MatrixXd Phi_e(static_cast<Index>(dofs.size()), nq);
    for (std::size_t i = 0; i < dofs.size(); ++i) Phi_e.row(static_cast<Index>(i)) = Phi.row(dofs[i]);
    for (const auto& s : em.samples) {
      U.noalias() = s.N * Phi_e;
      acc.Pdm += s.w * U;
      for (int a = 0; a < 3; ++a) {
        acc.rPdm[a] += (s.w * s.c(a)) * U;
        for (int b = a; b < 3; ++b) acc.PPdm[a][b].noalias() += s.w * U.row(a).transpose() * U.row(b);
      }
    }
    if (em.M_rotary.size() > 0) {
      Eigen::Matrix<double, Eigen::Dynamic, 3> Rot(Phi_e.rows(), 3);
      for (std::size_t i = 0; i < dofs.size(); ++i) Rot.row(static_cast<Index>(i)) = model.rigid_motion(dofs[i]).tail<3>();
      acc.PsiI += Phi_e.transpose() * em.M_rotary * Rot;
      acc.PsiIPsi += Phi_e.transpose() * em.M_rotary * Phi_e;
    }
  }
}

}  // namespace

void compute_integrals(const FeModel& model, const Assembled& fe, const Eigen::MatrixXd& Phi, formats::Sid& sid) {
  const Index nq = Phi.cols();
  Accum total(nq);
  solid_part(model, fe, Phi, total);

  std::vector<ElementRef> refs;
  for (const auto& r : all_elements(model))
    if (r.block < 0 || model.blocks[static_cast<std::size_t>(r.block)].kind != ElementKind::Solid) refs.push_back(r);
  if (!refs.empty()) {
    const unsigned nt = std::max(1u, std::min<unsigned>(std::thread::hardware_concurrency(), static_cast<unsigned>(refs.size())));
    std::vector<Accum> parts(nt, Accum(nq));
    std::vector<std::thread> pool;
    std::exception_ptr error;
    std::mutex m;
    for (unsigned t = 0; t < nt; ++t)
      pool.emplace_back([&, t] {
        try {
          structural_part(model, Phi, refs, refs.size() * t / nt, refs.size() * (t + 1) / nt, parts[t]);
        } catch (...) {
          std::lock_guard<std::mutex> lock(m);
          error = std::current_exception();
        }
      });
    for (auto& th : pool) th.join();
    if (error) std::rethrow_exception(error);
    for (const auto& p : parts) total.add(p);
  }
  // PPdm[b][a] = PPdm[a][b]^T (the sample loop fills a <= b only; the solid part is diagonal).
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < a; ++b) total.PPdm[a][b] = total.PPdm[b][a].transpose();

  sid.refmod.mass = fe.mass;
  sid.integrals.rdm = fe.rdm;
  sid.integrals.rrdm = fe.rrdm;
  sid.integrals.Pdm = total.Pdm;
  sid.integrals.rPdm = total.rPdm;
  sid.integrals.PPdm = total.PPdm;
  sid.rotary.I = fe.rotary_I;
  sid.rotary.PsiI = total.PsiI;
  sid.rotary.PsiIPsi = total.PsiIPsi;
}

}  // namespace ffr::preproc
