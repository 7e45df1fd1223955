#include "distributed_reduction.hpp"

#include "ffr/preproc/reduce/invariants.hpp"
#include "ffr/preproc/solver/parallel_session.hpp"
#include "../solver/slepc_distributed.hpp"
#include "reduction_parts.hpp"
#include "setup.hpp"
#include "../stopwatch.hpp"

#include <nlohmann/json.hpp>
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iterator>
#include <sstream>

namespace ffr::preproc::detail {
namespace {

// A dense Eigen matrix summed over the ranks, in place.
template <class M>
void sum_dense(M& A) {
  sum_over_ranks(A.data(), static_cast<std::size_t>(A.size()));
}

// Peak resident memory of this process so far, in bytes (Linux reports KiB).
std::int64_t peak_rss_bytes() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<std::int64_t>(u.ru_maxrss) * 1024;
}

}  // namespace

bool distributed_reduction_applies(const PartSpec& part) {
  return parallel_session_active() && part.reduction.backend == "slepc" && !part.matrices.given() && !part.stiffening &&
         part.preload.empty() && part.reduction.method != ReductionSpec::Method::CraigBampton;
}

DistributedReduction::DistributedReduction(const FeModel& model, const ReductionSpec& spec)
    : model_(model), spec_(spec), t_(build_transform(model, states_for(model, spec))) {
  const int rank = session_rank(), size = session_size();
  const std::int64_t n = t_.num_ind();
  std::vector<std::int64_t> starts(static_cast<std::size_t>(size));
  for (int r = 0; r < size; ++r) starts[static_cast<std::size_t>(r)] = first_row(n, r, size);
  const auto refs = all_elements(model);
  for (std::size_t e = 0; e < refs.size(); ++e) {
    std::int64_t lowest = -1;
    for (const Index d : element_dofs(model, refs[e])) {
      const Index i = t_.ind_of_full[static_cast<std::size_t>(d)];
      if (i >= 0 && (lowest < 0 || i < lowest)) lowest = i;
    }
    // An element on held or dependent DOFs alone (inside an interface's group) by its index.
    const int owner = lowest < 0 ? static_cast<int>(e % static_cast<std::size_t>(size))
                                 : static_cast<int>(std::upper_bound(starts.begin(), starts.end(), lowest) - starts.begin()) - 1;
    if (owner == rank) elements_.push_back(refs[e]);
  }
}

Assembled DistributedReduction::assemble(const std::function<void(double)>& progress) {
  AssemblyOptions aopt;
  aopt.elements = &elements_;
  aopt.progress = progress;
  // Element errors on one rank end the job with that rank's message (ffr-reduce aborts all).
  Assembled fe = preproc::assemble(model_, aopt);
  assembled_entries_ = fe.K.nonZeros() + fe.M.nonZeros();
  // The whole body's sums (the integrals of the solids from Ms and the samples of the others
  // are sums over elements).
  double s[1 + 3 + 9 + 9];
  s[0] = fe.mass;
  std::copy(fe.rdm.data(), fe.rdm.data() + 3, s + 1);
  std::copy(fe.rrdm.data(), fe.rrdm.data() + 9, s + 4);
  std::copy(fe.rotary_I.data(), fe.rotary_I.data() + 9, s + 13);
  sum_over_ranks(s, std::size(s));
  fe.mass = s[0];
  std::copy(s + 1, s + 4, fe.rdm.data());
  std::copy(s + 4, s + 13, fe.rrdm.data());
  std::copy(s + 13, s + 22, fe.rotary_I.data());
  std::int64_t counts[2] = {fe.elements, fe.has_structural ? 1 : 0};
  sum_over_ranks(counts, 2);
  fe.elements = counts[0];
  fe.has_structural = counts[1] > 0;
  const auto [worst, at] = min_over_ranks(fe.worst_scaled_jacobian);
  fe.worst_scaled_jacobian = worst;
  fe.worst_element = broadcast(fe.worst_element, at);
  return fe;
}

ReductionResult DistributedReduction::reduce(Assembled& fe, const ReductionLog& log) {
  const PartSpec& part = *model_.part;
  require_connected(model_);
  auto clock = std::chrono::steady_clock::now();
  SparseMatrix K = constrained(t_, fe.K, false);
  release(fe.K);
  SparseMatrix M = constrained(t_, fe.M, false);
  release(fe.M);
  DistributedPencil pencil(K, M, true);
  release(K);
  release(M);
  row_entries_ = pencil.local_nonzeros();
  require_mass(static_cast<Index>(pencil.massless_dofs()), t_.num_ind(), part);
  const double t_constraints = seconds_since(clock);

  const bool free = spec_.method == ReductionSpec::Method::Free;
  // The serial path's shifts (reduction.cpp).
  const double sigma = free ? -lambda_of_frequency(1.0, part) : -lambda_of_frequency(0.1, part);
  const EigenOptions o = reduction_eigen_options(spec_, part, sigma);
  const Eigen::MatrixXd R = free ? rigid_body_modes(model_, t_) : Eigen::MatrixXd();
  if (log.message)
    log.message(std::string(free ? "free-free" : "clamped") + " eigen-solve: " + std::to_string(t_.num_ind()) + " DOF, " +
                (spec_.max_frequency_hz ? "up to " + std::to_string(*spec_.max_frequency_hz) + " Hz"
                                        : std::to_string(o.nev) + " modes") +
                ", slepc, MUMPS factorization; assembled and checked distributed over " +
                std::to_string(session_size()) + " rank(s)");
  const DistributedModes modes = pencil.eigenmodes(R, o, log.progress);
  if (log.message) {
    std::ostringstream line;
    line.precision(3);
    line << "timing: constraints " << t_constraints << " s, SLEPc Krylov-Schur with its MUMPS factorization "
         << modes.solve_seconds << " s (" << modes.iterations << " restarts), checks " << modes.verify_seconds << " s";
    log.message(line.str());
    if (!modes.factor.empty()) log.message(modes.factor);
  }
  require_no_zero_modes(model_, modes.lambda, free ? "beyond the six rigid-body modes" : "with the interface held");

  ReductionResult r;
  r.lambda = modes.lambda;
  r.Ke = modes.XtKX;
  r.Me = modes.XtMX;
  r.types.assign(static_cast<std::size_t>(modes.lambda.size()), formats::ModeType::Normal);
  r.backend = to_string(EigenBackend::Slepc);
  r.lanczos_seconds = modes.solve_seconds;
  r.iterations = modes.iterations;
  r.max_residual = modes.max_relative_residual;
  r.orthonormality_error = modes.orthonormality_error;
  r.reference = free ? "free" : "clamped:" + spec_.interface;
  nlohmann::json params = {{"method", free ? "free" : "clamped"}, {"shift", sigma}, {"backend", r.backend}};
  if (!free) params["interface"] = spec_.interface;
  params["modes"] = spec_.modes;
  if (spec_.max_frequency_hz) params["max_frequency_hz"] = *spec_.max_frequency_hz;
  params["factorization"] = spec_.factorization;
  r.parameters_json = params.dump();
  r.Phi = t_.identity ? modes.X : Eigen::MatrixXd(t_.T * modes.X);
  return r;
}

void DistributedReduction::integrals(const Assembled& fe, const Eigen::MatrixXd& Phi, formats::Sid& sid) const {
  // fe's scalar sums are already the body's (assemble); the modal integrals are this rank's.
  compute_integrals(model_, fe, Phi, sid, &elements_);
  sum_dense(sid.integrals.Pdm);
  for (auto& m : sid.integrals.rPdm) sum_dense(m);
  for (auto& row : sid.integrals.PPdm)
    for (auto& m : row) sum_dense(m);
  sum_dense(sid.rotary.PsiI);
  sum_dense(sid.rotary.PsiIPsi);
}

std::vector<std::string> DistributedReduction::rank_lines() const {
  const int rank = session_rank(), size = session_size();
  std::vector<std::int64_t> v(static_cast<std::size_t>(4 * size), 0);
  auto* mine = v.data() + 4 * rank;
  mine[0] = static_cast<std::int64_t>(elements_.size());
  mine[1] = assembled_entries_;
  mine[2] = row_entries_;
  mine[3] = peak_rss_bytes();
  sum_over_ranks(v.data(), v.size());
  std::vector<std::string> lines;
  for (int r = 0; r < size; ++r) {
    const auto* x = v.data() + 4 * r;
    std::ostringstream o;
    o << "rank " << r << " of " << size << ": " << x[0] << " elements, " << x[1] << " assembled entries of K and M, "
      << x[2] << " entries in its rows of K and M, peak RSS " << x[3] / (1 << 20) << " MiB";
    lines.push_back(o.str());
  }
  return lines;
}

}  // namespace ffr::preproc::detail
