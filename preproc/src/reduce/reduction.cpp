#include "ffr/preproc/reduce/reduction.hpp"

#include "ffr/formats/h5.hpp"
#include "ffr/preproc/solver/eigen_solver.hpp"
#include "ffr/preproc/solver/memory.hpp"
#include "../solver/eigen_backends.hpp"
#include "node_mass.hpp"
#include "pattern_analysis.hpp"
#include "reduction_parts.hpp"
#include "setup.hpp"
#include "sparse_ops.hpp"

#include <Eigen/Eigenvalues>
#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>
#include <algorithm>
#include <sstream>

namespace ffr::preproc {
namespace {

using formats::FormatError;

double seconds_per_time_unit(const std::string& t) { return t == "ms" ? 1e-3 : 1.0; }

// omega^2 of a frequency in Hz, in the part's time unit.
double lambda_of_hz(double hz, const PartSpec& part) {
  const double w = 2 * M_PI * hz * seconds_per_time_unit(part.units.time);
  return w * w;
}

std::string node_text(const FeModel& model, const DofTransform& t, Index ind_dof) {
  Index owner;
  int comp;
  bool is_itf;
  model.dof_owner(t.full_of_ind[static_cast<std::size_t>(ind_dof)], owner, comp, is_itf);
  static const char* names[] = {"ux", "uy", "uz", "rx", "ry", "rz"};
  std::ostringstream o;
  if (is_itf) o << "interface '" << model.interfaces[static_cast<std::size_t>(owner)].name << "'";
  else o << "node " << model.mesh->node_tag(owner);
  o << " (" << names[comp] << ")";
  return o.str();
}

[[noreturn]] void mechanism(const FeModel& model, const std::string& what) {
  throw FormatError(model.part->file.string(), "reduction",
                    "the part is a mechanism or not held enough: " + what);
}

// Near-zero eigenvalues mean mechanisms (after exact deflation of the rigid-body modes).
void check_no_zero_modes(const FeModel& model, const Eigen::VectorXd& lambda, const PartSpec& part,
                         const std::string& held) {
  const double zero = 1e-6 * lambda_of_hz(1.0, part);  // ~1 mHz
  int n = 0;
  for (Index i = 0; i < lambda.size(); ++i) n += lambda(i) < zero ? 1 : 0;
  if (n > 0)
    mechanism(model, std::to_string(n) + " zero-frequency mode(s) " + held +
                         "; check that every piece is connected and enough of the part is held");
}

EigenOptions eigen_options(const ReductionSpec& spec, const PartSpec& part, double sigma) {
  EigenOptions o;
  o.nev = spec.modes > 0 ? spec.modes : 10;
  if (spec.max_frequency_hz) o.lambda_max = lambda_of_hz(*spec.max_frequency_hz, part);
  o.sigma = sigma;
  o.backend = spec.backend == "arpack"  ? EigenBackend::Arpack
              : spec.backend == "block" ? EigenBackend::Block
              : spec.backend == "slepc" ? EigenBackend::Slepc
                                        : EigenBackend::Spectra;
  o.factor = detail::eigen_factor_options(spec);
  o.mumps = spec.mumps;
  return o;
}

void attach_progress(EigenSolver& s, const ReductionLog& log) {
  if (!log.progress) return;
  s.set_progress([&log](const EigenProgress& p) {
    std::ostringstream o;
    o << p.stage << ": round " << p.round << ", nev " << p.nev << ", " << p.operator_applications << " solves";
    if (p.converged >= 0) o << ", " << p.converged << " converged";
    log.progress(o.str());
  });
}

void record(ReductionResult& r, const EigenSolver& s) {
  r.factor = s.info().factor;
  r.factor_seconds = s.info().factorize_seconds;
  r.lanczos_seconds = s.info().lanczos_seconds;
  r.iterations = s.info().iterations;
  r.max_residual = s.result().max_relative_residual;
  r.orthonormality_error = s.result().orthonormality_error;
  r.backend = to_string(s.info().backend_used);
}

// Wall seconds since t0 (and restart the clock).
double lap(std::chrono::steady_clock::time_point& t0) {
  const auto now = std::chrono::steady_clock::now();
  const double s = std::chrono::duration<double>(now - t0).count();
  t0 = now;
  return s;
}

// One line with the parts of the eigen-solve, for anyone looking for where the time goes.
std::string timing_line(double constraints, double analyze, double factorize, const EigenInfo* eig) {
  std::ostringstream o;
  o.precision(3);
  o << "timing: constraints " << constraints << " s, analyze " << analyze << " s, factorize " << factorize << " s";
  if (eig && eig->factor.factor_parallel_fraction > 0)
    o << " (" << std::lround(100 * eig->factor.factor_parallel_fraction) << " % of its flops in parallel subtrees)";
  if (eig) {
    const FactorStatistics& f = eig->factor;
    o << ", lanczos " << eig->lanczos_seconds << " s, solves " << eig->operator_applications << " (on ";
    if (f.solve_threads > 1) o << f.solve_threads << " threads, " << std::lround(100 * f.solve_parallel_fraction) << " % of the factor in parallel";
    else o << "1 thread";
    o << "), checks " << eig->verify_seconds << " s";
  }
  return o.str();
}

std::string factor_line(const FactorStatistics& f) {
  std::ostringstream o;
  o.precision(3);
  o << "factor: n = " << f.n << ", nnz(L) = " << f.nnz_L << ", " << f.flops / 1e9 << " GFlop, "
    << static_cast<double>(f.peak_bytes) / (1u << 20) << " MiB peak (" << f.ordering;
  if (f.ordering_vertices != f.n) o << " on " << f.ordering_vertices << " nodes";
  o << ")";
  const bool blas = f.dense_kernels.empty() || f.dense_kernels == "BLAS";
  if (!blas) o << ", dense kernels " << f.dense_kernels;
  if (!f.blas_kernels.empty()) o << (blas ? ", OpenBLAS " : " (OpenBLAS's: ") << f.blas_kernels << (blas ? " kernels" : ")");
  // Advice only where the BLAS does the factorization's work.
  if (blas && !f.blas_kernels_suited.empty())
    o << " (this CPU runs the faster " << f.blas_kernels_suited << " ones: set OPENBLAS_CORETYPE=" << f.blas_kernels_suited
      << ")";
  return o.str();
}

// The eigen-solve's factor of A, analysed: taken over from the early analysis when there was
// one (it keeps that analysis as long as A has the structure it was made for: factorize
// compares them), else analysed here. Its statistics go to the log either way.
CholmodFactor analysed_factor(const SparseMatrix& A, const FeModel& model, const DofTransform& t,
                              const ReductionSpec& spec, EarlyAnalysis* early, const ReductionLog& log) {
  std::unique_ptr<CholmodFactor> taken = early ? early->take() : nullptr;
  CholmodFactor factor = taken ? std::move(*taken) : CholmodFactor(detail::eigen_factor_options(spec));
  // The early analysis's order from the node graph here too (pattern_analysis.hpp).
  if (!taken && !detail::analyse_from_pattern(model, t, spec, &A, nullptr, factor)) factor.analyze(A);
  std::string line = factor_line(factor.info().stats);
  if (taken) {
    std::ostringstream o;
    o.precision(3);
    o << ", analysed during the assembly in " << early->seconds() << " s";
    line += o.str();
  }
  if (log.message) log.message(line);
  return factor;
}

// The block Lanczos's products with M from the solids' node mass, where it is the same matrix
// (node_mass.hpp).
void use_node_mass(EigenOptions& o, const FeModel& model, const Assembled& fe, const DofTransform& t,
                   const ReductionSpec& spec) {
  if (auto product = detail::NodeMassProduct::make(model, fe, detail::factorized_rows(model, t, spec)))
    o.mass_product = [product](const Eigen::MatrixXd& X, Eigen::MatrixXd& Y) { product->apply(X, Y); };
}

// A body in several pieces has more rigid-body modes than the six a free reduction removes,
// and held at one interface its other pieces are mechanisms: refused naming a node of each.
void require_one_piece(const FeModel& model) {
  const auto pieces = connected_pieces(model);
  if (pieces.size() <= 1) return;
  std::ostringstream o;
  o << "the body is not one connected piece: " << pieces.size() << " pieces (containing nodes";
  for (std::size_t i = 0; i < std::min<std::size_t>(pieces.size(), 5); ++i) o << ' ' << model.mesh->node_tag(pieces[i]);
  o << (pieces.size() > 5 ? " ...)" : ")");
  throw FormatError(model.part->file.string(), "geometry", o.str());
}

// K and M on the independent DOFs (T^T K T, T^T M T). The eigen-solves need only the upper
// triangles (half the memory, and the products with them read half the bytes); Craig-Bampton
// partitions K into blocks and keeps full storage. Where M has K's structure (one pattern and
// one transform) only M's values are kept, read on K's index arrays: M's own indices are half
// of it (31 MB of the 100k plate of tools/bench/reduce at both of its memory peaks).
struct ConstrainedPencil {
  SparseMatrix K;
  SparseMatrix M;                 ///< empty when M lives on K's structure (m_values)
  std::vector<double> m_values;   ///< M's values on K's structure, when shared
  bool shared = false;
  SymmetricStorage storage = SymmetricStorage::UpperOnly;

  /// M as the solvers read it; `on_K` must outlive the result (it is the view of m_values).
  SparseRef mass(const Eigen::Map<const SparseMatrix>& on_K) const { return shared ? SparseRef(on_K) : SparseRef(M); }
  Eigen::Map<const SparseMatrix> mass_on_K() const {
    return {K.rows(), K.cols(), K.nonZeros(), K.outerIndexPtr(), K.innerIndexPtr(), m_values.data()};
  }
};

// fe_owned: the same object as fe, when its K and M may be freed once constrained.
ConstrainedPencil constrain_pencil(const FeModel& model, const Assembled& fe, Assembled* fe_owned,
                                   const ReductionSpec& spec, const DofTransform& t) {
  ConstrainedPencil p;
  const bool cb = spec.method == ReductionSpec::Method::CraigBampton;
  p.storage = cb ? SymmetricStorage::Full : SymmetricStorage::UpperOnly;
  p.K = detail::constrained(t, fe.K, cb);
  if (fe_owned) detail::release(fe_owned->K);
  // Without an assembled M (AssemblyOptions::node_mass_only) its values on K's structure come
  // from Ms; the caller asks for that only where it can be done.
  const bool assembled_M = fe.M.rows() > 0;
  if (!assembled_M) {
    if (!cb) p.m_values = detail::node_mass_values(model, fe.Ms, p.K, detail::factorized_rows(model, t, spec));
    if (p.m_values.size() != static_cast<std::size_t>(p.K.nonZeros()))
      throw std::logic_error("reduction: M was not assembled, and this reduction cannot form it from the node mass");
    p.shared = true;
    return p;
  }
  p.M = detail::constrained(t, fe.M, cb);
  if (fe_owned) detail::release(fe_owned->M);
  p.shared = !cb && detail::same_structure(p.K, p.M);
  if (p.shared) {
    p.m_values.assign(p.M.valuePtr(), p.M.valuePtr() + p.M.nonZeros());
    detail::release(p.M);
  }
  return p;
}

// Where densities are 0 (point masses on a massless structure), M is singular, and the
// eigen-solvers fail on it (the block Lanczos, Spectra and ARPACK alike: garbage or zero
// eigenvalues and a failed residual check, exit 1, naming no input): refused as bad input.
void require_mass_at_every_dof(const SparseRef& M, const PartSpec& part) {
  Index massless = 0;
  const auto* outer = M.outerIndexPtr();
  const auto* inner = M.innerIndexPtr();
  for (Index j = 0; j < M.outerSize(); ++j) {
    const auto* d = std::lower_bound(inner + outer[j], inner + outer[j + 1], j);  // rows are sorted
    massless += d != inner + outer[j + 1] && *d == j && M.valuePtr()[d - inner] != 0.0 ? 0 : 1;
  }
  detail::require_mass(massless, M.cols(), part);
}

}  // namespace

void detail::require_mass(Index massless, Index n, const PartSpec& part) {
  if (massless > 0)
    throw FormatError(part.file.string(), "materials",
                      std::to_string(massless) + " of " + std::to_string(n) +
                          " degrees of freedom carry no mass (a density of 0): the eigen-solve needs mass at every "
                          "one; give each material a density (a small one for a nearly massless part)");
}

namespace {

// The shifted stiffness C = K - sigma M (upper triangle), a matrix of its own: K stays as
// assembled for the eigen-solver's products and checks. On M's shared structure only the
// values are combined.
SparseMatrix shifted_stiffness(const ConstrainedPencil& p, const SparseRef& M, double sigma) {
  if (!p.shared) return shifted_upper(p.K, M, sigma);
  SparseMatrix C = p.K;
  detail::add_scaled_values(C, M, -sigma);
  return C;
}

// The eigen-solver's modes as the basis, refused if some are mechanisms; Ke and Me of exactly
// these vectors, from the eigen-solver's checks.
void modes_from(const EigenSolver& solver, const FeModel& model, const PartSpec& part, const std::string& held,
                ReductionResult& r, Eigen::MatrixXd& basis) {
  check_no_zero_modes(model, solver.result().lambda, part, held);
  basis = solver.result().X;
  r.Ke = solver.result().XtKX;
  r.Me = solver.result().XtMX;
  r.lambda = solver.result().lambda;
  r.types.assign(static_cast<std::size_t>(basis.cols()), formats::ModeType::Normal);
}

// Free or clamped: the lowest eigenpairs (lambda, x) of K x = lambda M x above the shift sigma
// (below every wanted eigenvalue, so that K - sigma M is definite), with the rigid-body modes
// deflated for a free body. The modes are the basis; Ke = X^T K X, Me = X^T M X.
void eigenmode_basis(const FeModel& model, const Assembled& fe, const ConstrainedPencil& p, const DofTransform& t,
                     const ReductionSpec& spec, const ReductionLog& log, EarlyAnalysis* early,
                     std::chrono::steady_clock::time_point& clock, ReductionResult& r, Eigen::MatrixXd& basis,
                     nlohmann::json& params) {
  const PartSpec& part = *model.part;
  const auto M_on_K = p.mass_on_K();
  const SparseRef M = p.mass(M_on_K);
  const bool free = spec.method == ReductionSpec::Method::Free;
  // Free: a negative shift keeps K - sigma M definite while the rigid-body modes are deflated.
  const double sigma = free ? -lambda_of_hz(1.0, part) : -lambda_of_hz(0.1, part);
  EigenOptions o = eigen_options(spec, part, sigma);
  if (free) o.deflation = rigid_body_modes(model, t);
  use_node_mass(o, model, fe, t, spec);
  if (log.message)
    log.message(std::string(free ? "free-free" : "clamped") + " eigen-solve: " + std::to_string(t.num_ind()) + " DOF, " +
                (spec.max_frequency_hz ? "up to " + std::to_string(*spec.max_frequency_hz) + " Hz"
                                       : std::to_string(o.nev) + " modes") +
                ", " + spec.backend + ", " + (spec.backend == "slepc" ? std::string("MUMPS") : spec.factorization) +
                " factorization");
  const double t_constraints = lap(clock);
  if (o.backend == EigenBackend::Slepc) {
    // SLEPc factorizes K - sigma M itself (MUMPS, distributed over the ranks): no factor here.
    EigenSolver solver(o);
    attach_progress(solver, log);
    solver.compute(p.K, M);
    if (log.message) {
      std::ostringstream line;
      line.precision(3);
      line << "timing: constraints " << t_constraints << " s, SLEPc Krylov-Schur with its MUMPS factorization "
           << solver.info().lanczos_seconds << " s (" << solver.info().iterations << " restarts), checks "
           << solver.info().verify_seconds << " s";
      log.message(line.str());
    }
    record(r, solver);
    modes_from(solver, model, part, free ? "beyond the six rigid-body modes" : "with the interface held", r, basis);
    r.reference = free ? "free" : "clamped:" + spec.interface;
    params = {{"method", free ? "free" : "clamped"}, {"shift", sigma}, {"backend", r.backend}};
    if (!free) params["interface"] = spec.interface;
    return;
  }
  SparseMatrix C = shifted_stiffness(p, M, sigma);
  // Analysed first and the factor's size reported, so a factor that will not fit is refused
  // (by factorize, with the numbers) after the user has seen what it would need.
  CholmodFactor factor = analysed_factor(C, model, t, spec, early, log);
  const double t_analyze = lap(clock);
  double t_factorize = 0;
  EigenSolver solver(o);
  attach_progress(solver, log);
  // What the assembly, the constraints and the analysis freed (METIS's and CHOLMOD's work
  // arrays at one thread, where the analysis runs here) would otherwise stay resident under
  // the factorization: 58 MB on the 100k plate.
  release_free_heap();
  try {
    factor.factorize_shifted_upper(C, sigma);
    detail::release(C);  // the factor holds what the solves need
    // The factorization's workspace, freed now, sits in the middle of the heap: given back
    // before the Lanczos vectors are allocated on top of it.
    release_free_heap();
    t_factorize = lap(clock);
    solver.compute(p.K, M, factor);
  } catch (const NotPositiveDefiniteError& e) {
    mechanism(model, "the stiffness is singular at " + node_text(model, t, e.column));
  }
  if (log.message) log.message(timing_line(t_constraints, t_analyze, t_factorize, &solver.info()));
  record(r, solver);
  r.factor = factor.info().stats;
  modes_from(solver, model, part, free ? "beyond the six rigid-body modes" : "with the interface held", r, basis);
  r.reference = free ? "free" : "clamped:" + spec.interface;
  params = {{"method", free ? "free" : "clamped"}, {"shift", sigma}, {"backend", r.backend}};
  if (!free) params["interface"] = spec.interface;
}

// Craig-Bampton: with the frame interface held, the boundary b = the six DOFs of every other
// interface node, the interior i the rest. The basis is [I 0; Psi_i Phi_i]: the static
// constraint modes Psi_i = -K_ii^{-1} K_ib (the interior's response to a unit motion of each
// boundary DOF) and the fixed-interface modes Phi_i of (K_ii, M_ii), both with one factor of
// K_ii. A constraint mode's frequency is its Rayleigh quotient.
void craig_bampton_basis(const FeModel& model, const Assembled& fe, const ConstrainedPencil& p, const DofTransform& t,
                         const ReductionSpec& spec, const ReductionLog& log, EarlyAnalysis* early,
                         std::chrono::steady_clock::time_point& clock, ReductionResult& r, Eigen::MatrixXd& basis,
                         nlohmann::json& params) {
  const PartSpec& part = *model.part;
  const SparseMatrix& K = p.K;
  const SparseMatrix& M = p.M;
  const std::vector<Index> boundary = detail::boundary_dofs(model, t, spec);
  const auto split = detail::split(K, M, boundary);
  if (log.message)
    log.message("craig-bampton: " + std::to_string(boundary.size()) + " boundary DOF, " +
                std::to_string(split.interior.size()) + " interior DOF, " +
                (spec.backend == "slepc" ? std::string("MUMPS") : spec.factorization) + " factorization");
  const double t_constraints = lap(clock);
  // The slepc backend: the constraint modes and the fixed-interface modes from MUMPS factors
  // distributed over the ranks (one for the solves, one inside SLEPc), no CHOLMOD factor.
  const bool distributed = spec.backend == "slepc";
  CholmodFactor factor = distributed ? CholmodFactor(detail::eigen_factor_options(spec))
                                     : analysed_factor(split.Kii, model, t, spec, early, log);
  const double t_analyze = lap(clock);
  Eigen::MatrixXd Psi_i;
  try {
    if (distributed) {
      Psi_i = -detail::distributed_spd_solve(split.Kii, SymmetricStorage::Full, Eigen::MatrixXd(split.Kib), spec.mumps);
    } else {
      factor.factorize(split.Kii);
      Psi_i = -factor.solve(Eigen::MatrixXd(split.Kib));
    }
  } catch (const NotPositiveDefiniteError& e) {
    mechanism(model, "with the frame interface '" + spec.frame + "' held, the stiffness is singular" +
                         (e.column >= 0 ? " at " + node_text(model, t, split.interior[static_cast<std::size_t>(e.column)])
                                        : std::string(" (") + e.what() + ")"));
  }
  const double t_factorize = lap(clock);
  r.factor = factor.info().stats;
  Eigen::MatrixXd modes_i;
  Eigen::VectorXd lambda_n;
  if (spec.modes > 0 || spec.max_frequency_hz) {
    EigenOptions o = eigen_options(spec, part, 0.0);
    use_node_mass(o, model, fe, t, spec);
    EigenSolver solver(o);
    attach_progress(solver, log);
    if (distributed) solver.compute(split.Kii, split.Mii);
    else solver.compute(split.Kii, split.Mii, factor);
    if (log.message) log.message(timing_line(t_constraints, t_analyze, t_factorize, &solver.info()));
    record(r, solver);
    check_no_zero_modes(model, solver.result().lambda, part, "with the frame interface held");
    modes_i = solver.result().X;
    lambda_n = solver.result().lambda;
  } else if (log.message) {
    log.message(timing_line(t_constraints, t_analyze, t_factorize, nullptr));
  }
  const Index nb = static_cast<Index>(boundary.size());
  const Index nn = modes_i.cols();
  basis = Eigen::MatrixXd::Zero(t.num_ind(), nb + nn);
  for (Index j = 0; j < nb; ++j) {
    basis(boundary[static_cast<std::size_t>(j)], j) = 1.0;
    for (std::size_t i = 0; i < split.interior.size(); ++i) basis(split.interior[i], j) = Psi_i(static_cast<Index>(i), j);
  }
  for (Index j = 0; j < nn; ++j)
    for (std::size_t i = 0; i < split.interior.size(); ++i) basis(split.interior[i], nb + j) = modes_i(static_cast<Index>(i), j);
  r.types.assign(static_cast<std::size_t>(nb), formats::ModeType::Constraint);
  r.types.resize(static_cast<std::size_t>(nb + nn), formats::ModeType::Normal);
  r.lambda.resize(nb + nn);
  for (Index j = 0; j < nb; ++j) {
    const Eigen::VectorXd kb = K * basis.col(j), mb = M * basis.col(j);
    r.lambda(j) = basis.col(j).dot(kb) / basis.col(j).dot(mb);  // Rayleigh quotient
  }
  r.lambda.tail(nn) = lambda_n;
  r.reference = "craig-bampton";
  params = {{"method", "craig-bampton"}, {"interfaces", spec.interfaces}, {"frame", spec.frame},
            {"orthonormalized", spec.orthonormalize}};
  if (spec.orthonormalize) {
    // The whole basis replaced by the eigenvectors of the reduced pencil (all normal modes).
    const Eigen::MatrixXd Kr = basis.transpose() * sym_multiply(K, p.storage, basis);
    const Eigen::MatrixXd Mr = basis.transpose() * sym_multiply(M, p.storage, basis);
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> ges(Kr, Mr);
    if (ges.info() != Eigen::Success) throw std::runtime_error("orthonormalization of the Craig-Bampton basis failed");
    basis = basis * ges.eigenvectors();
    r.lambda = ges.eigenvalues();
    r.types.assign(static_cast<std::size_t>(basis.cols()), formats::ModeType::Normal);
  }
  r.Ke = basis.transpose() * sym_multiply(K, p.storage, basis);
  r.Me = basis.transpose() * sym_multiply(M, p.storage, basis);
}

// The reduction: the constrained pencil (K, M) on the independent DOFs, a basis of it (modes,
// or Craig-Bampton's constraint and fixed-interface modes), and the basis over the full DOFs
// Phi = T basis. fe_owned: the same object as fe, when its K and M may be freed after use.
ReductionResult reduce_impl(const FeModel& model, const Assembled& fe, Assembled* fe_owned, const ReductionSpec& spec,
                            const ReductionLog& log, EarlyAnalysis* early) {
  require_one_piece(model);
  auto clock = std::chrono::steady_clock::now();
  const DofTransform t = build_transform(model, detail::states_for(model, spec));
  const ConstrainedPencil pencil = constrain_pencil(model, fe, fe_owned, spec, t);
  {
    const auto M_on_K = pencil.mass_on_K();
    require_mass_at_every_dof(pencil.mass(M_on_K), *model.part);
  }
  ReductionResult r;
  nlohmann::json params;
  Eigen::MatrixXd basis;  // over the independent DOFs
  if (spec.method == ReductionSpec::Method::CraigBampton)
    craig_bampton_basis(model, fe, pencil, t, spec, log, early, clock, r, basis, params);
  else
    eigenmode_basis(model, fe, pencil, t, spec, log, early, clock, r, basis, params);
  params["modes"] = spec.modes;
  if (spec.max_frequency_hz) params["max_frequency_hz"] = *spec.max_frequency_hz;
  params["factorization"] = spec.factorization;
  r.parameters_json = params.dump();
  r.Phi = t.identity ? basis : Eigen::MatrixXd(t.T * basis);
  return r;
}

}  // namespace

ReductionResult reduce(const FeModel& model, const Assembled& fe, const ReductionSpec& spec, const ReductionLog& log,
                       EarlyAnalysis* early) {
  return reduce_impl(model, fe, nullptr, spec, log, early);
}

ReductionResult reduce_consuming_matrices(const FeModel& model, Assembled& fe, const ReductionSpec& spec,
                                          const ReductionLog& log, EarlyAnalysis* early) {
  return reduce_impl(model, fe, &fe, spec, log, early);
}

double detail::lambda_of_frequency(double hz, const PartSpec& part) { return lambda_of_hz(hz, part); }
EigenOptions detail::reduction_eigen_options(const ReductionSpec& spec, const PartSpec& part, double sigma) {
  return eigen_options(spec, part, sigma);
}
void detail::require_connected(const FeModel& model) { require_one_piece(model); }
void detail::require_no_zero_modes(const FeModel& model, const Eigen::VectorXd& lambda, const std::string& held) {
  check_no_zero_modes(model, lambda, *model.part, held);
}

}  // namespace ffr::preproc
