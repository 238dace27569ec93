/* moorsim detector plugins: the C ABI a detector built outside the moorsim tree implements
 * to run beside the built-in ones (in `moorsim run`, `moorsim batch` and the tests).
 *
 * A plugin is a shared library that exports two functions with C linkage:
 *
 *   int moorsim_plugin_abi_version(void);
 *       returns MOORSIM_DETECTOR_ABI_VERSION as the plugin was compiled; moorsim refuses a
 *       library whose version differs from its own before it reads anything else;
 *   const moorsim_detector_plugin* moorsim_detector_plugins(int* count);
 *       the detector types the library provides (*count of them), valid while it is loaded.
 *
 * moorsim calls a type's functions from one thread at a time per detector instance (a
 * campaign runs instances on several threads at once: keep no mutable global state).
 * Every function that can fail returns 0 on success and otherwise writes a one-line reason
 * (NUL-terminated, at most error_size bytes) to `error`; moorsim reports it with the
 * plugin's path and type and records the run as failed.
 *
 * Conventions are moorsim's: SI units, NED Earth frame, hypothesis 0 = every line intact,
 * hypothesis k = line k parted (1-based), further indices for pairs of lines.
 * The version changes whenever a struct below or a function's meaning changes. */
#ifndef MOORSIM_DETECTOR_PLUGIN_H
#define MOORSIM_DETECTOR_PLUGIN_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

#define MOORSIM_DETECTOR_ABI_VERSION 1

/* What one hypothesis's observer makes of a sample: the innovation (measured minus
 * predicted x [m], y [m], psi [rad], psi wrapped), its covariance S (row-major 3 x 3) and
 * the Gaussian log-likelihood log N(innovation; 0, S) over the `dimension` valid channels. */
typedef struct moorsim_hypothesis_evidence {
  double innovation[3];
  double covariance[9];
  double log_likelihood;
  int dimension;
} moorsim_hypothesis_evidence;

/* The intact filter's load picture (EKF observers only): its bias estimate b [N, N, N m]
 * (Earth frame) and covariance (row-major), per hypothesis h the load of the lines h says
 * have failed at the filter's pose (line_load[3 h + i], line_load[0..2] = 0), and the
 * wave-frequency motion estimate [m, m, rad]. */
typedef struct moorsim_load_evidence {
  double bias[3];
  double bias_covariance[9];
  const double* line_load;
  double wave_motion[3];
} moorsim_load_evidence;

/* One sample: time [s] and the evidence of every hypothesis (hypothesis[0] intact);
 * `nominal` the intact model's evidence from a filter nothing but the measurements touch
 * (NULL where the bank does not provide it), `load` NULL unless the observers estimate it. */
typedef struct moorsim_evidence {
  double t;
  int hypotheses;
  const moorsim_hypothesis_evidence* hypothesis;
  const moorsim_hypothesis_evidence* nominal;
  const moorsim_load_evidence* load;
} moorsim_evidence;

/* The plugin's verdict after a sample: score[0 .. hypotheses-1] (moorsim provides the
 * array; what the score means is the plugin's to document, finite values only), the best
 * hypothesis (0 .. hypotheses-1) and whether a failure is declared (0 or 1). */
typedef struct moorsim_verdict {
  double* score;
  int hypothesis;
  int alarm;
} moorsim_verdict;

/* One numeric parameter, as the built-in detectors declare theirs: moorsim checks the
 * values a scenario gives against it (unknown names, out-of-range values and missing
 * required ones are located input errors) before create() sees them. The table is sorted
 * by name. */
typedef struct moorsim_parameter {
  const char* name;
  int has_default; /* 0: the scenario must give it */
  double default_value;
  double min, max; /* max = HUGE_VAL: no upper bound */
  int min_open, max_open, integer;
  const char* unit;        /* "" if dimensionless */
  const char* description; /* one line */
} moorsim_parameter;

typedef struct moorsim_detector_plugin {
  const char* type;        /* the `type:` a scenario names, unique within the library */
  const char* description; /* one line */
  int needs_load_evidence; /* 1: needs moorsim_evidence.load (the EKF observers) */
  const moorsim_parameter* parameters;
  int parameter_count;
  /* A new detector from the checked parameter values, in the table's order; NULL on
   * failure (with the reason in `error`). */
  void* (*create)(const double* values, char* error, size_t error_size);
  /* Starts over for `hypotheses` hypotheses (hypothesis 0 intact). failed_lines[2 h] and
   * failed_lines[2 h + 1] are the 1-based ids of the lines hypothesis h says have parted
   * (0 where there is none: both 0 for h = 0, the second 0 for a single line), so a
   * detector never has to guess where the pairs begin or which lines they join. */
  int (*reset)(void* detector, int hypotheses, const int* failed_lines, char* error,
               size_t error_size);
  /* One sample: reads `evidence`, fills `verdict`. */
  int (*step)(void* detector, const moorsim_evidence* evidence, moorsim_verdict* verdict,
              char* error, size_t error_size);
  void (*destroy)(void* detector);
} moorsim_detector_plugin;

/* The two entry points a plugin exports. */
typedef int (*moorsim_plugin_abi_version_fn)(void);
typedef const moorsim_detector_plugin* (*moorsim_detector_plugins_fn)(int* count);

#ifdef __cplusplus
}
#endif

#endif /* MOORSIM_DETECTOR_PLUGIN_H */
