#include "ffr/preproc/threads.hpp"

#include <algorithm>
#include <atomic>
#include <thread>

namespace ffr::preproc {
namespace {
std::atomic<unsigned> g_max_threads{0};
}

unsigned max_threads() {
  const unsigned n = g_max_threads.load(std::memory_order_relaxed);
  return n > 0 ? n : std::max(1u, std::thread::hardware_concurrency());
}

void set_max_threads(unsigned n) {
  g_max_threads.store(n, std::memory_order_relaxed);
}

}  // namespace ffr::preproc
