/* Every function of moorsim's C API misused the way a C program can: null handles and
 * pointers, arrays of the wrong length, NaN and infinities, huge and tiny times and steps,
 * calls out of order, states of another model and states cut short; then a long seeded
 * sequence of such calls on live instances. Whatever the call, it must return one of the
 * API's codes (never crash, which the sanitizer build also checks), a refusal must leave a
 * message that starts with the function's name, and a refused call must not move the
 * instance's time. Exit 0 if all of that held; each broken rule is one line on stderr.
 *
 *   c_api_misuse SOURCE_DIR     (for the library's seed scenario) */
#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "moorsim/moorsim.h"

static int failures = 0;

/* `code` (from `function`, `what` saying how it was called) must be an API code; a refusal
 * one of `allowed` (a bit per code) with a message naming the function. */
static void check(int code, const char* function, const char* what, unsigned allowed) {
  if (code < MOORSIM_OK || code > MOORSIM_ERROR_INTERRUPTED) {
    fprintf(stderr, "%s (%s): code %d is none of the API's\n", function, what, code);
    ++failures;
    return;
  }
  if (!(allowed & (1u << code))) {
    fprintf(stderr, "%s (%s): code %d, message '%s'\n", function, what, code, moorsim_last_error());
    ++failures;
  }
  if (code != MOORSIM_OK && strncmp(moorsim_last_error(), function, strlen(function)) != 0) {
    fprintf(stderr, "%s (%s): code %d with the message '%s'\n", function, what, code,
            moorsim_last_error());
    ++failures;
  }
}

#define OK (1u << MOORSIM_OK)
#define USAGE (1u << MOORSIM_ERROR_USAGE)
#define INPUT (1u << MOORSIM_ERROR_INPUT)
#define SOLVER (1u << MOORSIM_ERROR_SOLVER)
#define INTERRUPTED (1u << MOORSIM_ERROR_INTERRUPTED)

/* Four chains in 150 m of water, 20 segments each (as tests/api/c_api_test.cc). */
static const char* const kLines =
    "mooring:\n"
    "  water: {density: 1025, gravity: 9.81, depth: 150}\n"
    "  seabed: {stiffness: 3.0e6, damping: 3.0e5}\n"
    "  line_types:\n"
    "    - {name: chain, diameter: 0.08, mass_per_length: 140, axial_stiffness: 6.0e8,\n"
    "       axial_damping_ratio: 0.5, drag_normal: 1.2, drag_tangential: 0.4,\n"
    "       added_mass_normal: 1.0}\n"
    "  lines:\n"
    "    - {id: 1, type: chain, anchor: [600, 0, 150], fairlead: [10, 0, 5], length: 640}\n"
    "    - {id: 2, type: chain, anchor: [0, 600, 150], fairlead: [0, 10, 5], length: 640}\n"
    "    - {id: 3, type: chain, anchor: [-600, 0, 150], fairlead: [-10, 0, 5], length: 640}\n"
    "    - {id: 4, type: chain, anchor: [0, -600, 150], fairlead: [0, -10, 5], length: 640}\n"
    "  defaults: {segments: 20}\n";

/* A seeded generator (xorshift64*): the same sequence on every machine. */
static uint64_t state = 20261207u;
static uint64_t next(void) {
  state ^= state >> 12;
  state ^= state << 25;
  state ^= state >> 27;
  return state * 2685821657736338717ull;
}
static size_t below(size_t n) { return (size_t)(next() % n); }

static double any_double(void) {
  static const double pool[] = {0.0,    -0.0,   1.0,    -1.0,    0.1,  0.05,    1e-9,
                                5e-324, 1e-300, 1e300,  -1e300,  1e8,  86400.5, DBL_MAX,
                                -1.0e6, 3.0,    1000.0, -1000.0, 0.25, 2.0,     0.5};
  const size_t k = below(sizeof pool / sizeof pool[0] + 3);
  if (k == sizeof pool / sizeof pool[0]) return NAN;
  if (k == sizeof pool / sizeof pool[0] + 1) return INFINITY;
  if (k == sizeof pool / sizeof pool[0] + 2) return -INFINITY;
  return pool[k];
}
static int any_int(void) {
  static const int pool[] = {0, 1, 2, 3, 4, 5, -1, 7, 19, 20, 21, 63, INT_MAX, INT_MIN};
  return pool[below(sizeof pool / sizeof pool[0])];
}
/* A pose or rate: mostly sensible, sometimes not. */
static void any_dofs(double* x, int sensible) {
  for (int d = 0; d < 6; ++d) x[d] = sensible ? (double)below(5) * 0.2 - 0.4 : any_double();
}

/* The instance's time, to check that a refused call left it. */
static double lines_time(moorsim_lines* lines) {
  double t = NAN;
  if (moorsim_lines_time(lines, &t) != MOORSIM_OK) return NAN;
  return t;
}
static double plant_time(moorsim_plant* plant) {
  double t = NAN;
  if (moorsim_plant_time(plant, &t) != MOORSIM_OK) return NAN;
  return t;
}

/* Null handles and pointers, every function. */
static void null_everything(void) {
  double v[64];
  int n = 0;
  size_t size = 0;
  check(moorsim_lines_coupled_dofs(NULL, &n), "moorsim_lines_coupled_dofs", "NULL", USAGE);
  check(moorsim_lines_count(NULL, &n), "moorsim_lines_count", "NULL", USAGE);
  check(moorsim_lines_node_count(NULL, 1, &n), "moorsim_lines_node_count", "NULL", USAGE);
  check(moorsim_lines_time(NULL, v), "moorsim_lines_time", "NULL", USAGE);
  check(moorsim_lines_init(NULL, v, v), "moorsim_lines_init", "NULL", USAGE);
  check(moorsim_lines_step(NULL, v, v, v, v, v), "moorsim_lines_step", "NULL", USAGE);
  check(moorsim_lines_body_load(NULL, v), "moorsim_lines_body_load", "NULL", USAGE);
  check(moorsim_lines_fairlead_tensions(NULL, v, 4), "moorsim_lines_fairlead_tensions", "NULL",
        USAGE);
  check(moorsim_lines_fairlead_forces(NULL, v, 12), "moorsim_lines_fairlead_forces", "NULL", USAGE);
  check(moorsim_lines_anchor_tensions(NULL, v, 4), "moorsim_lines_anchor_tensions", "NULL", USAGE);
  check(moorsim_lines_segment_tensions(NULL, 1, v, 20), "moorsim_lines_segment_tensions", "NULL",
        USAGE);
  check(moorsim_lines_node_positions(NULL, 1, v, 63), "moorsim_lines_node_positions", "NULL",
        USAGE);
  check(moorsim_lines_part(NULL, 1, MOORSIM_PART_FAIRLEAD, 0), "moorsim_lines_part", "NULL", USAGE);
  check(moorsim_lines_save(NULL, NULL, 0, &size), "moorsim_lines_save", "NULL", USAGE);
  check(moorsim_lines_restore(NULL, v, 8), "moorsim_lines_restore", "NULL", USAGE);
  if (moorsim_lines_interrupt(NULL) != MOORSIM_ERROR_USAGE) {
    fprintf(stderr, "moorsim_lines_interrupt (NULL): not MOORSIM_ERROR_USAGE\n");
    ++failures;
  }
  moorsim_lines_destroy(NULL);
  if (moorsim_lines_create(NULL) != NULL || moorsim_lines_create_from_yaml(NULL) != NULL) {
    fprintf(stderr, "moorsim_lines_create* (NULL): a handle\n");
    ++failures;
  }
  check(moorsim_plant_line_count(NULL, &n), "moorsim_plant_line_count", "NULL", USAGE);
  check(moorsim_plant_time(NULL, v), "moorsim_plant_time", "NULL", USAGE);
  check(moorsim_plant_advance_to(NULL, 1.0), "moorsim_plant_advance_to", "NULL", USAGE);
  check(moorsim_plant_set_thrust(NULL, v), "moorsim_plant_set_thrust", "NULL", USAGE);
  check(moorsim_plant_set_external_load(NULL, v), "moorsim_plant_set_external_load", "NULL", USAGE);
  check(moorsim_plant_pose(NULL, v), "moorsim_plant_pose", "NULL", USAGE);
  check(moorsim_plant_measured_pose(NULL, v), "moorsim_plant_measured_pose", "NULL", USAGE);
  check(moorsim_plant_fairlead_tensions(NULL, v, 8), "moorsim_plant_fairlead_tensions", "NULL",
        USAGE);
  check(moorsim_plant_measured_tensions(NULL, v, 8), "moorsim_plant_measured_tensions", "NULL",
        USAGE);
  check(moorsim_plant_thrust(NULL, v, v), "moorsim_plant_thrust", "NULL", USAGE);
  check(moorsim_plant_loads(NULL, v, 30), "moorsim_plant_loads", "NULL", USAGE);
  check(moorsim_plant_save(NULL, NULL, 0, &size), "moorsim_plant_save", "NULL", USAGE);
  check(moorsim_plant_restore(NULL, v, 8), "moorsim_plant_restore", "NULL", USAGE);
  if (moorsim_plant_interrupt(NULL) != MOORSIM_ERROR_USAGE) {
    fprintf(stderr, "moorsim_plant_interrupt (NULL): not MOORSIM_ERROR_USAGE\n");
    ++failures;
  }
  moorsim_plant_destroy(NULL);
  if (moorsim_plant_create(NULL, 1) != NULL || moorsim_plant_create_from_yaml(NULL, 1) != NULL) {
    fprintf(stderr, "moorsim_plant_create* (NULL): a handle\n");
    ++failures;
  }
  /* Texts that are no scenario. */
  const char* const texts[] = {
      "", "{", "mooring: ~", "\xff\xfe", "base: /dev/zero", "mooring: {lines: []}"};
  for (size_t k = 0; k < sizeof texts / sizeof texts[0]; ++k) {
    moorsim_lines* l = moorsim_lines_create_from_yaml(texts[k]);
    moorsim_plant* p = moorsim_plant_create_from_yaml(texts[k], 1);
    if (l != NULL || p != NULL || moorsim_last_error()[0] == '\0') {
      fprintf(stderr, "create from '%s': a handle, or no message\n", texts[k]);
      ++failures;
    }
    moorsim_lines_destroy(l);
    moorsim_plant_destroy(p);
  }
}

/* One call of the lines' functions, its arguments drawn from the pools. */
static void lines_call(moorsim_lines* lines, const unsigned char* foreign, size_t foreign_size) {
  double x[6], xd[6], f[6], buffer[200], t = 0.0, dt = 0.0;
  int n = 0;
  size_t size = 0;
  const double before = lines_time(lines);
  int code = MOORSIM_OK;
  const char* function = "";
  switch (below(12)) {
    case 0:
      any_dofs(x, below(4) != 0);
      any_dofs(xd, below(4) != 0);
      function = "moorsim_lines_init";
      code = moorsim_lines_init(lines, below(8) ? x : NULL, xd);
      check(code, function, "drawn pose", OK | USAGE | INPUT | SOLVER);
      return; /* init may move the time back to 0 */
    case 1:
    case 2:
    case 3:
      any_dofs(x, below(4) != 0);
      any_dofs(xd, below(4) != 0);
      t = below(6) ? lines_time(lines) : any_double();
      dt = below(3) ? 0.05 * (double)(1 + below(3)) : any_double();
      if (dt >= 10.0 && dt <= 86400.0) dt = 0.5; /* valid but long: not what is tested here */
      function = "moorsim_lines_step";
      code = moorsim_lines_step(lines, x, xd, below(10) ? f : NULL, &t, &dt);
      /* An interrupt asked before lines that could not step yet is taken by this one. */
      check(code, function, "drawn step", OK | USAGE | INPUT | SOLVER | INTERRUPTED);
      break;
    case 4:
      function = "moorsim_lines_fairlead_tensions";
      code = moorsim_lines_fairlead_tensions(lines, below(8) ? buffer : NULL, any_int());
      check(code, function, "drawn length", OK | USAGE);
      break;
    case 5:
      function = "moorsim_lines_fairlead_forces";
      code = moorsim_lines_fairlead_forces(lines, buffer, below(2) ? 12 : any_int());
      check(code, function, "drawn length", OK | USAGE);
      break;
    case 6:
      function = "moorsim_lines_segment_tensions";
      code = moorsim_lines_segment_tensions(lines, any_int(), buffer, below(2) ? 20 : any_int());
      check(code, function, "drawn line and length", OK | USAGE);
      break;
    case 7:
      function = "moorsim_lines_node_positions";
      code = moorsim_lines_node_positions(lines, any_int(), buffer, below(2) ? 63 : any_int());
      check(code, function, "drawn line and length", OK | USAGE);
      break;
    case 8:
      function = "moorsim_lines_part";
      code = moorsim_lines_part(lines, any_int(), any_int(), any_int());
      check(code, function, "drawn line, where and node", OK | USAGE | INPUT | SOLVER);
      break;
    case 9: {
      function = "moorsim_lines_save";
      code = moorsim_lines_save(lines, NULL, 0, &size);
      check(code, function, "size", OK | USAGE);
      if (code != MOORSIM_OK) break;
      unsigned char* saved = malloc(size);
      const size_t capacity = below(3) ? size : size / 2;
      code = moorsim_lines_save(lines, saved, capacity, &size);
      check(code, function, "drawn capacity", OK | USAGE);
      if (code == MOORSIM_OK) {
        /* Restored whole, cut short, or with a byte changed. */
        const size_t kept = below(3) ? size : (size_t)below(size + 1);
        if (below(2) && kept > 0) saved[below(kept)] ^= (unsigned char)(1u << below(8));
        code = moorsim_lines_restore(lines, saved, kept);
        check(code, "moorsim_lines_restore", "own state, cut or changed", OK | INPUT);
      }
      free(saved);
      return;
    }
    case 10:
      function = "moorsim_lines_restore";
      code = moorsim_lines_restore(lines, foreign, (size_t)below(foreign_size + 1));
      check(code, function, "the plant's state", INPUT);
      break;
    default:
      function = "moorsim_lines_node_count";
      code = moorsim_lines_node_count(lines, any_int(), below(8) ? &n : NULL);
      check(code, function, "drawn line", OK | USAGE);
      code = moorsim_lines_body_load(lines, f);
      check(code, "moorsim_lines_body_load", "now", OK | USAGE);
      code = moorsim_lines_anchor_tensions(lines, buffer, below(2) ? 4 : any_int());
      check(code, "moorsim_lines_anchor_tensions", "drawn length", OK | USAGE);
      return;
  }
  const double after = lines_time(lines);
  if (code != MOORSIM_OK && !(after == before || (isnan(after) && isnan(before)))) {
    fprintf(stderr, "%s refused (%d) but moved the lines from %g to %g s\n", function, code, before,
            after);
    ++failures;
  }
}

/* One call of the plant's functions. */
static void plant_call(moorsim_plant* plant, const unsigned char* foreign, size_t foreign_size) {
  double v[40], t = 0.0;
  size_t size = 0;
  const double before = plant_time(plant);
  int code = MOORSIM_OK;
  const char* function = "";
  switch (below(8)) {
    case 0:
    case 1:
      /* A little ahead (runs), or a drawn time (mostly refused: behind, NaN, beyond a day). */
      t = below(2) ? before + 0.5 * (double)(1 + below(2)) : any_double();
      if (t > before + 5.0 && t <= before + 86400.0) t = before + 1.0;
      function = "moorsim_plant_advance_to";
      code = moorsim_plant_advance_to(plant, t);
      check(code, function, "drawn time", OK | INPUT | SOLVER);
      break;
    case 2:
      for (int k = 0; k < 3; ++k) v[k] = below(3) ? 1e5 * (double)below(3) : any_double();
      function = "moorsim_plant_set_thrust";
      code = moorsim_plant_set_thrust(plant, below(4) ? v : NULL);
      check(code, function, "drawn thrust", OK | INPUT);
      break;
    case 3:
      for (int k = 0; k < 3; ++k) v[k] = below(3) ? 1e4 * (double)below(3) : any_double();
      function = "moorsim_plant_set_external_load";
      code = moorsim_plant_set_external_load(plant, below(6) ? v : NULL);
      check(code, function, "drawn load", OK | USAGE | INPUT);
      break;
    case 4:
      function = "moorsim_plant_fairlead_tensions";
      code = moorsim_plant_fairlead_tensions(plant, below(6) ? v : NULL, any_int());
      check(code, function, "drawn length", OK | USAGE);
      code = moorsim_plant_measured_tensions(plant, v, below(2) ? 8 : any_int());
      check(code, "moorsim_plant_measured_tensions", "no cells", USAGE | INPUT);
      break;
    case 5:
      function = "moorsim_plant_loads";
      code = moorsim_plant_loads(plant, v, below(2) ? 30 : any_int());
      check(code, function, "drawn length", OK | USAGE);
      check(moorsim_plant_pose(plant, below(6) ? v : NULL), "moorsim_plant_pose", "now",
            OK | USAGE);
      check(moorsim_plant_measured_pose(plant, v), "moorsim_plant_measured_pose", "now", OK);
      check(moorsim_plant_thrust(plant, below(2) ? v : NULL, below(2) ? v + 3 : NULL),
            "moorsim_plant_thrust", "now", OK);
      break;
    case 6: {
      function = "moorsim_plant_save";
      code = moorsim_plant_save(plant, NULL, 0, below(8) ? &size : NULL);
      check(code, function, "size", OK | USAGE);
      if (code != MOORSIM_OK) break;
      unsigned char* saved = malloc(size + 1);
      code = moorsim_plant_save(plant, saved, below(3) ? size : size / 2, &size);
      check(code, function, "drawn capacity", OK | USAGE);
      if (code == MOORSIM_OK) {
        const size_t kept = below(2) ? size : (size_t)below(size + 1);
        if (below(2) && kept > 0) saved[below(kept)] ^= (unsigned char)(1u << below(8));
        code = moorsim_plant_restore(plant, saved, kept);
        check(code, "moorsim_plant_restore", "own state, cut or changed", OK | INPUT | SOLVER);
      }
      free(saved);
      return;
    }
    default:
      function = "moorsim_plant_restore";
      code = moorsim_plant_restore(plant, foreign, (size_t)below(foreign_size + 1));
      check(code, function, "the lines' state", INPUT);
      break;
  }
  const double after = plant_time(plant);
  if (code != MOORSIM_OK && after != before && !(code == MOORSIM_ERROR_SOLVER)) {
    fprintf(stderr, "%s refused (%d) but moved the plant from %g to %g s\n", function, code, before,
            after);
    ++failures;
  }
}

static void count_warning(const char* message, void* user) {
  (void)message;
  ++*(int*)user;
}

int main(int argc, char** argv) {
  if (argc != 2) {
    fprintf(stderr, "usage: c_api_misuse SOURCE_DIR\n");
    return 2;
  }
  int warnings = 0; /* the drawn motions warn often: counted, not printed */
  moorsim_set_warning_handler(count_warning, &warnings);
  null_everything();

  /* Out of order: everything before init. */
  moorsim_lines* lines = moorsim_lines_create_from_yaml(kLines);
  if (lines == NULL) {
    fprintf(stderr, "the lines: %s\n", moorsim_last_error());
    return 1;
  }
  double x[6] = {0}, xd[6] = {0}, f[6], t = 0.0, dt = 0.1, buffer[64];
  size_t size = 0;
  check(moorsim_lines_step(lines, x, xd, f, &t, &dt), "moorsim_lines_step", "before init", USAGE);
  check(moorsim_lines_body_load(lines, f), "moorsim_lines_body_load", "before init", USAGE);
  check(moorsim_lines_save(lines, NULL, 0, &size), "moorsim_lines_save", "before init", USAGE);
  check(moorsim_lines_part(lines, 1, MOORSIM_PART_NODE, 3), "moorsim_lines_part", "before init",
        USAGE);
  check(moorsim_lines_fairlead_tensions(lines, buffer, 4), "moorsim_lines_fairlead_tensions",
        "before init", USAGE);

  /* The plant of the library's seed case, short and coarse. */
  char yaml[4096];
  snprintf(yaml, sizeof yaml,
           "base: %s/scenarios/library/seed_tapm.yaml\n"
           "mooring: {defaults: {segments: 12}}\n"
           "simulation: {duration: 600, output_rate_hz: 2}\n",
           argv[1]);
  moorsim_plant* plant = moorsim_plant_create_from_yaml(yaml, 7);
  if (plant == NULL) {
    fprintf(stderr, "the plant: %s\n", moorsim_last_error());
    return 1;
  }
  /* Each one's state for the other (foreign states). */
  unsigned char plant_state[65536], lines_state[65536];
  size_t plant_size = 0, lines_size = 0;
  check(moorsim_plant_save(plant, plant_state, sizeof plant_state, &plant_size),
        "moorsim_plant_save", "whole", OK);
  check(moorsim_lines_init(lines, x, xd), "moorsim_lines_init", "at rest", OK);
  check(moorsim_lines_save(lines, lines_state, sizeof lines_state, &lines_size),
        "moorsim_lines_save", "whole", OK);

  /* The seeded sequence, now and then a new instance in place of the old. */
  for (int call = 0; call < 300; ++call) {
    if (below(60) == 0) {
      moorsim_lines_destroy(lines);
      lines = moorsim_lines_create_from_yaml(kLines);
      if (lines == NULL) return 1;
    }
    if (below(2)) {
      lines_call(lines, plant_state, plant_size);
    } else {
      plant_call(plant, lines_state, lines_size);
    }
    /* An interrupt asked between calls: the next long call stops before it moves. */
    if (below(40) == 0) {
      moorsim_lines_interrupt(lines);
      moorsim_plant_interrupt(plant);
      double now = lines_time(lines), step = 0.1, load[6];
      int code = moorsim_lines_step(lines, x, xd, load, &now, &step);
      check(code, "moorsim_lines_step", "after an interrupt", USAGE | INTERRUPTED);
      const double before = plant_time(plant);
      code = moorsim_plant_advance_to(plant, before + 1.0);
      check(code, "moorsim_plant_advance_to", "after an interrupt", INTERRUPTED);
      if (plant_time(plant) != before) {
        fprintf(stderr, "an interrupted advance moved the plant\n");
        ++failures;
      }
    }
  }
  moorsim_lines_destroy(lines);
  moorsim_plant_destroy(plant);
  if (failures > 0) {
    fprintf(stderr, "%d broken rules\n", failures);
    return 1;
  }
  printf("every call returned an API code, every refusal with its message (%d warnings)\n",
         warnings);
  return 0;
}
