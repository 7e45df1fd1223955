#pragma once
// How many worker threads the preprocessor's own thread pools use (element assembly, the
// shell/beam invariant pass, the geometric-stiffness projection). Process-wide, like
// Eigen::setNbThreads: a command line sets it once (ffr-reduce --threads) so that a benchmark
// or a shared machine can hold the whole run to N cores. It counts only the library's own
// threads: the BLAS's and OpenMP's counts belong to the host program (ffr-reduce sets them in
// main(), tools/common/include/ffr/cli/process_threads.hpp), never to the library.

namespace ffr::preproc {

/// The thread count in effect: the last set_max_threads(n > 0), else the hardware concurrency.
unsigned max_threads();
/// n > 0 sets it; 0 restores the default (hardware concurrency).
void set_max_threads(unsigned n);

}  // namespace ffr::preproc
