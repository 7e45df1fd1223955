#pragma once
// Fresh memory faulted in by one system call before it is first written.
//
// Why: the first write to each 4 KiB page of fresh memory takes a page fault, and the
// factorization's first pass writes the whole factor (430 MB on the 100k-DOF plate of
// tools/bench/reduce, 105 000 pages). Linux (5.14 on) faults in a range at once on request
// (MADV_POPULATE_WRITE), without the trap of each fault: on the AMD EPYC VM of that benchmark,
// 400 MiB of fresh memory took 139-186 ms so against 203-226 ms written a page at a time (four
// alternating pairs). Pages already present are left as they are; where the kernel does not know
// the request, nothing happens and the writes fault as before.

#include <cstddef>
#include <cstdint>

#include <sys/mman.h>
#include <unistd.h>

#ifndef MADV_POPULATE_WRITE
#define MADV_POPULATE_WRITE 23
#endif

namespace ffr::preproc::detail {

/// Faults in, for writing, the whole pages inside [p, p + bytes).
inline void populate_for_writing(void* p, std::size_t bytes) {
  static const auto page = static_cast<std::uintptr_t>(sysconf(_SC_PAGESIZE) > 0 ? sysconf(_SC_PAGESIZE) : 4096);
  const auto begin = (reinterpret_cast<std::uintptr_t>(p) + page - 1) & ~(page - 1);
  const auto end = (reinterpret_cast<std::uintptr_t>(p) + bytes) & ~(page - 1);
  if (end > begin) (void)madvise(reinterpret_cast<void*>(begin), end - begin, MADV_POPULATE_WRITE);
}

}  // namespace ffr::preproc::detail
