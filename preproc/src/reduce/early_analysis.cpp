// EarlyAnalysis: the structure of the matrix the eigen-solve factorizes, from the mesh and the
// interfaces alone, and its symbolic factorization, on a thread of its own (reduction.hpp).
#include "ffr/preproc/reduce/reduction.hpp"
#include "ffr/preproc/solver/memory.hpp"
#include "ffr/preproc/threads.hpp"
#include "pattern_analysis.hpp"
#include "setup.hpp"
#include "sparse_ops.hpp"
#include "../stopwatch.hpp"

#include <atomic>
#include <chrono>
#include <thread>

namespace ffr::preproc {

struct EarlyAnalysis::State {
  std::thread thread;
  std::atomic<bool> cancel{false};  ///< nobody will take the factor (an error upstream)
  std::atomic<bool> done{false};    ///< the thread has finished
  std::unique_ptr<CholmodFactor> factor;  ///< analysed, or null after a failure
  double seconds = 0;
};

EarlyAnalysis::EarlyAnalysis() noexcept = default;
EarlyAnalysis::EarlyAnalysis(EarlyAnalysis&&) noexcept = default;

EarlyAnalysis::~EarlyAnalysis() {
  // Left without take(): the assembly or the reduction failed before the factorization. The
  // thread skips the analysis if it has not begun it, so the error is not held up by METIS.
  if (!state_) return;
  state_->cancel = true;
  if (state_->thread.joinable()) state_->thread.join();
}

EarlyAnalysis EarlyAnalysis::start(const FeModel& model, const ReductionSpec& spec) {
  EarlyAnalysis e;
  if (max_threads() < 2) return e;
  // The slepc backend factorizes with MUMPS, not CHOLMOD.
  if (spec.backend == "slepc") return e;
  e.state_ = std::make_unique<State>();
  State* s = e.state_.get();
  // The state lives on the heap, so the thread's pointer stays valid when `e` is moved.
  s->thread = std::thread([s, &model, spec] {
    struct Done {
      std::atomic<bool>& flag;
      ~Done() { flag = true; }
    } done{s->done};  // on every way out
    const auto t0 = std::chrono::steady_clock::now();
    try {
      // The structure of K - sigma M is that of the constrained K (M has K's structure); for
      // Craig-Bampton, that of the constrained K's interior block.
      const DofTransform t = build_transform(model, detail::states_for(model, spec));
      const bool cb = spec.method == ReductionSpec::Method::CraigBampton;
      auto f = std::make_unique<CholmodFactor>(detail::eigen_factor_options(spec));
      if (!detail::analyse_from_pattern(model, t, spec, nullptr, &s->cancel, *f)) {
        SparseMatrix C = detail::constrained(t, assembly_pattern(model), cb);
        if (cb) {
          const auto interior = detail::interior_of(C.rows(), detail::boundary_dofs(model, t, spec));
          SparseMatrix Kii = detail::congruence(detail::selection(C.rows(), interior), C);
          C.swap(Kii);  // (Eigen 3.4's SparseMatrix has no move assignment)
        }
        if (s->cancel) return;
        f->analyze(C);
      }
      if (s->cancel) return;
      s->factor = std::move(f);
      // What this thread freed (the structure, METIS's and CHOLMOD's work arrays) stays in its
      // own malloc arena otherwise: ~100 MiB of resident memory on the 100k plate, which
      // raised the run's peak (at the factorization) by 70 MiB.
      release_free_heap();
    } catch (...) {
      // Bad input (an unknown interface, overlapping groups, ...): the reduction meets it
      // again, in its usual order and with its usual message.
      s->factor.reset();
    }
    s->seconds = seconds_since(t0);
  });
  return e;
}

bool EarlyAnalysis::started() const { return state_ != nullptr; }

bool EarlyAnalysis::finished() const { return state_ && state_->done; }

std::unique_ptr<CholmodFactor> EarlyAnalysis::take() {
  if (!state_) return nullptr;
  if (state_->thread.joinable()) state_->thread.join();
  return std::move(state_->factor);
}

double EarlyAnalysis::seconds() const { return state_ ? state_->seconds : 0.0; }

}  // namespace ffr::preproc
