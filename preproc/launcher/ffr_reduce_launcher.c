/* ffr-reduce as users call it: a launcher that chooses the page size of the reduction's heap,
 * then replaces itself (execv) with the reduction program, libexec/ffr/ffr-reduce-main beside this
 * bin/ folder, with the same arguments. Exit status, output and signals are the program's own.
 *
 * Why: a reduction first-touches most of its memory once (the factor alone is ~370 MB on the
 * 100k-DOF plate of tools/bench/reduce), and on some virtual machines a fault on a 4 KiB page
 * costs ~10 us: 300 000 faults, a third of a 9 s run. glibc backs its heap with transparent huge
 * pages when told so by the tunable glibc.malloc.hugetlb=1, which it reads only when a program
 * starts, hence this launcher. On other machines fresh 2 MiB pages cost more than they save (a
 * host that has not backed the memory zeroes them slowly; measured in earlier benchmark runs).
 * So the choice is measured here, in a few milliseconds: fault in 8 MiB as 2 MiB pages and as
 * 4 KiB pages (twice each when the first round is close) and use the huge pages when they fault
 * in at most half the time.
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

#ifndef FFR_REDUCE_PROGRAM
#define FFR_REDUCE_PROGRAM "../libexec/ffr/ffr-reduce-main" /* relative to this launcher's folder */
#endif

static double seconds(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* Time to fault in `bytes` of fresh anonymous memory with the given advice; < 0 on failure. */
static double fault_in(size_t bytes, int advice) {
  const size_t huge = (size_t)2 << 20;
  char* raw = mmap(NULL, bytes + huge, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (raw == MAP_FAILED) return -1;
  char* p = (char*)(((uintptr_t)raw + huge - 1) & ~(uintptr_t)(huge - 1)); /* 2 MiB aligned */
  double t = -1;
  if (madvise(p, bytes, advice) == 0) {
    t = seconds();
    for (size_t i = 0; i < bytes; i += 4096) ((volatile char*)p)[i] = 1;
    t = seconds() - t;
  }
  munmap(raw, bytes + huge);
  return t;
}

static int thp_available(void) {
  FILE* f = fopen("/sys/kernel/mm/transparent_hugepage/enabled", "r");
  if (!f) return 0;
  char line[128] = {0};
  const int ok = fgets(line, sizeof line, f) != NULL && strstr(line, "[never]") == NULL;
  fclose(f);
  return ok;
}

/* "on" or "off", with the measurement behind an automatic choice in `why`; null for a value of
 * FFR_HUGE_PAGES that is none of the accepted ones. */
static const char* choose(char* why, size_t n) {
  const char* want = getenv("FFR_HUGE_PAGES");
  if (want && (!strcmp(want, "on") || !strcmp(want, "1"))) return "on";
  if (want && (!strcmp(want, "off") || !strcmp(want, "0"))) return "off";
  if (want && *want && strcmp(want, "auto") != 0) return NULL;
  if (!thp_available()) return "off";
  const size_t bytes = (size_t)8 << 20;
  double huge = 1e30, small = 1e30;
  /* A second round only when the first is close to the threshold (huge pages at a quarter to
   * the whole of the small pages' time): elsewhere one round decides (here 0.5 ms against 21). */
  for (int round = 0; round < 2; ++round) {
    const double h = fault_in(bytes, MADV_HUGEPAGE), s = fault_in(bytes, MADV_NOHUGEPAGE);
    if (h < 0 || s < 0) return "off";
    if (h < huge) huge = h;
    if (s < small) small = s;
    if (huge < 0.25 * small || huge > small) break;
  }
  snprintf(why, n, "%s (8 MiB faulted in %.1f ms as 2 MiB pages, %.1f ms as 4 KiB pages)",
           huge <= 0.5 * small ? "on" : "off", 1e3 * huge, 1e3 * small);
  return huge <= 0.5 * small ? "on" : "off";
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
    char why[160] = "";
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
