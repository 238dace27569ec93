/* Plugins that break the contract, for the loader's tests: "nan_score" writes NaN into its
 * scores, "wrong_hypothesis" names a hypothesis past the last, "refuses" fails create() and
 * "needs_gain" has a parameter without default; "lines_map" (well behaved) scores each
 * hypothesis 100 a + b from the lines (a, b) that reset() said it fails, so a test can read
 * the map back. Built twice: as is, and with
 * FAULTY_ABI_VERSION set to another ABI version. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "moorsim_detector_plugin.h"

#ifndef FAULTY_ABI_VERSION
#define FAULTY_ABI_VERSION MOORSIM_DETECTOR_ABI_VERSION
#endif

static int dummy;

static void* faulty_create(const double* values, char* error, size_t error_size) {
  (void)values;
  (void)error;
  (void)error_size;
  return &dummy;
}

static void* refusing_create(const double* values, char* error, size_t error_size) {
  (void)values;
  snprintf(error, error_size, "this detector accepts no configuration");
  return NULL;
}

static int faulty_reset(void* detector, int hypotheses, const int* failed_lines, char* error,
                        size_t error_size) {
  (void)detector;
  (void)hypotheses;
  (void)failed_lines;
  (void)error;
  (void)error_size;
  return 0;
}

static int nan_step(void* detector, const moorsim_evidence* evidence, moorsim_verdict* verdict,
                    char* error, size_t error_size) {
  (void)detector;
  (void)error;
  (void)error_size;
  verdict->score[evidence->hypotheses - 1] = NAN;
  return 0;
}

static int wrong_step(void* detector, const moorsim_evidence* evidence, moorsim_verdict* verdict,
                      char* error, size_t error_size) {
  (void)detector;
  (void)error;
  (void)error_size;
  verdict->hypothesis = evidence->hypotheses;
  verdict->alarm = 1;
  return 0;
}

static void faulty_destroy(void* detector) { (void)detector; }

typedef struct lines_map {
  int hypotheses;
  double code[64];
} lines_map;

static void* lines_map_create(const double* values, char* error, size_t error_size) {
  (void)values;
  lines_map* m = (lines_map*)calloc(1, sizeof(lines_map));
  if (m == NULL) snprintf(error, error_size, "out of memory");
  return m;
}

static int lines_map_reset(void* detector, int hypotheses, const int* failed_lines, char* error,
                           size_t error_size) {
  lines_map* m = (lines_map*)detector;
  if (hypotheses > 64) {
    snprintf(error, error_size, "%d hypotheses, at most 64", hypotheses);
    return 1;
  }
  m->hypotheses = hypotheses;
  for (int h = 0; h < hypotheses; ++h) {
    m->code[h] = 100.0 * failed_lines[2 * h] + failed_lines[2 * h + 1];
  }
  return 0;
}

static int lines_map_step(void* detector, const moorsim_evidence* evidence,
                          moorsim_verdict* verdict, char* error, size_t error_size) {
  const lines_map* m = (const lines_map*)detector;
  (void)evidence;
  (void)error;
  (void)error_size;
  for (int h = 0; h < m->hypotheses; ++h) verdict->score[h] = m->code[h];
  return 0;
}

static void lines_map_destroy(void* detector) { free(detector); }

static const moorsim_parameter needs_gain_parameters[] = {
    {"gain", 0, 0.0, 0.0, 1.0, 1, 0, 0, "", "required, in (0, 1]"},
};

static const moorsim_detector_plugin faulty_types[] = {
    {"nan_score", "writes NaN scores", 0, NULL, 0, faulty_create, faulty_reset, nan_step,
     faulty_destroy},
    {"wrong_hypothesis", "names a hypothesis past the last", 0, NULL, 0, faulty_create,
     faulty_reset, wrong_step, faulty_destroy},
    {"refuses", "fails create()", 0, NULL, 0, refusing_create, faulty_reset, nan_step,
     faulty_destroy},
    {"needs_gain", "has a required parameter", 0, needs_gain_parameters, 1, faulty_create,
     faulty_reset, wrong_step, faulty_destroy},
    {"lines_map", "scores the reset's failed-lines map", 0, NULL, 0, lines_map_create,
     lines_map_reset, lines_map_step, lines_map_destroy},
};

int moorsim_plugin_abi_version(void) { return FAULTY_ABI_VERSION; }

const moorsim_detector_plugin* moorsim_detector_plugins(int* count) {
  *count = 5;
  return faulty_types;
}
