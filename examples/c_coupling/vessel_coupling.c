/* A vessel integrator of one's own, coupled to moorsim's mooring lines through the C API
 * (include/moorsim/moorsim.h), the way a code that calls MoorDyn couples to it.
 *
 * The vessel is a rigid body that moves in surge and sway (heave, roll, pitch and yaw held:
 * the lines hang from a turret, whose bearing leaves the hull's heading to itself) with its
 * mass and added mass, linear damping, and a steady load (a current or wind force) toward
 * north. It is stepped by semi-implicit Euler at DT; after each step
 * the lines are stepped to the vessel's new pose and velocity and return their load, which
 * drives the next step. The run ends when the vessel has stopped (speed below 1e-4 m/s for
 * a minute) or at the time limit, and prints where it came to rest and the lines' load
 * there, which `moorsim static --offset X,Y,0` gives for the same pose.
 *
 *   vessel_coupling SCENARIO FORCE_N [MAX_TIME_S]
 *
 * Halfway through, the state is saved; at the end it is restored and the first ten seconds
 * after the save are stepped again, and must repeat bit for bit. */
#include <math.h>
#include <moorsim/moorsim.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { kSurge = 0, kSway = 1 };

static int check(int code, const char* call) {
  if (code != MOORSIM_OK) fprintf(stderr, "vessel_coupling: %s: %s\n", call, moorsim_last_error());
  return code;
}

/* The vessel: surge-sway mass (with added mass) [kg] and linear damping near critical for
 * a mooring of about 1e5 N/m [N s/m]. */
typedef struct {
  double mass, damping;
  double x[6], xd[6];
} Vessel;

/* One semi-implicit Euler step under the load f (the lines' force and moment, Earth axes)
 * and the steady force toward north. */
static void vessel_step(Vessel* v, const double* f, double force_north, double dt) {
  const double fx = f[0] + force_north - v->damping * v->xd[kSurge];
  const double fy = f[1] - v->damping * v->xd[kSway];
  v->xd[kSurge] += dt * fx / v->mass;
  v->xd[kSway] += dt * fy / v->mass;
  v->x[kSurge] += dt * v->xd[kSurge];
  v->x[kSway] += dt * v->xd[kSway];
}

/* Steps vessel and lines together for `steps` steps, keeping the surge history. */
static int run(moorsim_lines* lines, Vessel* v, double* f, double force, double dt, int steps,
               double* t, double* history) {
  for (int k = 0; k < steps; ++k) {
    vessel_step(v, f, force, dt);
    double step = dt;
    if (check(moorsim_lines_step(lines, v->x, v->xd, f, t, &step), "step")) return 1;
    if (history) history[k] = v->x[kSurge];
  }
  return 0;
}

int main(int argc, char** argv) {
  if (argc < 3 || argc > 4) {
    fprintf(stderr, "usage: vessel_coupling SCENARIO FORCE_N [MAX_TIME_S]\n");
    return 2;
  }
  const double force = atof(argv[2]);
  const double max_time = argc == 4 ? atof(argv[3]) : 3000.0;
  const double dt = 0.1;
  if (moorsim_api_version() != MOORSIM_API_VERSION) {
    fprintf(stderr, "vessel_coupling: built for API %d, the library is %d\n", MOORSIM_API_VERSION,
            moorsim_api_version());
    return 1;
  }
  moorsim_lines* lines = moorsim_lines_create(argv[1]);
  if (!lines) {
    fprintf(stderr, "vessel_coupling: %s\n", moorsim_last_error());
    return 1;
  }
  int dofs = 0, count = 0;
  moorsim_lines_coupled_dofs(lines, &dofs);
  moorsim_lines_count(lines, &count);
  printf("moorsim %s: %d lines, %d coupled degrees of freedom\n", moorsim_version(), count, dofs);

  Vessel v = {.mass = 2.0e8, .damping = 1.0e7};
  memset(v.x, 0, sizeof v.x);
  memset(v.xd, 0, sizeof v.xd);
  double f[6], t = 0.0;
  if (check(moorsim_lines_init(lines, v.x, v.xd), "init")) return 1;
  if (check(moorsim_lines_body_load(lines, f), "body_load")) return 1;

  /* Half the time limit, then a save, then on until the vessel stops. */
  const int half = (int)(0.5 * max_time / dt);
  if (run(lines, &v, f, force, dt, half, &t, NULL)) return 1;
  size_t size = 0;
  if (check(moorsim_lines_save(lines, NULL, 0, &size), "save")) return 1;
  unsigned char* saved = malloc(size);
  if (check(moorsim_lines_save(lines, saved, size, &size), "save")) return 1;
  const Vessel v_saved = v;
  double f_saved[6];
  memcpy(f_saved, f, sizeof f);
  const double t_saved = t;
  const int repeat = (int)(10.0 / dt);
  double first[100], again[100];
  if (run(lines, &v, f, force, dt, repeat, &t, first)) return 1;

  double still = 0.0;
  while (t < max_time && still < 60.0) {
    if (run(lines, &v, f, force, dt, 1, &t, NULL)) return 1;
    const double speed = hypot(v.xd[kSurge], v.xd[kSway]);
    still = speed < 1e-4 ? still + dt : 0.0;
  }
  double tensions[64];
  if (count > 64 || check(moorsim_lines_fairlead_tensions(lines, tensions, count), "tensions")) {
    return 1;
  }
  printf("at rest: %s after %.1f s\n", still >= 60.0 ? "yes" : "no", t);
  printf("offset: %.6f %.6f\n", v.x[kSurge], v.x[kSway]);
  printf("load: %.3f %.3f\n", f[0], f[1]);
  printf("tensions:");
  for (int i = 0; i < count; ++i) printf(" %.1f", tensions[i]);
  printf("\n");

  /* Back to the saved state: the same ten seconds again. */
  if (check(moorsim_lines_restore(lines, saved, size), "restore")) return 1;
  v = v_saved;
  memcpy(f, f_saved, sizeof f);
  t = t_saved;
  if (run(lines, &v, f, force, dt, repeat, &t, again)) return 1;
  printf("repeat after restore: %s\n",
         memcmp(first, again, sizeof(double) * repeat) == 0 ? "identical" : "DIFFERENT");
  free(saved);
  moorsim_lines_destroy(lines);
  return 0;
}
