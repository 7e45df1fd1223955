#include "fe_bodies.hpp"

#include "ffr/formats/sid_io.hpp"
#include "ffr/preproc/assembly/assembly.hpp"
#include "ffr/preproc/mesh/gmsh_import.hpp"
#include "ffr/preproc/model/fe_model.hpp"
#include "ffr/preproc/part/part.hpp"
#include "ffr/preproc/reduce/invariants.hpp"
#include "ffr/preproc/reduce/node_data.hpp"
#include "ffr/preproc/reduce/reduction.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/SparseCore>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace bench {
namespace fs = std::filesystem;
namespace syn = ffr::formats::synthetic;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

using Sparse = Eigen::SparseMatrix<double>;

// The 3N x 3N mass Ms (x) I3 (DOF 3p + a) of a scalar nodal mass Ms (N x N, full storage).
Sparse expand3(const Sparse& Ms) {
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(static_cast<std::size_t>(3 * Ms.nonZeros()));
  for (int k = 0; k < Ms.outerSize(); ++k)
    for (Sparse::InnerIterator it(Ms, k); it; ++it)
      for (int a = 0; a < 3; ++a) t.emplace_back(3 * it.row() + a, 3 * it.col() + a, it.value());
  Sparse M(3 * Ms.rows(), 3 * Ms.cols());
  M.setFromTriplets(t.begin(), t.end());
  return M;
}

// Every shape integral (formats/SPEC.md 8) of nodal mass Ms (x) I3 at nodes X moving with Phi,
// written from the definitions: int f dm = sum_pq Ms_pq f_p f_q for the products of nodal
// fields; then the SID members from them (the preprocessor's formulas).
void integrals_from_mass(const Sparse& Ms, const VectorXd& X, const MatrixXd& Phi, ffr::formats::Sid& sid) {
  const Eigen::Index N = Ms.rows(), nq = Phi.cols();
  MatrixXd x(N, 3);
  std::array<MatrixXd, 3> F;
  for (int a = 0; a < 3; ++a) {
    F[a].resize(N, nq);
    for (Eigen::Index p = 0; p < N; ++p) {
      x(p, a) = X(3 * p + a);
      F[a].row(p) = Phi.row(3 * p + a);
    }
  }
  const VectorXd ones = VectorXd::Ones(N);
  const MatrixXd Mx = Ms * x;
  auto& I = sid.integrals;
  sid.refmod.mass = ones.dot(Ms * ones);
  I.rdm = Mx.transpose() * ones;
  I.rrdm = x.transpose() * Mx;
  I.Pdm.resize(3, nq);
  for (int b = 0; b < 3; ++b) {
    const MatrixXd Z = Ms * F[b];
    I.Pdm.row(b) = ones.transpose() * Z;
    for (int a = 0; a < 3; ++a) {
      I.rPdm[a].resize(3, nq);
      I.rPdm[a].row(b) = x.col(a).transpose() * Z;
      I.PPdm[a][b] = F[a].transpose() * Z;
    }
  }
  sid.rotary = {};
  sid.rotary.PsiI = ffr::formats::MatX3::Zero(nq, 3);
  sid.rotary.PsiIPsi = MatrixXd::Zero(nq, nq);
  ffr::preproc::members_from_integrals(sid);
}

// The cache of a solid bar's FE data: N, nq, X, Phi, then M's triplets (raw binary in the
// host's byte order and sizes: a cache, never exchanged).
void write_cache(const fs::path& p, const ffr::runtime::FullMass& F) {
  std::ofstream f(p, std::ios::binary);
  const long n3 = F.X.size(), nq = F.Phi.cols(), nnz = F.M.nonZeros();
  f.write(reinterpret_cast<const char*>(&n3), sizeof n3);
  f.write(reinterpret_cast<const char*>(&nq), sizeof nq);
  f.write(reinterpret_cast<const char*>(&nnz), sizeof nnz);
  f.write(reinterpret_cast<const char*>(F.X.data()), static_cast<std::streamsize>(sizeof(double) * n3));
  f.write(reinterpret_cast<const char*>(F.Phi.data()), static_cast<std::streamsize>(sizeof(double) * n3 * nq));
  for (int k = 0; k < F.M.outerSize(); ++k)
    for (Sparse::InnerIterator it(F.M, k); it; ++it) {
      const long r = it.row(), c = it.col();
      const double v = it.value();
      f.write(reinterpret_cast<const char*>(&r), sizeof r);
      f.write(reinterpret_cast<const char*>(&c), sizeof c);
      f.write(reinterpret_cast<const char*>(&v), sizeof v);
    }
  if (!f) throw std::runtime_error("cannot write " + p.string());
}

std::shared_ptr<ffr::runtime::FullMass> read_cache(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  long n3 = 0, nq = 0, nnz = 0;
  f.read(reinterpret_cast<char*>(&n3), sizeof n3);
  f.read(reinterpret_cast<char*>(&nq), sizeof nq);
  f.read(reinterpret_cast<char*>(&nnz), sizeof nnz);
  auto F = std::make_shared<ffr::runtime::FullMass>();
  F->X.resize(n3);
  F->Phi.resize(n3, nq);
  f.read(reinterpret_cast<char*>(F->X.data()), static_cast<std::streamsize>(sizeof(double) * n3));
  f.read(reinterpret_cast<char*>(F->Phi.data()), static_cast<std::streamsize>(sizeof(double) * n3 * nq));
  std::vector<Eigen::Triplet<double>> t(static_cast<std::size_t>(nnz));
  for (auto& e : t) {
    long r = 0, c = 0;
    double v = 0;
    f.read(reinterpret_cast<char*>(&r), sizeof r);
    f.read(reinterpret_cast<char*>(&c), sizeof c);
    f.read(reinterpret_cast<char*>(&v), sizeof v);
    e = {static_cast<int>(r), static_cast<int>(c), v};
  }
  if (!f) throw std::runtime_error("cannot read " + p.string());
  F->M.resize(n3, n3);
  F->M.setFromTriplets(t.begin(), t.end());
  return F;
}

}  // namespace

FeBody consistent_rod(const syn::ChainParams& p) {
  const syn::Chain chain = syn::spring_chain(p);
  const int n = p.points, nq = p.modes;
  const double me = p.mass / (n - 1);
  std::vector<Eigen::Triplet<double>> t;
  for (int e = 0; e + 1 < n; ++e) {
    t.emplace_back(e, e, me / 3);
    t.emplace_back(e + 1, e + 1, me / 3);
    t.emplace_back(e, e + 1, me / 6);
    t.emplace_back(e + 1, e, me / 6);
  }
  Sparse Ms(n, n);
  Ms.setFromTriplets(t.begin(), t.end());
  const Sparse M = expand3(Ms);
  // Free-free: the five rigid-body modes of a chain on its axis (no torsion) come first.
  Eigen::GeneralizedSelfAdjointEigenSolver<MatrixXd> es(chain.model.K, MatrixXd(M));
  if (es.info() != Eigen::Success) throw std::runtime_error("consistent_rod: eigen-solve failed");
  const VectorXd lam = es.eigenvalues();
  const int rigid = p.clamped ? 0 : 5;
  if (rigid > 0 && !(lam(rigid) > 1e3 * std::abs(lam(rigid - 1))))
    throw std::runtime_error("consistent_rod: no gap after the rigid-body modes");
  const MatrixXd Phi = es.eigenvectors().middleCols(rigid, nq);  // M-orthonormal
  VectorXd X(3 * n);
  for (int q = 0; q < n; ++q) X.segment<3>(3 * q) = chain.model.points[static_cast<std::size_t>(q)].c;

  FeBody out;
  out.dof = 3L * n;
  ffr::formats::Sid& sid = out.sid;
  sid = chain.sid;
  sid.resize(nq);
  sid.stiffening.reset();
  sid.KeM1.clear();
  for (int k = 0; k < nq; ++k) {
    sid.refmod.frequency_hz(k) = std::sqrt(lam(rigid + k)) / (2 * M_PI);
    sid.refmod.mode_type[static_cast<std::size_t>(k)] = ffr::formats::ModeType::Normal;
  }
  const MatrixXd Psi = chain.model.rotation_recovery * Phi;
  for (auto& node : sid.nodes) {
    Eigen::Index q = 0;
    while (q < n && (X.segment<3>(3 * q) - node.origin).norm() > 1e-12) ++q;
    if (q == n) throw std::runtime_error("consistent_rod: node " + node.name + " is not a chain point");
    node.phi = Phi.middleRows(3 * q, 3);
    node.psi = Psi.middleRows(3 * q, 3);
  }
  integrals_from_mass(Ms, X, Phi, sid);
  sid.Ke = lam.segment(rigid, nq).asDiagonal();
  sid.De = MatrixXd::Zero(nq, nq);
  auto F = std::make_shared<ffr::runtime::FullMass>();
  F->X = X;
  F->Phi = Phi;
  F->M = M;
  out.full_mass = F;
  return out;
}

FeBody solid_bar(const fs::path& workdir, double length, double side, double size, int modes) {
  char tag[96];
  std::snprintf(tag, sizeof tag, "bar_%g_%g_%g_%d", length, side, size, modes);
  const fs::path sid_path = workdir / (std::string(tag) + ".sid.h5"), fe_path = workdir / (std::string(tag) + ".fe.bin");
  FeBody out;
  if (fs::exists(sid_path) && fs::exists(fe_path)) {
    out.sid = ffr::formats::read_sid(sid_path);
    out.full_mass = read_cache(fe_path);
    out.dof = static_cast<long>(out.full_mass->X.size());
    return out;
  }
  fs::create_directories(workdir);
  {
    std::ofstream g(workdir / (std::string(tag) + ".geo"));
    g << "SetFactory(\"OpenCASCADE\");\nBox(1) = {0, " << -side / 2 << ", " << -side / 2 << ", " << length << ", " << side << ", "
      << side << "};\nPhysical Volume(\"body\") = {1};\n";
    std::ofstream j(workdir / (std::string(tag) + ".json"));
    j << R"({"geometry": ")" << tag << R"(.geo", "mesh": {"size": )" << size
      << R"(, "order": 2}, "materials": [{"group": "body", "E": 2.0e11, "nu": 0.3, "rho": 7870}],
  "reduction": {"method": "free", "modes": )"
      << modes << R"(}, "output_nodes": [{"name": "A", "at": [0, 0, 0]}, {"name": "B", "at": [)" << length << ", 0, 0]}]}";
  }
  const ffr::preproc::PartSpec part = ffr::preproc::load_part(workdir / (std::string(tag) + ".json"));
  const ffr::preproc::Mesh mesh = ffr::preproc::load_mesh(part);
  const ffr::preproc::FeModel model = ffr::preproc::build_model(mesh, part);
  const ffr::preproc::Assembled fe = ffr::preproc::assemble(model);
  const ffr::preproc::ReductionResult red = ffr::preproc::reduce(model, fe, part.reduction, {}, nullptr);
  const Eigen::Index N = mesh.num_nodes(), nq = red.Phi.cols();
  // Mesh-node order, 3 translations each (every node of a solid mesh carries them).
  auto F = std::make_shared<ffr::runtime::FullMass>();
  F->X.resize(3 * N);
  F->Phi.resize(3 * N, nq);
  for (Eigen::Index p = 0; p < N; ++p)
    for (int a = 0; a < 3; ++a) {
      F->X(3 * p + a) = mesh.x(p, a);
      F->Phi.row(3 * p + a) = red.Phi.row(model.node_dof[static_cast<std::size_t>(p)] + a);
    }
  std::remove_cv_t<decltype(fe.Ms)> Ms_sym;
  Ms_sym = fe.Ms.selfadjointView<Eigen::Upper>();
  const Sparse Ms_full = Ms_sym;
  F->M = expand3(Ms_full);
  ffr::formats::Sid& sid = out.sid;
  sid.resize(nq);
  sid.nodes = ffr::preproc::node_data(model, red.Phi);
  for (Eigen::Index k = 0; k < nq; ++k) sid.refmod.frequency_hz(k) = std::sqrt(std::max(0.0, red.lambda(k))) / (2 * M_PI);
  sid.refmod.mode_type = red.types;
  sid.refmod.reference = red.reference;
  // The preprocessor's own integrals (what ffr-reduce writes).
  ffr::preproc::compute_integrals(model, fe, red.Phi, sid);
  ffr::preproc::members_from_integrals(sid);
  sid.Ke = red.Ke;
  sid.De = MatrixXd::Zero(nq, nq);
  ffr::formats::write_sid(sid, sid_path);
  write_cache(fe_path, *F);
  out.full_mass = F;
  out.dof = 3L * N;
  return out;
}

FeBody first_modes(const FeBody& b, int nq) {
  FeBody out;
  out.dof = b.dof;
  const ffr::formats::Sid& s = b.sid;
  ffr::formats::Sid& t = out.sid;
  t = s;
  t.stiffening.reset();
  t.KeM1.clear();
  t.resize(nq);
  t.refmod = s.refmod;
  t.refmod.frequency_hz = s.refmod.frequency_hz.head(nq);
  t.refmod.mode_type.resize(static_cast<std::size_t>(nq));
  for (std::size_t k = 0; k < t.nodes.size(); ++k) {
    t.nodes[k].phi = s.nodes[k].phi.leftCols(nq);
    t.nodes[k].psi = s.nodes[k].psi.leftCols(nq);
  }
  t.integrals.rdm = s.integrals.rdm;
  t.integrals.rrdm = s.integrals.rrdm;
  t.integrals.Pdm = s.integrals.Pdm.leftCols(nq);
  for (int a = 0; a < 3; ++a) {
    t.integrals.rPdm[a] = s.integrals.rPdm[a].leftCols(nq);
    for (int c = 0; c < 3; ++c) t.integrals.PPdm[a][c] = s.integrals.PPdm[a][c].topLeftCorner(nq, nq);
  }
  t.rotary.I = s.rotary.I;
  t.rotary.PsiI = s.rotary.PsiI.topRows(nq);
  t.rotary.PsiIPsi = s.rotary.PsiIPsi.topLeftCorner(nq, nq);
  ffr::preproc::members_from_integrals(t);
  t.Ke = s.Ke.topLeftCorner(nq, nq);
  t.De = s.De.topLeftCorner(nq, nq);
  auto F = std::make_shared<ffr::runtime::FullMass>();
  F->X = b.full_mass->X;
  F->Phi = b.full_mass->Phi.leftCols(nq);
  F->M = b.full_mass->M;
  out.full_mass = F;
  return out;
}

}  // namespace bench
