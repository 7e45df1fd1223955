#pragma once
// Wall time of a stage of the reducer, for the statistics and progress it reports (internal).

#include <chrono>

namespace ffr::preproc {

inline double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace ffr::preproc
