#include "stop_signals.hpp"

namespace ffr::sim {
namespace {

std::atomic<int> g_caught{0};  // lock-free, so storing it is async-signal-safe

extern "C" void on_stop_signal(int sig) { g_caught.store(sig, std::memory_order_relaxed); }

// Installs the handler for `sig` unless the process ignores it; keeps the previous action.
bool install(int sig, struct sigaction& old) {
  if (sigaction(sig, nullptr, &old) != 0 || old.sa_handler == SIG_IGN) return false;
  struct sigaction sa {};
  sa.sa_handler = on_stop_signal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESETHAND;
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
