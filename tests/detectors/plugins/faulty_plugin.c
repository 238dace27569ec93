/* Plugins that break the contract, for the loader's tests: "nan_score" writes NaN into its
 * scores, "wrong_hypothesis" names a hypothesis past the last, "refuses" fails create() and
 * "needs_gain" has a parameter without default. Built twice: as is, and with
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

static int faulty_reset(void* detector, int hypotheses, char* error, size_t error_size) {
  (void)detector;
  (void)hypotheses;
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
};

int moorsim_plugin_abi_version(void) { return FAULTY_ABI_VERSION; }

const moorsim_detector_plugin* moorsim_detector_plugins(int* count) {
  *count = 4;
  return faulty_types;
}
