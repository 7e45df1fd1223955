#pragma once
// SIGINT and SIGTERM (Ctrl-C, a batch system's time limit) turned into a stop request of the
// time loop for `ffr-sim --keep-partial`, so that an interrupted run still writes what it has.

#include <atomic>
#include <csignal>

namespace ffr::sim {

/// While alive: the first SIGINT or SIGTERM sets flag() instead of ending the process; another
/// one a second or more later ends it at once (the default action), so a run that does not stop
/// can still be killed; one sooner is taken for the first delivered twice. A signal the process
/// was started ignoring (nohup, a background job) stays ignored.
class StopOnSignals {
 public:
  StopOnSignals();
  ~StopOnSignals();
  StopOnSignals(const StopOnSignals&) = delete;
  StopOnSignals& operator=(const StopOnSignals&) = delete;

  const std::atomic<int>* flag() const;
  int signal() const;  ///< the signal caught, 0 if none
  /// Restores the previous handlers and raises the caught signal again, so that the caller's
  /// shell sees the process end by it (exit status 128 + signal); returns if none was caught.
  void reraise();

 private:
  struct sigaction old_int_ {}, old_term_ {};
  bool int_installed_ = false, term_installed_ = false;
  void restore();
};

}  // namespace ffr::sim
