/* ffr-reduce as users call it: a launcher that chooses the page size of the reduction's heap,
 * then replaces itself (execv) with the reduction program, libexec/ffr/ffr-reduce-main beside this
 * bin/ folder, with the same arguments. Exit status, output and signals are the program's own.
 *
 * Why: a reduction first-touches most of its memory once (the factor alone is ~370 MB on the
 * 100k-DOF plate of tools/bench/reduce), and on some virtual machines a fault on a 4 KiB page
 * costs ~10 us: 300 000 faults, a third of a 9 s run. glibc backs its heap with transparent huge
 * pages when told so by the tunable glibc.malloc.hugetlb=1, which it reads only when a program
 * starts, hence this launcher. On other machines fresh 2 MiB pages cost more than they save (a
 * host that has not backed the memory zeroes them slowly). So the choice is measured here: 8 MiB
 * faulted in as 4 KiB pages (twice), then up to 64 MiB as 2 MiB pages one page at a time, stopped
 * as soon as the verdict is clear; where the guest reports its free pages to the host, huge pages
 * are taken only when small faults are slower than the host's re-faulting of a huge page
 * (huge_page_verdict.h says why a small sample of huge pages misleads there).
 *
 * FFR_HUGE_PAGES=on|off|auto (default auto) overrides the probe; a GLIBC_TUNABLES that already
 * names glibc.malloc.hugetlb is left as it is. The program logs the choice (FFR_HUGE_PAGES_CHOSEN).
 * Plain C with libc only, so that starting it costs nothing next to the program it starts. */
#define _GNU_SOURCE
#include <errno.h>
#include <limits.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <time.h>
#include <unistd.h>

#include "huge_page_verdict.h"

#ifndef FFR_REDUCE_PROGRAM
#define FFR_REDUCE_PROGRAM "../libexec/ffr/ffr-reduce-main" /* relative to this launcher's folder */
#endif

static double seconds(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* Fresh anonymous memory, 2 MiB aligned, with the given advice; null on failure. */
static char* map_aligned(size_t bytes, int advice, char** raw) {
  const size_t huge = (size_t)2 << 20;
  *raw = mmap(NULL, bytes + huge, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (*raw == MAP_FAILED) return NULL;
  char* p = (char*)(((uintptr_t)*raw + huge - 1) & ~(uintptr_t)(huge - 1));
  if (madvise(p, bytes, advice) != 0) {
    munmap(*raw, bytes + huge);
    return NULL;
  }
  return p;
}

/* Touches every 4 KiB page of [p, p + bytes): a 2 MiB page that fell back to small pages is
 * timed as the 512 faults it then costs. */
static double touch(char* p, size_t bytes) {
  const double t = seconds();
  for (size_t i = 0; i < bytes; i += 4096) ((volatile char*)p)[i] = 1;
  return seconds() - t;
}

/* Walks up to FFR_PROBE_MAX_PAGES huge pages until ffr_huge_page_verdict decides; the pages
 * walked and their time go to *pages and *total, the last FFR_PROBE_SLOW_RUN pages' to *last. */
static int walk_huge_pages(double small_2mib, int* pages, double* total, double* last) {
  const size_t huge = (size_t)2 << 20, bytes = (size_t)FFR_PROBE_MAX_PAGES * huge;
  char* raw = NULL;
  char* p = map_aligned(bytes, MADV_HUGEPAGE, &raw);
  if (!p) return FFR_PROBE_OFF;
  double t[FFR_PROBE_MAX_PAGES];
  int verdict = FFR_PROBE_MORE, n = 0;
  *total = *last = 0;
  while (verdict == FFR_PROBE_MORE) {
    t[n] = touch(p + (size_t)n * huge, huge);
    *total += t[n];
    verdict = ffr_huge_page_verdict(t, ++n, small_2mib);
  }
  for (int i = n > FFR_PROBE_SLOW_RUN ? n - FFR_PROBE_SLOW_RUN : 0; i < n; ++i) *last += t[i];
  *pages = n;
  munmap(raw, bytes + huge);
  return verdict;
}

static int thp_available(void) {
  FILE* f = fopen("/sys/kernel/mm/transparent_hugepage/enabled", "r");
  if (!f) return 0;
  char line[128] = {0};
  const int ok = fgets(line, sizeof line, f) != NULL && strstr(line, "[never]") == NULL;
  fclose(f);
  return ok;
}

/* Whether a virtio balloon device reports free pages to the host (feature bit 5,
 * VIRTIO_BALLOON_F_REPORTING, in the driver's features string, bit 0 first). */
static int free_page_reporting(void) {
  for (int d = 0; d < 64; ++d) {
    char path[96], text[160] = {0};
    snprintf(path, sizeof path, "/sys/bus/virtio/devices/virtio%d/device", d);
    FILE* f = fopen(path, "r");
    if (!f) continue;
    const int balloon = fgets(text, sizeof text, f) != NULL && strtol(text, NULL, 0) == 5;
    fclose(f);
    if (!balloon) continue;
    snprintf(path, sizeof path, "/sys/bus/virtio/devices/virtio%d/features", d);
    if (!(f = fopen(path, "r"))) continue;
    const int reporting = fgets(text, sizeof text, f) != NULL && strlen(text) > 5 && text[5] == '1';
    fclose(f);
    if (reporting) return 1;
  }
  return 0;
}

/* "on" or "off", with the measurement behind an automatic choice in `why`; null for a value of
 * FFR_HUGE_PAGES that is none of the accepted ones. */
static const char* choose(char* why, size_t n) {
  const char* want = getenv("FFR_HUGE_PAGES");
  if (want && (!strcmp(want, "on") || !strcmp(want, "1"))) return "on";
  if (want && (!strcmp(want, "off") || !strcmp(want, "0"))) return "off";
  if (want && *want && strcmp(want, "auto") != 0) return NULL;
  if (!thp_available()) return "off";
  /* 4 KiB pages: the better of two samples of 8 MiB (a single one was 4-8 times slow at times). */
  const size_t small_bytes = (size_t)8 << 20;
  double small = 1e30;
  for (int round = 0; round < 2; ++round) {
    char* raw = NULL;
    char* p = map_aligned(small_bytes, MADV_NOHUGEPAGE, &raw);
    if (!p) return "off";
    const double t = touch(p, small_bytes);
    if (t < small) small = t;
    munmap(raw, small_bytes + ((size_t)2 << 20));
  }
  int pages = 0;
  double total = 0, last = 0;
  const int verdict = walk_huge_pages(small / 4, &pages, &total, &last);
  const int reporting = free_page_reporting();
  const char* choice = ffr_huge_pages_pay(verdict, small / 4, reporting) ? "on" : "off";
  snprintf(why, n,
           "%s (%d MiB faulted in %.1f ms as 2 MiB pages, the last %d MiB in %.1f ms; 8 MiB in %.1f ms as 4 KiB "
           "pages%s)",
           choice, 2 * pages, 1e3 * total, 2 * (pages < FFR_PROBE_SLOW_RUN ? pages : FFR_PROBE_SLOW_RUN), 1e3 * last,
           1e3 * small, reporting ? "; free pages are reported to the host" : "");
  return choice;
}

int main(int argc, char** argv) {
  (void)argc;
  char self[PATH_MAX], program[PATH_MAX];
  const ssize_t len = readlink("/proc/self/exe", self, sizeof self - 1);
  if (len <= 0) {
    fprintf(stderr, "ffr-reduce: error: cannot find its own location (/proc/self/exe): %s\n", strerror(errno));
    return 1;
  }
  self[len] = '\0';
  char* slash = strrchr(self, '/');
  if (slash) *slash = '\0';
  if (snprintf(program, sizeof program, "%s/%s", self, FFR_REDUCE_PROGRAM) >= (int)sizeof program) {
    fprintf(stderr, "ffr-reduce: error: path too long: %s\n", self);
    return 1;
  }

  const char* tunables = getenv("GLIBC_TUNABLES");
  if (!tunables || !strstr(tunables, "glibc.malloc.hugetlb")) {
    char why[320] = "";
    const char* choice = choose(why, sizeof why);
    if (!choice) {
      fprintf(stderr, "ffr-reduce: error: environment variable FFR_HUGE_PAGES: expected on, off or auto, got '%s'\n",
              getenv("FFR_HUGE_PAGES"));
      return 2;
    }
    setenv("FFR_HUGE_PAGES_CHOSEN", why[0] ? why : choice, 1);
    if (!strcmp(choice, "on")) {
      char value[1024];
      const int w = tunables && *tunables ? snprintf(value, sizeof value, "%s:glibc.malloc.hugetlb=1", tunables)
                                          : snprintf(value, sizeof value, "glibc.malloc.hugetlb=1");
      if (w > 0 && w < (int)sizeof value) setenv("GLIBC_TUNABLES", value, 1);
    }
  }
  execv(program, argv);
  fprintf(stderr, "ffr-reduce: error: cannot start the reduction program %s: %s\n", program, strerror(errno));
  return 1;
}
