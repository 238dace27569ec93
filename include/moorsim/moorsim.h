/* moorsim's C API: the mooring lines of a moorsim scenario as a library that another
 * program's body model steps, with the lifecycle of MoorDyn's C API so that a coupling
 * written for MoorDyn maps one call to one call:
 *
 *   MoorDyn_Create(file)             moorsim_lines_create(file) or _create_from_yaml(text)
 *   MoorDyn_NCoupledDOF(sys, &n)     moorsim_lines_coupled_dofs(lines, &n)        (n = 6)
 *   MoorDyn_Init(sys, x, xd)         moorsim_lines_init(lines, x, xd)
 *   MoorDyn_Step(sys, x, xd, f, &t, &dt)
 *                                    moorsim_lines_step(lines, x, xd, f, &t, &dt)
 *   MoorDyn_GetFairTens, GetLineNodePos, ...
 *                                    moorsim_lines_fairlead_tensions, _node_positions, ...
 *   MoorDyn_Serialize/Deserialize    moorsim_lines_save / moorsim_lines_restore
 *   MoorDyn_Close(sys)               moorsim_lines_destroy(lines)
 *
 * Conventions are moorsim's: SI units, the NED Earth frame (x north, y east, z down), line
 * numbers from 1 as in the scenario. The coupled body is the vessel whose fairleads the
 * scenario gives (mooring.lines[].fairlead, body frame): its six degrees of freedom are its
 * reference point's position north, east, down [m] and its roll, pitch, yaw [rad] (the
 * fairleads carried by Rz(yaw) Ry(pitch) Rx(roll)); their rates are the time derivatives of
 * the same six numbers [m/s, rad/s]. x = 0 puts the reference point where the scenario's
 * anchors are laid out from.
 *
 * Between two calls to step the body follows the cubic Hermite path through the two poses
 * and velocities given, so its velocity is continuous and the lines see no jolt.
 *
 * Errors: every function that can fail returns MOORSIM_OK (0) or an error code, and the
 * calling thread's moorsim_last_error() says what and where; the create functions return
 * NULL. Bad use (a null handle or pointer, an array of the wrong length, a step before
 * init, a saved state of another model or version, NaN) is an error code, never a crash.
 * Instances are independent: several may live side by side, each used from one thread at a
 * time (different instances on different threads at once are fine).
 *
 * MOORSIM_API_VERSION changes whenever a function's signature or meaning changes; a program
 * can compare it with moorsim_api_version() of the library it loaded. */
#ifndef MOORSIM_MOORSIM_H
#define MOORSIM_MOORSIM_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

#define MOORSIM_API_VERSION 2

/* Return codes. */
#define MOORSIM_OK 0
#define MOORSIM_ERROR_USAGE 1       /* null handle or pointer, wrong length, call out of order */
#define MOORSIM_ERROR_INPUT 2       /* a scenario, value or saved state that cannot be used */
#define MOORSIM_ERROR_SOLVER 3      /* the integrator or the static solve failed */
#define MOORSIM_ERROR_INTERNAL 4    /* a defect in moorsim: please report it with the message */
#define MOORSIM_ERROR_INTERRUPTED 5 /* stopped by moorsim_lines_interrupt/_plant_interrupt */

/* Where a line parts (moorsim_lines_part). */
#define MOORSIM_PART_FAIRLEAD 0
#define MOORSIM_PART_NODE 1
#define MOORSIM_PART_ANCHOR 2

/* MOORSIM_API_VERSION as the library was built. */
int moorsim_api_version(void);
/* The library's version ("0.1.0-..."), static storage. */
const char* moorsim_version(void);
/* The calling thread's last error message ("" if none yet), valid until its next call
 * into moorsim. */
const char* moorsim_last_error(void);

/* Warnings: what a call did although it looks wrong (a fairlead far above the water at
 * init, a body moving faster than a moored body can in a step), one sentence each, each
 * kind once per instance. The call still returns MOORSIM_OK. By default they are written to
 * stderr as "moorsim: warning: <function>: <what>"; a program may take them instead with
 * its own handler (NULL: back to the default), called on the thread of the call that
 * warns. The handler is the process's, for every instance: set it before calls run. */
typedef void (*moorsim_warning_handler)(const char* message, void* user);
void moorsim_set_warning_handler(moorsim_warning_handler handler, void* user);

/* Warnings: what a call did although it looks wrong (a fairlead far above the water at
 * init, a body moving faster than a moored body can in a step), one sentence each, each
 * kind once per instance. The call still returns MOORSIM_OK. By default they are written to
 * stderr as "moorsim: warning: <function>: <what>"; a program may take them instead with
 * its own handler (NULL: back to the default), called on the thread of the call that
 * warns. The handler is the process's, for every instance: set it before calls run. */
typedef void (*moorsim_warning_handler)(const char* message, void* user);
void moorsim_set_warning_handler(moorsim_warning_handler handler, void* user);

/* ---- The mooring lines alone ------------------------------------------------------ */

typedef struct moorsim_lines moorsim_lines;

/* The lines of a scenario file (its mooring, environment.current, the waves the lines see
 * and the solver settings), or of a scenario given as YAML text. NULL on error. */
moorsim_lines* moorsim_lines_create(const char* scenario_path);
moorsim_lines* moorsim_lines_create_from_yaml(const char* yaml_text);
/* Frees the instance (NULL is allowed and does nothing). */
void moorsim_lines_destroy(moorsim_lines* lines);

/* The number of coupled degrees of freedom: 6, the body's. */
int moorsim_lines_coupled_dofs(const moorsim_lines* lines, int* count);
/* The number of lines. */
int moorsim_lines_count(const moorsim_lines* lines, int* count);
/* The number of nodes of line `line` (1-based): its segments + 1. */
int moorsim_lines_node_count(const moorsim_lines* lines, int line, int* count);
/* The lines' time [s]. */
int moorsim_lines_time(const moorsim_lines* lines, double* t);

/* Puts the body at x[6] moving at xd[6] at time 0 and the lines at their static
 * equilibrium there. May be called again to start over with every line intact. */
int moorsim_lines_init(moorsim_lines* lines, const double* x, const double* xd);
/* Integrates the lines from *t to *t + *dt with the body arriving at x[6] moving at xd[6],
 * writes their load on the body to f[6] (force [N] and moment about the reference point
 * [N m], Earth axes) and advances *t. *t must be the lines' time (moorsim_lines_time) and
 * *dt from MOORSIM_MIN_STEP (and 1e-12 of *t, below which a step is lost in its rounding)
 * to MOORSIM_MAX_STEP: MOORSIM_ERROR_INPUT otherwise. On a solver error or an interruption
 * the lines stay at the time and state before the call. */
int moorsim_lines_step(moorsim_lines* lines, const double* x, const double* xd, double* f,
                       double* t, double* dt);
#define MOORSIM_MIN_STEP 1e-9    /* [s] */
#define MOORSIM_MAX_STEP 86400.0 /* [s]: a day; step again to go further */
/* Asks a moorsim_lines_step running on `lines` (in another thread, or the thread this is
 * called from a signal handler of) to stop: it returns MOORSIM_ERROR_INTERRUPTED soon after,
 * the lines as they were before it. A request made while no step runs stops the next one
 * before it moves. The one function that may be called from a signal handler or another
 * thread while the instance is in use; it sets no message. MOORSIM_ERROR_USAGE for NULL. */
int moorsim_lines_interrupt(moorsim_lines* lines);
/* The lines' load on the body now, as step writes it. */
int moorsim_lines_body_load(moorsim_lines* lines, double* f);

/* Each line's tension at its upper end (the magnitude of its force on the fairlead or the
 * free point it hangs from) [N]: n must be the number of lines. */
int moorsim_lines_fairlead_tensions(moorsim_lines* lines, double* tensions, int n);
/* Each line's force on what holds its upper end, Earth frame, 3 per line [N]: n must be 3
 * times the number of lines. */
int moorsim_lines_fairlead_forces(moorsim_lines* lines, double* forces, int n);
/* Each line's tension at its anchor (its lowest segment's) [N]: n = number of lines. */
int moorsim_lines_anchor_tensions(moorsim_lines* lines, double* tensions, int n);
/* Line `line`'s segment tensions from the anchor up [N]: n = its node count - 1. */
int moorsim_lines_segment_tensions(moorsim_lines* lines, int line, double* tensions, int n);
/* Line `line`'s node positions, anchor first, x y z per node [m]: n = 3 x its node count. */
int moorsim_lines_node_positions(moorsim_lines* lines, int line, double* xyz, int n);

/* Parts line `line` now: at its fairlead (MOORSIM_PART_FAIRLEAD), at internal node `node`
 * (MOORSIM_PART_NODE, 1 .. node count - 2, counted from the anchor), or its anchor lets go
 * (MOORSIM_PART_ANCHOR); `node` is ignored but for MOORSIM_PART_NODE. */
int moorsim_lines_part(moorsim_lines* lines, int line, int where, int node);

/* Saves the whole state (time, the body's pose and velocity, parted lines, every node) to
 * buffer[capacity] and its size to *size. With buffer NULL, only *size is set. Saving
 * restarts the integrator from the saved state, so stepping on after a save and stepping
 * after a restore of it give the same trajectory bit for bit. */
int moorsim_lines_save(moorsim_lines* lines, void* buffer, size_t capacity, size_t* size);
/* Returns to a saved state. A buffer from another model, another moorsim version, or cut
 * short is MOORSIM_ERROR_INPUT and leaves the instance as it was. */
int moorsim_lines_restore(moorsim_lines* lines, const void* buffer, size_t size);

/* ---- The coupled plant ------------------------------------------------------------ */

/* The whole coupled simulation of a scenario (the vessel on its lines in the scenario's
 * sea, current and wind, its thrusters, sensors and detectors), moved forward by the
 * caller, with the scenario's controller or the caller's thrust command. Advanced through
 * the output instants of a scenario with its controller, it gives `moorsim run`'s rows
 * bit for bit. Readings are at the plant's current time; poses are the reference point's
 * x, y, z [m] (NED) and roll, pitch, yaw [rad]. */
typedef struct moorsim_plant moorsim_plant;

/* The plant of a scenario file or YAML text for run seed `seed` (`moorsim run` uses the
 * scenario's simulation.seed), at its moored static start. NULL on error. */
moorsim_plant* moorsim_plant_create(const char* scenario_path, unsigned long long seed);
moorsim_plant* moorsim_plant_create_from_yaml(const char* yaml_text, unsigned long long seed);
void moorsim_plant_destroy(moorsim_plant* plant);

int moorsim_plant_line_count(const moorsim_plant* plant, int* count);
int moorsim_plant_time(const moorsim_plant* plant, double* t);
/* Integrates to time t [s] (not behind the plant's; its own time does nothing; at most
 * MOORSIM_MAX_ADVANCE ahead of it, MOORSIM_ERROR_INPUT otherwise), acting on every sensor
 * sample, controller instant and scheduled failure on the way. */
int moorsim_plant_advance_to(moorsim_plant* plant, double t);
#define MOORSIM_MAX_ADVANCE 86400.0 /* [s]: a day; advance again to go further */
/* Asks a moorsim_plant_advance_to or moorsim_plant_restore running on `plant` (in another
 * thread, or from a signal handler) to stop at the plant's next sensor sample, controller
 * instant or failure: it returns MOORSIM_ERROR_INTERRUPTED with the plant there (as if it
 * had been asked to advance to that time; an interrupted restore that would have rebuilt
 * the plant leaves it as it was). A request made while no call runs stops the next one
 * before it moves. Safe from a signal handler or another thread; it sets no message.
 * MOORSIM_ERROR_USAGE for NULL. */
int moorsim_plant_interrupt(moorsim_plant* plant);
/* From now on, the thrust command X, Y [N], N [N m] (body frame, command[3]) at every
 * controller instant instead of the controller's; NULL gives it back to the controller.
 * The allocation and the thrusters' dynamics act on it as on the controller's. */
int moorsim_plant_set_thrust(moorsim_plant* plant, const double* command);
/* A steady load on the hull from now on: X north, Y east [N], moment about z [N m]. */
int moorsim_plant_set_external_load(moorsim_plant* plant, const double* load);
/* The true pose (low- plus wave-frequency), pose[6]. */
int moorsim_plant_pose(moorsim_plant* plant, double* pose);
/* The latest measurement x, y, heading, pose[3] (NaN until a channel has delivered). */
int moorsim_plant_measured_pose(moorsim_plant* plant, double* pose);
/* Each line's fairlead tension [N]: n = number of lines. */
int moorsim_plant_fairlead_tensions(moorsim_plant* plant, double* tensions, int n);
/* The load cells' latest readings [N]: n = number of lines (an error without cells). */
int moorsim_plant_measured_tensions(moorsim_plant* plant, double* tensions, int n);
/* The thrust the controller (or the caller) commanded and the thrusters deliver, X, Y, N
 * (body frame), commanded[3] and delivered[3]; either may be NULL. */
int moorsim_plant_thrust(moorsim_plant* plant, double* commanded, double* delivered);
/* The loads on the hull about its origin, body frame, 6 each in this order: mooring, wave
 * drift, current, wind, thrust (X, Y, Z [N], K, M, N [N m]); n must be 30. */
int moorsim_plant_loads(moorsim_plant* plant, double* loads, int n);

/* Saves the plant's state (its inputs since it was created: every advance, thrust command
 * and load, in order) to buffer[capacity], its size to *size; buffer NULL gives the size.
 * Restoring rebuilds the plant and repeats them: the plant is the saved one bit for bit,
 * at the cost of its simulated time run again (less when the saved state continues the
 * current one). A state of another scenario, seed or version is MOORSIM_ERROR_INPUT. */
int moorsim_plant_save(const moorsim_plant* plant, void* buffer, size_t capacity, size_t* size);
int moorsim_plant_restore(moorsim_plant* plant, const void* buffer, size_t size);

#ifdef __cplusplus
}
#endif

#endif /* MOORSIM_MOORSIM_H */
