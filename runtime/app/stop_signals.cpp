#include "stop_signals.hpp"

#include <time.h>

namespace ffr::sim {
namespace {

// Lock-free, so the handler's loads and stores are async-signal-safe.
std::atomic<int> g_caught{0};
std::atomic<long long> g_first_ns{0};

long long monotonic_ns() {
  timespec now{};
  clock_gettime(CLOCK_MONOTONIC, &now);  // async-signal-safe
  return static_cast<long long>(now.tv_sec) * 1000000000LL + now.tv_nsec;
}

// The first signal asks the run to stop. One within a second of it is the same request arriving
// twice (`timeout` signals the process and then its process group) and is dropped; a later one
// takes the signal's default action at once.
extern "C" void on_stop_signal(int sig) {
  const long long now = monotonic_ns();
  int none = 0;
  if (g_caught.compare_exchange_strong(none, sig)) {
    g_first_ns.store(now);
    return;
  }
  if (now - g_first_ns.load() < 1000000000LL) return;
  struct sigaction dfl {};
  dfl.sa_handler = SIG_DFL;
  sigemptyset(&dfl.sa_mask);
  sigaction(sig, &dfl, nullptr);
  raise(sig);  // blocked while this handler runs: delivered, with the default action, on return
}

// Installs the handler for `sig` unless the process ignores it; keeps the previous action.
bool install(int sig, struct sigaction& old) {
  if (sigaction(sig, nullptr, &old) != 0 || old.sa_handler == SIG_IGN) return false;
  struct sigaction sa {};
  sa.sa_handler = on_stop_signal;
  sigemptyset(&sa.sa_mask);
  return sigaction(sig, &sa, nullptr) == 0;
}

}  // namespace

StopOnSignals::StopOnSignals() {
  g_caught.store(0);
  int_installed_ = install(SIGINT, old_int_);
  term_installed_ = install(SIGTERM, old_term_);
}

StopOnSignals::~StopOnSignals() { restore(); }

void StopOnSignals::restore() {
  if (int_installed_) sigaction(SIGINT, &old_int_, nullptr);
  if (term_installed_) sigaction(SIGTERM, &old_term_, nullptr);
  int_installed_ = term_installed_ = false;
}

const std::atomic<int>* StopOnSignals::flag() const { return &g_caught; }

int StopOnSignals::signal() const { return g_caught.load(); }

void StopOnSignals::reraise() {
  const int sig = g_caught.load();
  restore();
  if (sig != 0) std::raise(sig);
}

}  // namespace ffr::sim
