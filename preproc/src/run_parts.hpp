#pragma once
// Runs a body over parts of a range, one thread per part, the first part on the calling thread;
// the preprocessor's fork-join mechanism (the assembly's colour classes, the eigen-solver's
// substitutions, products with M and orthogonalisation). parts_for() sizes the memory-bound
// vector work of the eigen-solver: one core does not saturate the memory bus here (one stream
// 20-24 GB/s, two concurrent streams about 20 GB/s each), so two threads nearly halve it, and
// small ranges stay on one thread: starting one costs tens of microseconds.

#include "ffr/preproc/threads.hpp"

#include <algorithm>
#include <cstdint>
#include <exception>
#include <thread>
#include <vector>

namespace ffr::preproc::detail {

/// Parts for a range of `work` units (e.g. stored entries): 1 below min_work, else
/// max_threads() (at most 8).
inline unsigned parts_for(std::int64_t work, std::int64_t min_work) {
  if (work < min_work) return 1;
  return std::clamp(max_threads(), 1u, 8u);
}

/// body(part, begin, end) for `parts` parts with boundaries from split(part) (split(0) = begin
/// of the range, split(parts) = its end). The first exception thrown by a part is rethrown
/// after all parts have finished.
template <class Split, class Body>
void run_parts(unsigned parts, Split&& split, Body&& body) {
  if (parts <= 1) {
    body(0u, split(0u), split(1u));
    return;
  }
  std::vector<std::exception_ptr> errors(parts);
  auto guarded = [&](unsigned p) {
    try {
      body(p, split(p), split(p + 1));
    } catch (...) {
      errors[p] = std::current_exception();
    }
  };
  std::vector<std::thread> pool;
  pool.reserve(parts - 1);
  try {
    for (unsigned p = 1; p < parts; ++p) pool.emplace_back(guarded, p);
  } catch (...) {  // no thread to be had: join those started, then report it
    for (auto& t : pool) t.join();
    throw;
  }
  guarded(0);
  for (auto& t : pool) t.join();
  for (auto& e : errors)
    if (e) std::rethrow_exception(e);
}

}  // namespace ffr::preproc::detail
