#include "ffr/preproc/reduce/stiffening.hpp"

#include "ffr/formats/h5.hpp"
#include "ffr/preproc/elements/solid.hpp"
#include "ffr/preproc/solver/solver_errors.hpp"
#include "ffr/preproc/threads.hpp"
#include "geometric_kernels.hpp"
#include "static_solver.hpp"
#include "../stopwatch.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <chrono>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <thread>

namespace ffr::preproc {
namespace {

Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d s;
  s << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return s;
}

// An acceleration field a + A c of the material points.
struct Field {
  Eigen::Vector3d a = Eigen::Vector3d::Zero();
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
};

// Consistent inertial loads f = -int (a + A c) dm for each field (num_dofs x fields): solids
// through Ms (exact: the field is linear and interpolated exactly), the other elements
// through their mass samples.
Eigen::MatrixXd inertial_loads(const FeModel& model, const Assembled& fe, const std::vector<Field>& fields) {
  const Index N = model.mesh->num_nodes();
  Eigen::MatrixXd F = Eigen::MatrixXd::Zero(model.num_dofs, static_cast<Index>(fields.size()));
  for (std::size_t L = 0; L < fields.size(); ++L) {
    if (fe.Ms.nonZeros() == 0) break;
    Eigen::MatrixX3d V(N, 3);
    for (Index n = 0; n < N; ++n) V.row(n) = (fields[L].a + fields[L].A * model.mesh->x.row(n).transpose()).transpose();
    const Eigen::MatrixX3d MV = fe.Ms.selfadjointView<Eigen::Upper>() * V;
    for (Index n = 0; n < N; ++n)
      if (model.node_ndof[static_cast<std::size_t>(n)] > 0)
        for (int c = 0; c < 3; ++c) F(model.dof(n, c), static_cast<Index>(L)) -= MV(n, c);
  }
  for (const auto& ref : all_elements(model)) {
    if (ref.block >= 0 && model.blocks[static_cast<std::size_t>(ref.block)].kind == ElementKind::Solid) continue;
    const ElementMatrices em = element_matrices(model, ref);
    const auto dofs = element_dofs(model, ref);
    for (const auto& s : em.samples)
      for (std::size_t L = 0; L < fields.size(); ++L) {
        const Eigen::VectorXd fe_L = -s.w * s.N.transpose() * (fields[L].a + fields[L].A * s.c);
        for (std::size_t i = 0; i < dofs.size(); ++i) F(dofs[i], static_cast<Index>(L)) += fe_L(static_cast<Index>(i));
      }
  }
  return F;
}

// Phi^T K_G(u_L) Phi for the stress of each displacement field u_L (columns of U, full DOFs):
// one threaded pass over the elements, projecting element by element (no global K_G). The
// calling thread takes the first share and reports its progress (0..1).
std::vector<Eigen::MatrixXd> project_geometric(const FeModel& model, const Eigen::MatrixXd& U, const Eigen::MatrixXd& Phi,
                                               detail::GeometricRule rule = detail::GeometricRule::Stiffness,
                                               const std::function<void(double)>& progress = {}) {
  const Index nq = Phi.cols(), nL = U.cols();
  const auto refs = all_elements(model);
  const unsigned nt = max_threads();
  std::vector<std::vector<Eigen::MatrixXd>> part(nt, std::vector<Eigen::MatrixXd>(static_cast<std::size_t>(nL), Eigen::MatrixXd::Zero(nq, nq)));
  std::exception_ptr error;
  std::mutex m;
  auto work = [&](unsigned t) {
    try {
      const std::size_t r0 = refs.size() * t / nt, r1 = refs.size() * (t + 1) / nt;
      std::size_t reported = 0;
      for (std::size_t r = r0; r < r1; ++r) {
        if (t == 0 && progress && (r - r0) * 100 / std::max<std::size_t>(r1 - r0, 1) > reported) {
          reported = (r - r0) * 100 / (r1 - r0);
          progress(static_cast<double>(reported) / 100);
        }
        if (refs[r].block < 0) continue;  // attached masses carry no stress
        const auto dofs = element_dofs(model, refs[r]);
        Eigen::MatrixXd Phi_e(static_cast<Index>(dofs.size()), nq);
        for (std::size_t i = 0; i < dofs.size(); ++i) Phi_e.row(static_cast<Index>(i)) = Phi.row(dofs[i]);
        for (Index L = 0; L < nL; ++L) {
          const Eigen::MatrixXd Kg = detail::geometric_element(model, refs[r], U.col(L), rule).K;
          part[t][static_cast<std::size_t>(L)].noalias() += Phi_e.transpose() * (Kg * Phi_e);
        }
      }
    } catch (...) {
      std::lock_guard<std::mutex> lock(m);
      if (!error) error = std::current_exception();
    }
  };
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < nt; ++t) pool.emplace_back(work, t);
  work(0);
  for (auto& th : pool) th.join();
  if (error) std::rethrow_exception(error);
  std::vector<Eigen::MatrixXd> out(static_cast<std::size_t>(nL), Eigen::MatrixXd::Zero(nq, nq));
  for (const auto& p : part)
    for (Index L = 0; L < nL; ++L) out[static_cast<std::size_t>(L)] += p[static_cast<std::size_t>(L)];
  for (auto& P : out) P = 0.5 * (P + P.transpose()).eval();
  return out;
}

std::vector<InterfaceState> reference_states(const FeModel& model, const ReductionSpec& spec) {
  std::vector<InterfaceState> st(model.interfaces.size(), InterfaceState::Free);
  if (spec.method == ReductionSpec::Method::Clamped)
    st.at(static_cast<std::size_t>(model.find_interface(spec.interface))) = InterfaceState::Held;
  if (spec.method == ReductionSpec::Method::CraigBampton)
    for (const auto& name : spec.interfaces) st.at(static_cast<std::size_t>(model.find_interface(name))) = InterfaceState::Held;
  return st;
}

// For forces at interfaces, only the clamp or the Craig–Bampton frame is held.
std::vector<InterfaceState> force_states(const FeModel& model, const ReductionSpec& spec) {
  std::vector<InterfaceState> st(model.interfaces.size(), InterfaceState::Free);
  if (spec.method == ReductionSpec::Method::Clamped)
    st.at(static_cast<std::size_t>(model.find_interface(spec.interface))) = InterfaceState::Held;
  if (spec.method == ReductionSpec::Method::CraigBampton)
    st.at(static_cast<std::size_t>(model.find_interface(spec.frame))) = InterfaceState::Held;
  return st;
}

void unit_load_cases(const FeModel& model, const Assembled& fe, const Eigen::MatrixXd& Phi,
                     const detail::StaticSolver& forced, const std::vector<InterfaceState>& fstates,
                     StiffeningResult& out, const std::function<void(const std::string&)>& log) {
  const PartSpec& part = *model.part;
  const Index nq = Phi.cols();
  const auto snq = static_cast<std::size_t>(nq);
  auto& st = out.stiffening;
  st.K0t.assign(snq, formats::MatX3::Zero(nq, 3));
  st.K0r.assign(snq, formats::MatX3::Zero(nq, 3));
  st.K0om.assign(snq, formats::MatX6::Zero(nq, 6));
  // Inertial load cases under the reference conditions.
  std::vector<Field> fields(12);
  for (int c = 0; c < 3; ++c) {
    fields[static_cast<std::size_t>(c)].a = Eigen::Vector3d::Unit(c);
    fields[static_cast<std::size_t>(3 + c)].A = skew(Eigen::Vector3d::Unit(c));
  }
  for (int j = 0; j < 6; ++j) fields[static_cast<std::size_t>(6 + j)].A = centrifugal_coefficient(j);
  // Craig–Bampton holds its boundary interfaces too; otherwise the force solver's conditions
  // are the reference conditions and its factor is reused.
  const auto rstates = reference_states(model, part.reduction);
  std::unique_ptr<detail::StaticSolver> own;
  if (rstates != fstates) own = std::make_unique<detail::StaticSolver>(model, fe, rstates);
  const detail::StaticSolver& inertial = own ? *own : forced;
  if (log) log(std::string("stiffening: 12 inertial load cases") + (inertial.inertia_relief() ? " (inertia relief)" : ""));
  const Eigen::MatrixXd U = inertial.solve(inertial_loads(model, fe, fields));
  auto store = [&](const Eigen::MatrixXd& K0, auto& target, int col) {
    for (Index k = 0; k < nq; ++k) target[static_cast<std::size_t>(k)].col(col) = K0.col(k);
  };
  const auto K0s = project_geometric(model, U, Phi);
  for (int L = 0; L < 12; ++L) {
    const Eigen::MatrixXd& K0 = K0s[static_cast<std::size_t>(L)];
    if (L < 3) store(K0, st.K0t, L);
    else if (L < 6) store(K0, st.K0r, L - 3);
    else store(K0, st.K0om, L - 6);
  }
  out.load_cases = 12;

  // Unit forces and moments at each interface that is not held.
  for (std::size_t i = 0; i < model.interfaces.size(); ++i) {
    if (fstates[i] == InterfaceState::Held) continue;
    Eigen::MatrixXd F = Eigen::MatrixXd::Zero(model.num_dofs, 6);
    for (int c = 0; c < 6; ++c) F(model.interfaces[i].dof + c, c) = 1.0;
    const Eigen::MatrixXd Ui = forced.solve(F);
    formats::Stiffening::Interface itf;
    itf.name = model.interfaces[i].name;
    itf.K0F.assign(snq, formats::MatX3::Zero(nq, 3));
    itf.K0M.assign(snq, formats::MatX3::Zero(nq, 3));
    const auto K0i = project_geometric(model, Ui, Phi);
    for (int c = 0; c < 6; ++c) {
      const Eigen::MatrixXd& K0 = K0i[static_cast<std::size_t>(c)];
      if (c < 3) store(K0, itf.K0F, c);
      else store(K0, itf.K0M, c - 3);
    }
    st.interfaces.push_back(std::move(itf));
    out.load_cases += 6;
  }
  if (log) log("stiffening: " + std::to_string(out.load_cases) + " load cases projected on " + std::to_string(nq) + " modes");

}

}  // namespace

Eigen::Matrix3d centrifugal_coefficient(int j) {
  // skew(w)^2 = w w^T - |w|^2 I, split by the products of omega_bar.
  Eigen::Matrix3d B = Eigen::Matrix3d::Zero();
  switch (j) {
    case formats::kXX: B(1, 1) = B(2, 2) = -1; break;
    case formats::kYY: B(0, 0) = B(2, 2) = -1; break;
    case formats::kZZ: B(0, 0) = B(1, 1) = -1; break;
    case formats::kXY: B(0, 1) = B(1, 0) = 1; break;
    case formats::kYZ: B(1, 2) = B(2, 1) = 1; break;
    case formats::kXZ: B(0, 2) = B(2, 0) = 1; break;
  }
  return B;
}

std::vector<Eigen::MatrixXd> self_geometric_stiffness(const FeModel& model, const Eigen::MatrixXd& Phi,
                                                      const std::function<void(const std::string&)>& progress) {
  // The modes are the displacement fields: nq stress fields, each projected on the modes.
  auto report = [&](double f) {
    if (progress) progress("Ke/M1 " + std::to_string(static_cast<int>(100 * f)) + " %");
  };
  return project_geometric(model, Phi, Phi, detail::GeometricRule::Cubic, report);
}

namespace {

StiffeningResult compute(const FeModel& model, const Assembled& fe, const Eigen::MatrixXd& Phi, bool unit_cases,
                         const std::function<void(const std::string&)>& log,
                         const std::function<void(const std::string&)>& progress) {
  const PartSpec& part = *model.part;
  StiffeningResult out;
  const auto fstates = force_states(model, part.reduction);
  const detail::StaticSolver forced(model, fe, fstates);
  if (unit_cases) {
    unit_load_cases(model, fe, Phi, forced, fstates, out, log);
    const auto t0 = std::chrono::steady_clock::now();
    out.KeM1 = self_geometric_stiffness(model, Phi, progress);
    for (std::size_t k = 0; k < out.KeM1.size(); ++k)
      if (!out.KeM1[k].allFinite())
        throw std::invalid_argument("the geometric stiffness of mode " + std::to_string(k) + "'s stress is not finite");
    if (log)
      log("stiffening: Ke/M1 from the stress of " + std::to_string(Phi.cols()) + " modes [" +
          std::to_string(seconds_since(t0)) + " s]");
  }

  // Prestress from the part's preload.
  if (!part.preload.empty()) {
    Field g;
    g.a = -part.preload.gravity;  // gravity g acts like a frame acceleration -g
    Eigen::MatrixXd F = inertial_loads(model, fe, {g});
    for (const auto& l : part.preload.loads) {
      const Index d0 = model.interfaces[static_cast<std::size_t>(model.find_interface(l.interface))].dof;
      F.block<3, 1>(d0, 0) += l.force;
      F.block<3, 1>(d0 + 3, 0) += l.moment;
    }
    const Eigen::MatrixXd u = forced.solve(F);
    out.ksigma.M1 = project_geometric(model, u, Phi).front();
    out.ksigma.M0 = Phi.transpose() * (fe.K * u.col(0));
    if (log) log("prestress: preload solved and projected");
  }
  return out;
}

}  // namespace

StiffeningResult compute_stiffening(const FeModel& model, const Assembled& fe, const Eigen::MatrixXd& Phi,
                                    bool unit_cases, const std::function<void(const std::string&)>& log,
                                    const std::function<void(const std::string&)>& progress) {
  // An element without a geometric stiffness, a load case the reference conditions cannot
  // carry, or a non-finite result is the part's request that cannot be met: named as such
  // (an input error), not as an internal failure.
  const PartSpec& part = *model.part;
  const std::string field = unit_cases ? "stiffening" : "preload";
  try {
    return compute(model, fe, Phi, unit_cases, log, progress);
  } catch (const InsufficientMemoryError&) {
    throw;
  } catch (const ElementError& e) {
    throw formats::FormatError(part.file.string(), field, std::string("cannot compute the geometric stiffness: ") + e.what());
  } catch (const SolverError& e) {
    throw formats::FormatError(part.file.string(), field, std::string("cannot solve its static load cases: ") + e.what());
  } catch (const std::invalid_argument& e) {
    throw formats::FormatError(part.file.string(), field, std::string("cannot be computed: ") + e.what());
  }
}

}  // namespace ffr::preproc
