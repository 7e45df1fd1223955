/* The C interface driven from C: open, loads, prescribed motion, stepping, outputs, every kind
 * of error with its code and message, a solver failure that keeps the last state, close.
 * Usage: capi_test MODEL.json FAILING_MODEL.json */
#include "ffr_runtime.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static int failures = 0;
#define CHECK(cond, ...)                                  \
  do {                                                    \
    if (!(cond)) {                                        \
      ++failures;                                         \
      fprintf(stderr, "FAILED line %d: ", __LINE__);      \
      fprintf(stderr, __VA_ARGS__);                       \
      fprintf(stderr, " [last error: %s]\n", ffr_last_error()); \
    }                                                     \
  } while (0)

int main(int argc, char** argv) {
  if (argc < 3) {
    fprintf(stderr, "usage: capi_test MODEL.json FAILING_MODEL.json\n");
    return 2;
  }
  ffr_sim* sim = NULL;

  /* Errors at open: a missing file is bad input, and the message names it. */
  CHECK(ffr_open("/nonexistent/model.json", &sim) == FFR_ERROR_INPUT, "missing model not refused");
  CHECK(sim == NULL, "handle set on failure");
  CHECK(strstr(ffr_last_error(), "/nonexistent/model.json") != NULL, "message does not name the file");
  CHECK(ffr_open(NULL, &sim) == FFR_ERROR_ARGUMENT, "NULL path accepted");

  /* A loaded and an unloaded copy of the same model. */
  ffr_sim *a = NULL, *b = NULL;
  CHECK(ffr_open(argv[1], &a) == FFR_OK, "open");
  CHECK(ffr_open(argv[1], &b) == FFR_OK, "open second");
  if (!a || !b) return 1;
  double h = 0;
  CHECK(ffr_step_size(a, &h) == FFR_OK && fabs(h - 1e-3) < 1e-15, "step size %g", h);
  int n = 0;
  CHECK(ffr_output_size(a, "tip", &n) == FFR_OK && n == 3, "tip size %d", n);

  /* 10 N up (+z) at the beam tip B of a, for 0.5 s; gravity pulls both down. */
  const double up[3] = {0, 0, 10};
  CHECK(ffr_set_load(a, "beam", "B", up, NULL) == FFR_OK, "set load");
  CHECK(ffr_step(a, 500) == FFR_OK, "step a");
  CHECK(ffr_step(b, 500) == FFR_OK, "step b");
  double ta = 0, tipa[3], tipb[3];
  CHECK(ffr_time(a, &ta) == FFR_OK && fabs(ta - 0.5) < 1e-9, "time %g", ta);
  CHECK(ffr_get_output(a, "tip", tipa, 3) == FFR_OK, "output a");
  CHECK(ffr_get_output(b, "tip", tipb, 3) == FFR_OK, "output b");
  CHECK(tipb[2] < 0, "gravity should bend the tip down (%g)", tipb[2]);
  CHECK(tipa[2] > tipb[2] + 1e-4, "the upward load should lift the tip (%g vs %g)", tipa[2], tipb[2]);

  /* Prescribed motion from the caller, set before every step (a smooth 0.2 rad turn over
   * 0.2 s: s = 3 x^2 - 2 x^3), then held: the hub angle follows it. */
  double angle = 0;
  for (int k = 1; k <= 300; ++k) {
    const double T = 0.2, t = (k < 200 ? k : 200) * 1e-3, x = t / T;
    const double v = 0.2 * (3 * x * x - 2 * x * x * x);
    const double vd = k < 200 ? 0.2 * (6 * x - 6 * x * x) / T : 0.0;
    const double vdd = k < 200 ? 0.2 * (6 - 12 * x) / (T * T) : 0.0;
    CHECK(ffr_set_motion(a, "hub", v, vd, vdd) == FFR_OK, "set motion");
    if (ffr_step(a, 1) != FFR_OK) {
      CHECK(0, "step with motion %d", k);
      break;
    }
  }
  CHECK(ffr_get_output(a, "angle", &angle, 1) == FFR_OK && fabs(angle - 0.2) < 1e-9, "angle %g", angle);
  CHECK(ffr_release_motion(a, "hub") == FFR_OK, "release motion");
  CHECK(ffr_clear_loads(a) == FFR_OK, "clear loads");

  /* State save and restore: b steps 50 more, is put back, and steps the same 50 again: the same
   * tip and time to the last bit. (A state of the wrong size or with a NaN is refused.) */
  {
    int ns = 0;
    CHECK(ffr_state_size(b, &ns) == FFR_OK && ns > 0 && ns < 100000, "state size %d", ns);
    static double saved[100000], again[100000], after[100000];
    double tip1[3], tip2[3], t1 = 0, t2 = 0;
    CHECK(ffr_save_state(b, saved, ns) == FFR_OK, "save state");
    CHECK(ffr_save_state(b, again, ns - 1) == FFR_ERROR_ARGUMENT, "short state buffer accepted");
    CHECK(ffr_step(b, 50) == FFR_OK && ffr_get_output(b, "tip", tip1, 3) == FFR_OK && ffr_time(b, &t1) == FFR_OK, "step b on");
    CHECK(ffr_restore_state(b, saved, ns) == FFR_OK, "restore state");
    CHECK(ffr_step(b, 50) == FFR_OK && ffr_get_output(b, "tip", tip2, 3) == FFR_OK && ffr_time(b, &t2) == FFR_OK, "step b again");
    CHECK(memcmp(tip1, tip2, sizeof tip1) == 0 && t1 == t2, "restored run differs: tip z %.17g vs %.17g", tip1[2], tip2[2]);
    CHECK(ffr_save_state(b, again, ns) == FFR_OK, "save again");
    CHECK(ffr_restore_state(b, saved, ns - 1) == FFR_ERROR_ARGUMENT && strstr(ffr_last_error(), "values"), "wrong state size accepted");
    saved[ns / 2] = NAN;
    CHECK(ffr_restore_state(b, saved, ns) == FFR_ERROR_ARGUMENT && strstr(ffr_last_error(), "not finite"), "NaN state accepted");

    CHECK(ffr_save_state(b, after, ns) == FFR_OK && memcmp(after, again, (size_t)ns * sizeof(double)) == 0, "refused restore changed the state");
  }

  /* Argument and lookup errors: codes and messages, state untouched. */
  CHECK(ffr_set_load(a, "nope", NULL, up, NULL) == FFR_ERROR_NOT_FOUND && strstr(ffr_last_error(), "nope"), "unknown body");
  CHECK(ffr_set_load(a, "beam", "Z", up, NULL) == FFR_ERROR_NOT_FOUND && strstr(ffr_last_error(), "'Z'"), "unknown node");
  const double bad[3] = {0, NAN, 0};
  CHECK(ffr_set_load(a, "beam", NULL, bad, NULL) == FFR_ERROR_ARGUMENT, "NaN load accepted");
  CHECK(ffr_set_motion(a, "clamp", 0, 0, 0) == FFR_ERROR_NOT_FOUND, "motion on a joint without one");
  CHECK(ffr_get_output(a, "tip", tipa, 2) == FFR_ERROR_ARGUMENT, "short buffer accepted");
  CHECK(ffr_get_output(a, "nope", tipa, 3) == FFR_ERROR_NOT_FOUND, "unknown output");
  CHECK(ffr_step(a, 0) == FFR_ERROR_ARGUMENT, "zero steps accepted");
  CHECK(ffr_step(NULL, 1) == FFR_ERROR_ARGUMENT, "NULL handle accepted");

  /* A solver failure returns FFR_ERROR_SOLVER, names the time, and keeps the last state. */
  ffr_sim* f = NULL;
  CHECK(ffr_open(argv[2], &f) == FFR_OK, "open failing model");
  if (f) {
    double t0 = -1, t1 = -1;
    ffr_time(f, &t0);
    CHECK(ffr_step(f, 1) == FFR_ERROR_SOLVER, "solver failure not reported");
    CHECK(strstr(ffr_last_error(), "Newton did not converge at t =") != NULL, "failure message");
    ffr_time(f, &t1);
    CHECK(t0 == t1, "time moved on failure (%g -> %g)", t0, t1);
    ffr_close(f);
  }
  long long steps = 0, iters = 0;
  CHECK(ffr_stats(a, &steps, &iters) == FFR_OK && steps == 800 && iters >= 800, "stats %lld %lld", steps, iters);
  ffr_close(a);
  ffr_close(b);
  ffr_close(NULL);
  if (failures == 0) printf("C API: all checks passed (ffr %s)\n", ffr_version());
  return failures ? 1 : 0;
}
