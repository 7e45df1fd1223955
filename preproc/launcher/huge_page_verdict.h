/* The launcher's rule for 2 MiB heap pages, from measured fault-in times (ffr_reduce_launcher.c).
 * A plain function of the timings so that tests can hand it the cases met on real machines.
 *
 * Why a walk over many huge pages, not one small sample: on a virtual machine whose balloon
 * device reports free memory to the host (virtio free page reporting, 2 MiB blocks), the guest
 * keeps only the blocks freed in the last seconds backed by the host. The first 2 MiB pages a
 * program touches come from those and fault in at ~6-8 GB/s; the rest come from blocks the host
 * has dropped and fault in at 0.4-0.6 GB/s, a quarter of the rate of 4 KiB pages (measured on
 * the AMD EPYC VM of tools/bench/reduce/RESULTS.md, twenty-second session: 8 MiB sampled as huge
 * pages looked 4-9 times faster, 400 MiB were 3.5-4.5 times slower).
 *
 * Why the walk is not enough where free pages are reported: how many blocks are still backed
 * depends on what ran before. On that VM a walk of 64 MiB was sometimes fast all the way, and the
 * run it chose huge pages for was still slower (twelve alternating runs: 3.63-4.11 s against
 * 3.32-3.61 s with 4 KiB pages). Freed huge pages go back to the host within seconds (its
 * counter of reported memory grew by 264 MiB after 400 MiB of huge pages were freed, by 4 MiB
 * after 400 MiB of small ones), so a program that takes huge pages pays the host's faults again
 * on every run. There, huge pages are chosen only when 4 KiB faults are slower than the host's
 * re-faulting of a huge page (0.4-0.6 GB/s there, ~4 ms per 2 MiB), as on a paravirtualised VM
 * of the sixteenth session, whose 4 KiB faults took ~10 us each (5 ms per 2 MiB). */
#ifndef FFR_HUGE_PAGE_VERDICT_H
#define FFR_HUGE_PAGE_VERDICT_H

enum { FFR_PROBE_MORE = 0, FFR_PROBE_ON = 1, FFR_PROBE_OFF = 2 };

/* Huge pages are walked up to this many (64 MiB); a run of this many slow ones ends the walk. */
enum { FFR_PROBE_MAX_PAGES = 32, FFR_PROBE_SLOW_RUN = 3 };

/* Verdict after the first `count` 2 MiB pages of the walk took page_seconds[0..count) each, when
 * 2 MiB faulted in as 4 KiB pages take small_seconds. A huge page pays when it takes at most half
 * of that. OFF as soon as the last FFR_PROBE_SLOW_RUN pages were all slow; at the end of the walk
 * ON only when its second half paid on average; MORE until then. */
static inline int ffr_huge_page_verdict(const double* page_seconds, int count, double small_seconds) {
  const double pays = 0.5 * small_seconds;
  if (count >= FFR_PROBE_SLOW_RUN) {
    int slow = 0;
    for (int i = count - FFR_PROBE_SLOW_RUN; i < count; ++i) slow += page_seconds[i] > pays;
    if (slow == FFR_PROBE_SLOW_RUN) return FFR_PROBE_OFF;
  }
  if (count < FFR_PROBE_MAX_PAGES) return FFR_PROBE_MORE;
  double late = 0;
  for (int i = count / 2; i < count; ++i) late += page_seconds[i];
  return late / (count - count / 2) <= pays ? FFR_PROBE_ON : FFR_PROBE_OFF;
}

/* Seconds to fault in a 2 MiB page that its host had dropped, as measured above. */
#define FFR_REPORTED_HUGE_PAGE_SECONDS 4e-3

/* Whether the heap takes 2 MiB pages: the walk's verdict, and where the guest reports its free
 * pages to the host, 4 KiB faults (small_seconds per 2 MiB) slower than a re-faulted huge page. */
static inline int ffr_huge_pages_pay(int walk_verdict, double small_seconds, int free_page_reporting) {
  if (walk_verdict != FFR_PROBE_ON) return 0;
  return !free_page_reporting || small_seconds > FFR_REPORTED_HUGE_PAGE_SECONDS;
}

#endif
