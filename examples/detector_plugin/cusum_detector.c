/* A moorsim detector plugin in plain C, built outside the moorsim tree (CMakeLists.txt
 * beside it) and by moorsim's tests: a bank CUSUM.
 * For every hypothesis h >= 1 it sums the log-likelihood ratio of h against "intact" less
 * a drift, S_h <- max(0, S_h + log L_h - log L_0 - drift) (Page 1954; Basseville &
 * Nikiforov 1993, section 2.2), and declares a failure of the h with the largest S_h once
 * that exceeds `threshold`. Scores: S_h [nats], score[0] = 0. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "moorsim_detector_plugin.h"

typedef struct cusum {
  double drift, threshold;
  int hypotheses;
  double* sum;
} cusum;

/* In the parameter table's order (sorted by name): drift, threshold. */
static void* cusum_create(const double* values, char* error, size_t error_size) {
  cusum* c = (cusum*)calloc(1, sizeof(cusum));
  if (c == NULL) {
    snprintf(error, error_size, "out of memory");
    return NULL;
  }
  c->drift = values[0];
  c->threshold = values[1];
  return c;
}

static int cusum_reset(void* detector, int hypotheses, const int* failed_lines, char* error,
                        size_t error_size) {
  cusum* c = (cusum*)detector;
  (void)failed_lines; /* every hypothesis is scored alike, single lines and pairs */
  double* sum = (double*)realloc(c->sum, (size_t)hypotheses * sizeof(double));
  if (sum == NULL) {
    snprintf(error, error_size, "out of memory for %d hypotheses", hypotheses);
    return 1;
  }
  c->sum = sum;
  c->hypotheses = hypotheses;
  for (int h = 0; h < hypotheses; ++h) c->sum[h] = 0.0;
  return 0;
}

static int cusum_step(void* detector, const moorsim_evidence* evidence, moorsim_verdict* verdict,
                      char* error, size_t error_size) {
  cusum* c = (cusum*)detector;
  if (evidence->hypotheses != c->hypotheses) {
    snprintf(error, error_size, "%d hypotheses after a reset for %d", evidence->hypotheses,
             c->hypotheses);
    return 1;
  }
  const double intact = evidence->hypothesis[0].log_likelihood;
  int best = 0;
  for (int h = 1; h < c->hypotheses; ++h) {
    const double ratio = evidence->hypothesis[h].log_likelihood - intact;
    c->sum[h] = fmax(0.0, c->sum[h] + ratio - c->drift);
    if (best == 0 || c->sum[h] > c->sum[best]) best = h;
    verdict->score[h] = c->sum[h];
  }
  verdict->score[0] = 0.0;
  verdict->alarm = best != 0 && c->sum[best] > c->threshold;
  verdict->hypothesis = verdict->alarm ? best : 0;
  return 0;
}

static void cusum_destroy(void* detector) {
  cusum* c = (cusum*)detector;
  if (c != NULL) free(c->sum);
  free(c);
}

static const moorsim_parameter cusum_parameters[] = {
    {"drift", 1, 0.0, 0.0, HUGE_VAL, 0, 0, 0, "nats",
     "subtracted from each sample's log-likelihood ratio"},
    {"threshold", 1, 10.0, 0.0, HUGE_VAL, 1, 0, 0, "nats", "sum that declares a failure"},
};

static const moorsim_detector_plugin cusum_types[] = {
    {"bank_cusum", "Page's CUSUM of each hypothesis's log-likelihood ratio against intact", 0,
     cusum_parameters, 2, cusum_create, cusum_reset, cusum_step, cusum_destroy},
};

int moorsim_plugin_abi_version(void) { return MOORSIM_DETECTOR_ABI_VERSION; }

const moorsim_detector_plugin* moorsim_detector_plugins(int* count) {
  *count = 1;
  return cusum_types;
}
