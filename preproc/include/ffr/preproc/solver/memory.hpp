#pragma once
// Memory facts the solver layer needs before it commits to a large allocation, and the
// peak-RSS probe the benchmarks print. Linux only (reads /proc and /sys/fs/cgroup).

#include <cstdint>
#include <optional>
#include <string>

namespace ffr::preproc {

/// Bytes the process can still allocate without swapping: /proc/meminfo MemAvailable,
/// lowered to the cgroup (v2 memory.max - memory.current, or v1 limit - usage) headroom when
/// the process runs in a memory-limited container. nullopt if /proc/meminfo is unreadable.
std::optional<std::uint64_t> available_memory_bytes();

/// Peak resident set size of this process (VmHWM of /proc/self/status), 0 if unknown.
std::uint64_t peak_rss_bytes();

/// Current resident set size (VmRSS), 0 if unknown.
std::uint64_t current_rss_bytes();

/// Resets the VmHWM counter to the current RSS (writes "5" to /proc/self/clear_refs) so a
/// benchmark can measure the peak of one stage. Returns false if the kernel refused.
bool reset_peak_rss();

/// Gives the pages of freed heap memory back to the system (glibc's malloc_trim; nothing
/// elsewhere). Why: glibc returns only the top of its heaps by itself, and after the first
/// large free it serves allocations up to 32 MiB from them, so the work arrays of one stage
/// (CHOLMOD's and METIS's, the assembly's) stay resident under the next stage's peak. Costs a
/// walk over the free chunks: call it between stages, not in loops.
void release_free_heap();

/// "1.23 GiB", "456.0 MiB", "789 B": for messages and benchmark tables.
std::string format_bytes(std::uint64_t bytes);

}  // namespace ffr::preproc
