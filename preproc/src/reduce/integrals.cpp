#include "ffr/preproc/reduce/invariants.hpp"

#include "ffr/preproc/threads.hpp"
#include "ffr/preproc/solver/sparse_types.hpp"

#include <array>
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
  // The three components side by side, [Phi_x Phi_y Phi_z] over the nodes, and their products
  // with Ms in one call: sym_multiply passes over Ms once per 16 columns, vectorized and on the
  // threads, where Eigen's selfadjoint product passed once per column on one thread (60 passes,
  // 60 ms of the 100k-DOF plate's invariants stage with 20 modes).
  Eigen::MatrixXd F = Eigen::MatrixXd::Zero(N, 3 * nq);
  for (int a = 0; a < 3; ++a)
    for (Index n = 0; n < N; ++n)
      if (model.node_ndof[static_cast<std::size_t>(n)] > 0) F.block(n, a * nq, 1, nq) = Phi.row(model.dof(n, a));
  const Eigen::MatrixXd G = sym_multiply(fe.Ms, SymmetricStorage::UpperOnly, F);
  const auto Phi_a = [&](int a) { return F.middleCols(a * nq, nq); };
  const auto Z = [&](int a) { return G.middleCols(a * nq, nq); };
  const Eigen::VectorXd ones = Eigen::VectorXd::Ones(N);
  for (int b = 0; b < 3; ++b) {
    acc.Pdm.row(b) += ones.transpose() * Z(b);
    for (int a = 0; a < 3; ++a) acc.rPdm[a].row(b) += model.mesh->x.col(a).transpose() * Z(b);
    // int Phi_a^T Phi_b dm = sum_pq Ms_pq Phi_pa^T Phi_qb: the products of two components of the
    // same displacement field, nonzero for a != b too (a mode moving a point along x and y at
    // once), though Ms (x) I3 couples no x DOF with a y DOF. The sample loop below fills a <= b.
    for (int a = 0; a <= b; ++a) acc.PPdm[a][b] += Phi_a(a).transpose() * Z(b);
  }
}

// The sample sums of the shells, beams and attached masses as matrix products: samples are
// collected row-wise (U_a = rows a of u = N Phi_e, one row per sample) and flushed in
// batches, instead of 3 x nq rank-one updates per sample.
class SampleBatch {
 public:
  explicit SampleBatch(Index nq) {
    for (auto& u : U_) u.resize(kRows, nq);
    w_.resize(kRows);
    c_.resize(kRows, 3);
  }
  /// One sample: mass w at c, moving with U (3 x nq) per unit modal coordinate.
  void add(double w, const Eigen::Vector3d& c, const Eigen::Ref<const Eigen::MatrixXd>& U, Accum& acc) {
    if (n_ == kRows) flush(acc);
    for (int a = 0; a < 3; ++a) U_[a].row(n_) = U.row(a);
    w_(n_) = w;
    c_.row(n_) = c.transpose();
    ++n_;
  }
  void flush(Accum& acc) {
    if (n_ == 0) return;
    const auto w = w_.head(n_);
    for (int b = 0; b < 3; ++b) {
      const auto Ub = U_[b].topRows(n_);
      acc.Pdm.row(b) += w.transpose() * Ub;
      for (int a = 0; a < 3; ++a)
        acc.rPdm[a].row(b) += (w.array() * c_.col(a).head(n_).array()).matrix().transpose() * Ub;
      const Eigen::MatrixXd WUb = w.asDiagonal() * Ub;
      for (int a = 0; a <= b; ++a) acc.PPdm[a][b].noalias() += U_[a].topRows(n_).transpose() * WUb;
    }
    n_ = 0;
  }

 private:
  static constexpr Index kRows = 512;
  std::array<Eigen::MatrixXd, 3> U_;
  Eigen::VectorXd w_;
  Eigen::MatrixX3d c_;
  Index n_ = 0;
};

// Shells, beams and attached masses: exact sums over their mass samples, plus the rotary part.
void structural_part(const FeModel& model, const Eigen::MatrixXd& Phi, const std::vector<ElementRef>& refs,
                     std::size_t begin, std::size_t end, Accum& acc) {
  const Index nq = Phi.cols();
  SampleBatch batch(nq);
  for (std::size_t r = begin; r < end; ++r) {
    const auto& ref = refs[r];
    const ElementMatrices em = element_mass(model, ref);
    const auto dofs = element_dofs(model, ref);
    Eigen::MatrixXd Phi_e(static_cast<Index>(dofs.size()), nq);
    for (std::size_t i = 0; i < dofs.size(); ++i) Phi_e.row(static_cast<Index>(i)) = Phi.row(dofs[i]);
    if (!em.samples.empty()) {
      // u of every sample at once: stacked N (3 S x ndof) times Phi_e.
      const Index S = static_cast<Index>(em.samples.size());
      Eigen::MatrixXd N(3 * S, Phi_e.rows());
      for (Index s = 0; s < S; ++s) N.middleRows(3 * s, 3) = em.samples[static_cast<std::size_t>(s)].N;
      const Eigen::MatrixXd U = N * Phi_e;
      for (Index s = 0; s < S; ++s) {
        const auto& smp = em.samples[static_cast<std::size_t>(s)];
        batch.add(smp.w, smp.c, U.middleRows(3 * s, 3), acc);
      }
    }
    if (em.M_rotary.size() > 0) {
      Eigen::Matrix<double, Eigen::Dynamic, 3> Rot(Phi_e.rows(), 3);
      for (std::size_t i = 0; i < dofs.size(); ++i) Rot.row(static_cast<Index>(i)) = model.rigid_motion(dofs[i]).tail<3>();
      acc.PsiI += Phi_e.transpose() * em.M_rotary * Rot;
      acc.PsiIPsi += Phi_e.transpose() * em.M_rotary * Phi_e;
    }
  }
  batch.flush(acc);
}

}  // namespace

void compute_integrals(const FeModel& model, const Assembled& fe, const Eigen::MatrixXd& Phi, formats::Sid& sid,
                       const std::vector<ElementRef>* elements) {
  const Index nq = Phi.cols();
  Accum total(nq);
  solid_part(model, fe, Phi, total);

  std::vector<ElementRef> refs;
  for (const auto& r : elements ? *elements : all_elements(model))
    if (r.block < 0 || model.blocks[static_cast<std::size_t>(r.block)].kind != ElementKind::Solid) refs.push_back(r);
  if (!refs.empty()) {
    const unsigned nt = std::max(1u, std::min<unsigned>(max_threads(), static_cast<unsigned>(refs.size())));
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
  // PPdm[b][a] = PPdm[a][b]^T (the solid part and the sample loop fill a <= b only).
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
