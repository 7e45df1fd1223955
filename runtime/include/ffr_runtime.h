/* ffr runtime, C interface: open a model, drive it step by step, read its outputs.
 *
 * Every function returns an ffr_status (0 = FFR_OK); on failure the message of the last
 * failing call in the calling thread is available from ffr_last_error(). No C++ exception
 * crosses this interface. A handle is not thread-safe: use one per thread.
 *
 *   ffr_sim* sim = NULL;
 *   if (ffr_open("model.json", &sim) != FFR_OK) { puts(ffr_last_error()); return 1; }
 *   double f[3] = {0, 0, -10}, tau[3] = {0, 0, 0};
 *   ffr_set_load(sim, "rod", "B", f, tau);       // held until changed
 *   ffr_step(sim, 100);
 *   double tip[3]; ffr_get_output(sim, "tip", tip, 3);
 *   ffr_close(sim);
 */
#ifndef FFR_RUNTIME_H
#define FFR_RUNTIME_H

#ifdef __cplusplus
extern "C" {
#endif

typedef struct ffr_sim ffr_sim;

typedef enum ffr_status {
  FFR_OK = 0,
  FFR_ERROR_INPUT = 1,     /* bad model file or SID file (the message names the file and field) */
  FFR_ERROR_SOLVER = 2,    /* the integration failed (Newton divergence, inconsistent constraints) */
  FFR_ERROR_ARGUMENT = 3,  /* a null pointer, a wrong size, a non-finite number */
  FFR_ERROR_NOT_FOUND = 4, /* no body, node, joint, motion or output of that name */
  FFR_ERROR_INTERNAL = 5   /* anything else (out of memory, ...) */
} ffr_status;

/* Version string of the library ("0.1.0"). */
const char* ffr_version(void);

/* Message of the last failing call in this thread ("" if none). Valid until the next call. */
const char* ffr_last_error(void);

/* Loads the model (and its SID files), makes the initial state consistent. *sim is NULL on failure. */
int ffr_open(const char* model_path, ffr_sim** sim);

/* Same from the model file's JSON text: relative SID paths are resolved against base_dir (NULL:
   the working directory); name (NULL: "<model text>") stands for the file in messages. */
int ffr_open_json(const char* json_text, const char* base_dir, const char* name, ffr_sim** sim);

/* Makes the initial state consistent again, now with the loads and motions set since opening
   (ffr_open did it without them: the first step would start from accelerations without the
   loads). Only at the start time, before the first step. */
int ffr_reinitialize(ffr_sim* sim);

/* Frees everything; NULL is accepted. */
void ffr_close(ffr_sim* sim);

/* Current time and the fixed step of the model [s] (with "step": "auto", the output interval). */
int ffr_time(const ffr_sim* sim, double* t);
int ffr_step_size(const ffr_sim* sim, double* h);

/* Advances n >= 1 steps (with "step": "auto", n output intervals of adaptive steps). On a solver
   failure the state is that of the last accepted step. */
int ffr_step(ffr_sim* sim, int n);

/* The integrator's state: time, coordinates, rates, accelerations, multipliers and what the
 * scheme and the step need to go on from them (runtime/include/ffr/runtime/state.hpp), as
 * ffr_state_size() doubles. After ffr_restore_state() the simulation continues bit for bit as it
 * did from the saved point (with the same loads and motions set); with the relative formulation
 * to rounding only (its joint coordinates are taken afresh from the restored absolute state, its
 * predictor's history not kept). The values are for saving and restoring with the same model
 * only, not for editing. */
int ffr_state_size(const ffr_sim* sim, int* size);
int ffr_save_state(const ffr_sim* sim, double* buffer, int capacity);
int ffr_restore_state(ffr_sim* sim, const double* buffer, int size);

/* External load on a body: force [N] and torque [N m], global components, applied at a SID node
 * (node = name) or at the body's frame origin (node = NULL). Either vector may be NULL (zero).
 * Held until set again; ffr_clear_loads() removes all of them. */
int ffr_set_load(ffr_sim* sim, const char* body, const char* node, const double force[3], const double torque[3]);
int ffr_clear_loads(ffr_sim* sim);

/* Prescribed motion of a joint that has a motion in the model: value, rate and acceleration
 * from now on (instead of the table). ffr_release_motion() returns it to its table. */
int ffr_set_motion(ffr_sim* sim, const char* joint, double value, double rate, double acceleration);
int ffr_release_motion(ffr_sim* sim, const char* joint);

/* Outputs declared in the model file, evaluated at the current state. */
int ffr_output_size(const ffr_sim* sim, const char* output, int* size);
int ffr_get_output(ffr_sim* sim, const char* output, double* values, int capacity);

/* Totals since ffr_open. */
int ffr_stats(const ffr_sim* sim, long long* steps, long long* newton_iterations);

#ifdef __cplusplus
}
#endif

#endif /* FFR_RUNTIME_H */
