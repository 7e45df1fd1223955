#pragma once
// The three reductions of the part file (preproc/PART_FILE.md, reduction.method):
//  - free: free-free eigenmodes; rigid-body modes deflated exactly (negative shift, so
//    nothing singular is factorized); elastic modes M-orthonormal and M-orthogonal to the
//    rigid-body motion, hence Ct.M0 = Cr.M0 = 0.
//  - clamped: the named interface held; its fixed-interface eigenmodes.
//  - craig-bampton: the frame interface held; six static constraint modes per other
//    interface (unit motion of one interface DOF, the others held), then fixed-interface
//    eigenmodes; optionally the whole basis orthonormalized by a reduced eigen-solve.
// The basis is returned over the full DOFs (Phi = T Phi_ind), ready for the invariants.

#include "ffr/formats/sid.hpp"
#include "ffr/preproc/assembly/assembly.hpp"
#include "ffr/preproc/model/constraints.hpp"
#include "ffr/preproc/solver/cholmod_factor.hpp"

#include <functional>
#include <memory>
#include <string>

namespace ffr::preproc {

struct ReductionLog {
  std::function<void(const std::string&)> message;  ///< stage lines ("factorizing ...")
  std::function<void(const std::string&)> progress; ///< transient progress (Lanczos rounds)
};

struct ReductionResult {
  Eigen::MatrixXd Phi;                      ///< num_dofs x nq, over the full DOFs
  Eigen::VectorXd lambda;                   ///< omega^2 (Rayleigh quotient for static modes)
  std::vector<formats::ModeType> types;
  std::string reference;                    ///< "free", "clamped:<interface>", "craig-bampton"
  Eigen::MatrixXd Ke, Me;                   ///< Phi^T K Phi, Phi^T M Phi (from the FE matrices)
  std::string parameters_json;              ///< method and parameters, for provenance
  // Statistics of the eigen-solve, for the log and provenance.
  FactorStatistics factor;
  double factor_seconds = 0, lanczos_seconds = 0, max_residual = 0, orthonormality_error = 0;
  int iterations = 0;
  std::string backend;
};

/// The symbolic analysis of the matrix the eigen-solve factorizes (K - sigma M for the free and
/// clamped methods, the interior block K_ii for Craig-Bampton), run on another thread while
/// the caller assembles K and M. It needs their structure only (the mesh's connectivity and the
/// interface constraints), so METIS and CHOLMOD's symbolic factorization, serial and 0.6-0.7 s
/// of the 100k-DOF plate, overlap the element integration. Started only with two or more
/// threads (max_threads()); otherwise empty, and reduce() analyses as before. The factor is the
/// same either way: the analysis reads the structure only, and a factorization of a matrix of
/// another structure analyses it anew.
class EarlyAnalysis {
 public:
  EarlyAnalysis() noexcept;
  /// `model` must outlive the analysis (take() and the destructor wait for it; the destructor
  /// first tells it to skip what it has not begun).
  static EarlyAnalysis start(const FeModel& model, const ReductionSpec& spec);
  EarlyAnalysis(EarlyAnalysis&&) noexcept;
  EarlyAnalysis& operator=(EarlyAnalysis&&) = delete;
  ~EarlyAnalysis();

  bool started() const;
  /// The analysis's thread has finished (its factor, if any, is ready for take()).
  bool finished() const;
  /// Waits for the analysis and hands its factor over; null if it was not started or failed
  /// (the caller then analyses itself, and meets the error, if any, where it always did).
  std::unique_ptr<CholmodFactor> take();
  /// Wall seconds the analysis took on its thread (after take()).
  double seconds() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

/// Runs the part's reduction. Throws formats::FormatError (exit 2) for a mechanism, a body in
/// several pieces, an unknown interface; other failures as std::runtime_error. With `early`
/// (started for the same model and spec), the eigen-solve takes its analysed factor over.
ReductionResult reduce(const FeModel& model, const Assembled& fe, const ReductionSpec& spec,
                       const ReductionLog& log = {}, EarlyAnalysis* early = nullptr);

/// The same, for a caller that needs fe.K and fe.M no more: they are freed as soon as the
/// constrained matrices are built, so they do not sit in memory next to the factor (the
/// peak of the whole run). The other members of `fe` are left as they are.
ReductionResult reduce_consuming_matrices(const FeModel& model, Assembled& fe, const ReductionSpec& spec,
                                          const ReductionLog& log = {}, EarlyAnalysis* early = nullptr);

}  // namespace ffr::preproc
