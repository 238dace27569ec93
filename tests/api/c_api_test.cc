// The C API of include/moorsim/moorsim.h, called as a C program calls it: the lines stepped
// through it along a prescribed motion against LineSimulation on the same motion; the
// body load against the fairlead forces it sums; save and restore repeating a trajectory
// bit for bit (across instances and topologies); instances on two threads at once; and
// every kind of misuse an error code with a message, never a crash (run under the
// sanitizers too).
#include "moorsim/moorsim.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <string>
#include <thread>
#include <vector>

#include "mooring_fem/line_simulation.h"
#include "runner/run.h"
#include "scenarios/convert.h"
#include "scenarios/load.h"

namespace {

// Four chains at 90 deg spacing in 150 m of water, 20 segments each: small enough for the
// sanitizer build, slack enough that the seabed, the catenary and the pretension all work.
std::string Mooring(int segments = 20, double length = 640.0, std::string solver = "") {
  std::string lines;
  const double anchor = 600.0, fairlead = 10.0;
  const int sign_x[] = {1, 0, -1, 0}, sign_y[] = {0, 1, 0, -1};
  for (int i = 0; i < 4; ++i) {
    lines += "    - {id: " + std::to_string(i + 1) + ", type: chain, anchor: [" +
             std::to_string(anchor * sign_x[i]) + ", " + std::to_string(anchor * sign_y[i]) +
             ", 150], fairlead: [" + std::to_string(fairlead * sign_x[i]) + ", " +
             std::to_string(fairlead * sign_y[i]) + ", 5], length: " + std::to_string(length) +
             ", segments: " + std::to_string(segments) + "}\n";
  }
  return "mooring:\n"
         "  water: {density: 1025, gravity: 9.81, depth: 150}\n"
         "  seabed: {stiffness: 3.0e6, damping: 3.0e5}\n"
         "  line_types:\n"
         "    - {name: chain, diameter: 0.08, mass_per_length: 140, axial_stiffness: 6.0e8,\n"
         "       axial_damping_ratio: 0.5, drag_normal: 1.2, drag_tangential: 0.4,\n"
         "       added_mass_normal: 1.0}\n"
         "  lines:\n" +
         lines + solver;
}

// A handle that is destroyed at the end of the scope.
struct Lines {
  explicit Lines(const std::string& yaml) : handle(moorsim_lines_create_from_yaml(yaml.c_str())) {
    EXPECT_NE(handle, nullptr) << moorsim_last_error();
  }
  ~Lines() { moorsim_lines_destroy(handle); }
  Lines(const Lines&) = delete;
  Lines& operator=(const Lines&) = delete;
  moorsim_lines* handle;
};

// The motion of the comparisons: surge, heave and yaw harmonics (the yaw turns every
// fairlead), its six values and rates at t.
struct Motion {
  static constexpr double kSurge = 6.0, kSurgePeriod = 40.0;
  static constexpr double kHeave = 1.5, kHeavePeriod = 9.0;
  static constexpr double kYaw = 0.08, kYawPeriod = 60.0;
  static void At(double t, double* x, double* xd) {
    const double ws = 2 * M_PI / kSurgePeriod, wh = 2 * M_PI / kHeavePeriod,
                 wy = 2 * M_PI / kYawPeriod;
    for (int d = 0; d < 6; ++d) x[d] = xd[d] = 0.0;
    x[0] = kSurge * std::sin(ws * t);
    xd[0] = kSurge * ws * std::cos(ws * t);
    x[2] = kHeave * std::sin(wh * t);
    xd[2] = kHeave * wh * std::cos(wh * t);
    x[5] = kYaw * std::sin(wy * t);
    xd[5] = kYaw * wy * std::cos(wy * t);
  }
  static moorsim::mooring_fem::PrescribedMotion Prescribed() {
    using moorsim::mooring_fem::PrescribedMotion;
    PrescribedMotion m;
    m.components[PrescribedMotion::kSurge] = {{kSurge, kSurgePeriod}};
    m.components[PrescribedMotion::kHeave] = {{kHeave, kHeavePeriod}};
    m.components[PrescribedMotion::kYaw] = {{kYaw, kYawPeriod}};
    return m;
  }
};

// Steps `lines` along the motion from its current time to `until` in steps of dt and
// returns the fairlead tensions after each step, all lines in a row.
std::vector<double> StepAlong(moorsim_lines* lines, double until, double dt) {
  std::vector<double> tensions;
  int count = 0;
  EXPECT_EQ(moorsim_lines_count(lines, &count), MOORSIM_OK);
  double t = 0.0;
  EXPECT_EQ(moorsim_lines_time(lines, &t), MOORSIM_OK);
  double x[6], xd[6], f[6];
  std::vector<double> row(count);
  while (t < until - 1e-9) {
    double step = dt;
    Motion::At(t + step, x, xd);
    if (moorsim_lines_step(lines, x, xd, f, &t, &step) != MOORSIM_OK) {
      ADD_FAILURE() << moorsim_last_error();
      break;
    }
    EXPECT_EQ(moorsim_lines_fairlead_tensions(lines, row.data(), count), MOORSIM_OK);
    tensions.insert(tensions.end(), row.begin(), row.end());
  }
  return tensions;
}

void InitAtRest(moorsim_lines* lines) {
  double x[6], xd[6];
  Motion::At(0.0, x, xd);
  ASSERT_EQ(moorsim_lines_init(lines, x, xd), MOORSIM_OK) << moorsim_last_error();
}

// The largest tension [N] and the largest difference [N] between the fairlead tensions of
// the lines stepped through the C API every 0.1 s and LineSimulation on the same motion,
// over 60 s, compared every second; with `solver` (a YAML solver section) for both.
std::pair<double, double> LargestDifferenceFromLineSimulation(const std::string& solver) {
  const std::string yaml = Mooring(20, 640.0, solver);
  const auto scenario = moorsim::scenarios::ParseScenario(yaml, "test");
  moorsim::mooring_fem::LineSimulation reference(
      moorsim::scenarios::ToMooringParameters(scenario.mooring), scenario.solver,
      Motion::Prescribed());
  Lines lines(yaml);
  InitAtRest(lines.handle);
  const double dt = 0.1;
  double t = 0.0, x[6], xd[6], f[6];
  double largest = 0.0, worst = 0.0;
  for (int k = 1; k <= 600; ++k) {
    double step = dt;
    Motion::At(k * dt, x, xd);
    if (moorsim_lines_step(lines.handle, x, xd, f, &t, &step) != MOORSIM_OK) {
      ADD_FAILURE() << moorsim_last_error();
      break;
    }
    if (k % 10 != 0) continue;
    reference.AdvanceTo(t);
    const std::vector<moorsim::Vec3> expected = reference.FairleadForces();
    double tensions[4];
    EXPECT_EQ(moorsim_lines_fairlead_tensions(lines.handle, tensions, 4), MOORSIM_OK);
    for (int i = 0; i < 4; ++i) {
      largest = std::max(largest, expected[i].norm());
      worst = std::max(worst, std::abs(tensions[i] - expected[i].norm()));
    }
  }
  EXPECT_NEAR(t, 60.0, 1e-9);
  return {largest, worst};
}

TEST(CApi, StepsGiveTheTensionsOfTheLinesOnThePrescribedMotion) {
  // The same lines on the same motion through LineSimulation (the motion's harmonics
  // exactly) and through the C API (a cubic Hermite path through the motion every 0.1 s,
  // whose error, h^4 |q''''| / 384, is below 1e-7 m here). They differ by the integrators'
  // error, as CVODE takes other steps when it must stop every 0.1 s: a fairlead position
  // error within atol_position (1 mm) is up to EA / l0 x 1 mm = 19 kN of tension in these
  // 32 m segments. Measured: 6.9 kN at the default tolerances (1.1 % of the largest
  // tension), 0.36 kN with tolerances 100 times smaller.
  const auto [largest, loose] = LargestDifferenceFromLineSimulation("");
  EXPECT_LT(loose, 0.02 * largest);
  const auto [largest_tight, tight] = LargestDifferenceFromLineSimulation(
      "solver: {rtol: 1.0e-6, atol_position: 1.0e-5, atol_velocity: 1.0e-5}\n");
  EXPECT_LT(tight, 1e-3 * largest_tight);
  EXPECT_LT(tight, loose / 5.0) << "the difference does not shrink with the tolerances";
}

TEST(CApi, TheBodyLoadIsTheFairleadForcesAndTheirMomentsAboutTheReferencePoint) {
  Lines lines(Mooring());
  InitAtRest(lines.handle);
  StepAlong(lines.handle, 7.3, 0.1);  // surged, heaved and yawed
  double t = 0.0, x[6], xd[6], f[6], forces[12], nodes[3 * 21];
  ASSERT_EQ(moorsim_lines_time(lines.handle, &t), MOORSIM_OK);
  Motion::At(t, x, xd);
  ASSERT_EQ(moorsim_lines_body_load(lines.handle, f), MOORSIM_OK);
  ASSERT_EQ(moorsim_lines_fairlead_forces(lines.handle, forces, 12), MOORSIM_OK);
  moorsim::Vec3 force = moorsim::Vec3::Zero(), moment = moorsim::Vec3::Zero();
  const moorsim::Vec3 reference(x[0], x[1], x[2]);
  for (int i = 0; i < 4; ++i) {
    // The fairlead is the line's top node.
    ASSERT_EQ(moorsim_lines_node_positions(lines.handle, i + 1, nodes, 3 * 21), MOORSIM_OK);
    const moorsim::Vec3 fairlead(nodes[60], nodes[61], nodes[62]);
    const moorsim::Vec3 fi(forces[3 * i], forces[3 * i + 1], forces[3 * i + 2]);
    force += fi;
    moment += (fairlead - reference).cross(fi);
    // The body-frame fairlead (10 m out, 5 m down) carried by the yaw and the heave.
    const double c = std::cos(x[5]), s = std::sin(x[5]);
    const double bx[] = {10, 0, -10, 0}, by[] = {0, 10, 0, -10};
    EXPECT_NEAR(fairlead.x(), x[0] + c * bx[i] - s * by[i], 1e-9);
    EXPECT_NEAR(fairlead.y(), x[1] + s * bx[i] + c * by[i], 1e-9);
    EXPECT_NEAR(fairlead.z(), x[2] + 5.0, 1e-9);
  }
  for (int m = 0; m < 3; ++m) {
    EXPECT_NEAR(f[m], force(m), 1e-9 * force.norm());
    EXPECT_NEAR(f[3 + m], moment(m), 1e-9 * moment.norm() + 1e-6);
  }
  // The chains pull the fairleads down and outward: the net vertical load is downward.
  EXPECT_GT(f[2], 0.0);
  // The anchors hold less than the fairleads (the weight of the hanging chain between).
  double fairlead_tension[4], anchor_tension[4], segments[20];
  ASSERT_EQ(moorsim_lines_fairlead_tensions(lines.handle, fairlead_tension, 4), MOORSIM_OK);
  ASSERT_EQ(moorsim_lines_anchor_tensions(lines.handle, anchor_tension, 4), MOORSIM_OK);
  ASSERT_EQ(moorsim_lines_segment_tensions(lines.handle, 1, segments, 20), MOORSIM_OK);
  EXPECT_EQ(anchor_tension[0], segments[0]);
  for (int i = 0; i < 4; ++i) EXPECT_LT(anchor_tension[i], fairlead_tension[i]);
}

TEST(CApi, RestoringASavedStateRepeatsTheTrajectoryBitForBit) {
  Lines lines(Mooring());
  InitAtRest(lines.handle);
  StepAlong(lines.handle, 5.0, 0.1);
  std::size_t size = 0;
  ASSERT_EQ(moorsim_lines_save(lines.handle, nullptr, 0, &size), MOORSIM_OK);
  std::vector<unsigned char> saved(size);
  std::size_t written = 0;
  ASSERT_EQ(moorsim_lines_save(lines.handle, saved.data(), saved.size(), &written), MOORSIM_OK);
  EXPECT_EQ(written, size);
  const std::vector<double> first = StepAlong(lines.handle, 15.0, 0.1);
  // Back to the save, in this instance and in a new one of the same model.
  ASSERT_EQ(moorsim_lines_restore(lines.handle, saved.data(), saved.size()), MOORSIM_OK);
  EXPECT_EQ(StepAlong(lines.handle, 15.0, 0.1), first);
  Lines other(Mooring());
  ASSERT_EQ(moorsim_lines_restore(other.handle, saved.data(), saved.size()), MOORSIM_OK);
  EXPECT_EQ(StepAlong(other.handle, 15.0, 0.1), first);
  // A parted line is part of the state: restored into an intact instance, and an intact
  // state restored into a parted one.
  ASSERT_EQ(moorsim_lines_part(lines.handle, 2, MOORSIM_PART_NODE, 7), MOORSIM_OK);
  std::vector<double> after_part = StepAlong(lines.handle, 16.0, 0.1);
  ASSERT_EQ(moorsim_lines_save(lines.handle, nullptr, 0, &size), MOORSIM_OK);
  std::vector<unsigned char> parted(size);
  ASSERT_EQ(moorsim_lines_save(lines.handle, parted.data(), parted.size(), &size), MOORSIM_OK);
  EXPECT_GT(parted.size(), saved.size());  // the split node's two copies
  const std::vector<double> parted_on = StepAlong(lines.handle, 20.0, 0.1);
  Lines fresh(Mooring());
  ASSERT_EQ(moorsim_lines_restore(fresh.handle, parted.data(), parted.size()), MOORSIM_OK);
  EXPECT_EQ(StepAlong(fresh.handle, 20.0, 0.1), parted_on);
  ASSERT_EQ(moorsim_lines_restore(fresh.handle, saved.data(), saved.size()), MOORSIM_OK);
  EXPECT_EQ(StepAlong(fresh.handle, 15.0, 0.1), first);
  // Line 2, parted at node 7, no longer holds at its anchor.
  double tensions[4];
  ASSERT_EQ(moorsim_lines_restore(fresh.handle, parted.data(), parted.size()), MOORSIM_OK);
  ASSERT_EQ(moorsim_lines_anchor_tensions(fresh.handle, tensions, 4), MOORSIM_OK);
  EXPECT_LT(tensions[1], 0.2 * tensions[3]);
}

TEST(CApi, InstancesOnTwoThreadsGiveWhatEachGivesAlone) {
  const std::vector<double> alone = [] {
    Lines lines(Mooring());
    InitAtRest(lines.handle);
    return StepAlong(lines.handle, 10.0, 0.1);
  }();
  std::vector<double> a, b;
  auto work = [](std::vector<double>* out) {
    Lines lines(Mooring());
    InitAtRest(lines.handle);
    *out = StepAlong(lines.handle, 10.0, 0.1);
  };
  std::thread one(work, &a), two(work, &b);
  one.join();
  two.join();
  EXPECT_EQ(a, alone);
  EXPECT_EQ(b, alone);
}

// The call returns `code` and the thread's message mentions `words`.
#define EXPECT_REFUSED(call, code, words)                                            \
  do {                                                                               \
    EXPECT_EQ((call), (code)) << #call;                                              \
    EXPECT_NE(std::string(moorsim_last_error()).find(words), std::string::npos)      \
        << #call << ": '" << moorsim_last_error() << "' does not mention " << words; \
  } while (0)

TEST(CApi, MisuseIsAnErrorCodeWithAMessageNeverACrash) {
  double x[6] = {0}, xd[6] = {0}, f[6], t = 0.0, dt = 0.1, buffer[100];
  int count = 0;
  std::size_t size = 0;
  // Null handles.
  EXPECT_REFUSED(moorsim_lines_count(nullptr, &count), MOORSIM_ERROR_USAGE, "handle is NULL");
  EXPECT_REFUSED(moorsim_lines_init(nullptr, x, xd), MOORSIM_ERROR_USAGE, "handle is NULL");
  EXPECT_REFUSED(moorsim_lines_step(nullptr, x, xd, f, &t, &dt), MOORSIM_ERROR_USAGE,
                 "handle is NULL");
  EXPECT_REFUSED(moorsim_lines_save(nullptr, nullptr, 0, &size), MOORSIM_ERROR_USAGE,
                 "handle is NULL");
  EXPECT_REFUSED(moorsim_lines_restore(nullptr, buffer, 8), MOORSIM_ERROR_USAGE, "handle is NULL");
  moorsim_lines_destroy(nullptr);
  // Scenarios that cannot be read.
  EXPECT_EQ(moorsim_lines_create("/nonexistent/scenario.yaml"), nullptr);
  EXPECT_NE(std::string(moorsim_last_error()).find("/nonexistent/scenario.yaml"), std::string::npos)
      << moorsim_last_error();
  EXPECT_EQ(moorsim_lines_create(nullptr), nullptr);
  EXPECT_EQ(moorsim_lines_create_from_yaml("mooring: {lines: [}"), nullptr);
  EXPECT_NE(std::string(moorsim_last_error()).find("<yaml text>"), std::string::npos)
      << moorsim_last_error();
  EXPECT_EQ(moorsim_lines_create_from_yaml(nullptr), nullptr);

  Lines lines(Mooring());
  moorsim_lines* h = lines.handle;
  // Before init.
  EXPECT_REFUSED(moorsim_lines_step(h, x, xd, f, &t, &dt), MOORSIM_ERROR_USAGE, "not initialised");
  EXPECT_REFUSED(moorsim_lines_fairlead_tensions(h, buffer, 4), MOORSIM_ERROR_USAGE,
                 "not initialised");
  EXPECT_REFUSED(moorsim_lines_save(h, nullptr, 0, &size), MOORSIM_ERROR_USAGE, "not initialised");
  EXPECT_REFUSED(moorsim_lines_part(h, 1, MOORSIM_PART_FAIRLEAD, 0), MOORSIM_ERROR_USAGE,
                 "not initialised");
  // Null arrays and NaN.
  EXPECT_REFUSED(moorsim_lines_init(h, nullptr, xd), MOORSIM_ERROR_USAGE, "x is NULL");
  double nan_pose[6] = {0, 0, std::nan(""), 0, 0, 0};
  EXPECT_REFUSED(moorsim_lines_init(h, nan_pose, xd), MOORSIM_ERROR_INPUT, "down");
  ASSERT_EQ(moorsim_lines_init(h, x, xd), MOORSIM_OK) << moorsim_last_error();
  EXPECT_REFUSED(moorsim_lines_step(h, nan_pose, xd, f, &t, &dt), MOORSIM_ERROR_INPUT,
                 "not a finite number");
  EXPECT_REFUSED(moorsim_lines_step(h, x, xd, nullptr, &t, &dt), MOORSIM_ERROR_USAGE, "f is NULL");
  double zero = 0.0, negative = -0.1, infinite = INFINITY;
  EXPECT_REFUSED(moorsim_lines_step(h, x, xd, f, &t, &zero), MOORSIM_ERROR_INPUT,
                 "must be a number from 1e-09 to 86400 s");
  EXPECT_REFUSED(moorsim_lines_step(h, x, xd, f, &t, &negative), MOORSIM_ERROR_INPUT,
                 "must be a number from 1e-09 to 86400 s");
  EXPECT_REFUSED(moorsim_lines_step(h, x, xd, f, &t, &infinite), MOORSIM_ERROR_INPUT,
                 "must be a number from 1e-09 to 86400 s");
  double tiny = 5e-324, day_and_more = 86400.5;
  EXPECT_REFUSED(moorsim_lines_step(h, x, xd, f, &t, &tiny), MOORSIM_ERROR_INPUT,
                 "time step 5e-324 s must be a number from 1e-09 to 86400 s");
  EXPECT_REFUSED(moorsim_lines_step(h, x, xd, f, &t, &day_and_more), MOORSIM_ERROR_INPUT,
                 "(step again to go further)");
  double elsewhere = 3.0;
  EXPECT_REFUSED(moorsim_lines_step(h, x, xd, f, &elsewhere, &dt), MOORSIM_ERROR_USAGE,
                 "the lines are at 0");
  // Wrong lengths and lines.
  EXPECT_REFUSED(moorsim_lines_fairlead_tensions(h, buffer, 3), MOORSIM_ERROR_USAGE,
                 "length 3, expected 4");
  EXPECT_REFUSED(moorsim_lines_fairlead_forces(h, buffer, 4), MOORSIM_ERROR_USAGE, "expected 12");
  EXPECT_REFUSED(moorsim_lines_node_positions(h, 1, buffer, 60), MOORSIM_ERROR_USAGE,
                 "expected 63");
  EXPECT_REFUSED(moorsim_lines_segment_tensions(h, 5, buffer, 20), MOORSIM_ERROR_USAGE,
                 "line 5 is not one of the lines 1..4");
  EXPECT_REFUSED(moorsim_lines_node_count(h, 0, &count), MOORSIM_ERROR_USAGE,
                 "line 0 is not one of");
  EXPECT_REFUSED(moorsim_lines_part(h, 1, 7, 0), MOORSIM_ERROR_USAGE, "where = 7");
  EXPECT_REFUSED(moorsim_lines_part(h, 1, MOORSIM_PART_NODE, 20), MOORSIM_ERROR_USAGE,
                 "node 20 is not an internal node of line 1 (1..19)");
  ASSERT_EQ(moorsim_lines_part(h, 1, MOORSIM_PART_FAIRLEAD, 0), MOORSIM_OK);
  EXPECT_REFUSED(moorsim_lines_part(h, 1, MOORSIM_PART_FAIRLEAD, 0), MOORSIM_ERROR_INPUT,
                 "already detached");
  // Saved states that do not fit.
  ASSERT_EQ(moorsim_lines_save(h, nullptr, 0, &size), MOORSIM_OK);
  std::vector<unsigned char> saved(size);
  EXPECT_REFUSED(moorsim_lines_save(h, saved.data(), size - 1, &size), MOORSIM_ERROR_USAGE,
                 "the state needs");
  ASSERT_EQ(moorsim_lines_save(h, saved.data(), saved.size(), &size), MOORSIM_OK);
  Lines other(Mooring(21));
  EXPECT_REFUSED(moorsim_lines_restore(other.handle, saved.data(), saved.size()),
                 MOORSIM_ERROR_INPUT, "another model");
  EXPECT_REFUSED(moorsim_lines_restore(h, saved.data(), saved.size() - 8), MOORSIM_ERROR_INPUT,
                 "damaged");
  EXPECT_REFUSED(moorsim_lines_restore(h, saved.data(), 20), MOORSIM_ERROR_INPUT, "cut short");
  std::vector<unsigned char> garbage(saved.size(), 0x5a);
  EXPECT_REFUSED(moorsim_lines_restore(h, garbage.data(), garbage.size()), MOORSIM_ERROR_INPUT,
                 "not a moorsim lines state");
  std::vector<unsigned char> other_version = saved;
  other_version[24] ^= 0x01;  // a character of the version string
  EXPECT_REFUSED(moorsim_lines_restore(h, other_version.data(), other_version.size()),
                 MOORSIM_ERROR_INPUT, "saved by moorsim");
  // After all that, the instance still steps.
  EXPECT_EQ(moorsim_lines_step(h, x, xd, f, &t, &dt), MOORSIM_OK) << moorsim_last_error();
  EXPECT_STREQ(moorsim_last_error(), "");
}

TEST(CApi, TheVersionsAreTheHeaders) {
  EXPECT_EQ(moorsim_api_version(), MOORSIM_API_VERSION);
  EXPECT_EQ(std::string(moorsim_version()).rfind("0.", 0), 0u) << moorsim_version();
}

// The seed case's plant (no detectors), 12 segments a line, for 30 s.
std::string SeedPlant() {
  return "base: " MOORSIM_SOURCE_DIR
         "/scenarios/library/seed_tapm.yaml\n"
         "mooring: {defaults: {segments: 12}}\n"
         "simulation: {duration: 30, output_rate_hz: 2}\n";
}

struct Plant {
  explicit Plant(const std::string& yaml, unsigned long long seed = 7)
      : handle(moorsim_plant_create_from_yaml(yaml.c_str(), seed)) {
    EXPECT_NE(handle, nullptr) << moorsim_last_error();
  }
  ~Plant() { moorsim_plant_destroy(handle); }
  Plant(const Plant&) = delete;
  Plant& operator=(const Plant&) = delete;
  moorsim_plant* handle;
};

// The plant's pose and fairlead tensions, all in a row.
std::vector<double> PlantReadings(moorsim_plant* plant) {
  std::vector<double> r(6 + 8);
  EXPECT_EQ(moorsim_plant_pose(plant, r.data()), MOORSIM_OK) << moorsim_last_error();
  EXPECT_EQ(moorsim_plant_fairlead_tensions(plant, r.data() + 6, 8), MOORSIM_OK);
  return r;
}

TEST(CApiPlant, AdvancedThroughTheOutputInstantsWithItsControllerItGivesTheRunsRows) {
  const std::string yaml = SeedPlant();
  moorsim::runner::RunRequest request;
  auto scenario = std::make_shared<moorsim::scenarios::Scenario>(
      moorsim::scenarios::ParseScenario(yaml, "<yaml text>"));
  scenario->simulation.seed = 7;
  request.scenario = scenario;
  request.write_files = false;
  std::vector<moorsim::simulation::Sample> rows;
  request.on_row = [&rows](const moorsim::simulation::Sample& s) { rows.push_back(s); };
  const moorsim::runner::RunResult result = moorsim::runner::RunScenario(request);
  ASSERT_EQ(result.status, moorsim::runner::RunStatus::kOk) << result.message;
  ASSERT_EQ(rows.size(), 61u);

  Plant plant(yaml, 7);
  for (const auto& row : rows) {
    ASSERT_EQ(moorsim_plant_advance_to(plant.handle, row.time), MOORSIM_OK);
    const std::vector<double> r = PlantReadings(plant.handle);
    for (int d = 0; d < 6; ++d) ASSERT_EQ(r[d], row.pose_true(d)) << "t " << row.time;
    for (int i = 0; i < 8; ++i) ASSERT_EQ(r[6 + i], row.fairlead_tension[i]) << "t " << row.time;
    double measured[3];
    ASSERT_EQ(moorsim_plant_measured_pose(plant.handle, measured), MOORSIM_OK);
    for (int c = 0; c < 3; ++c) {
      if (std::isnan(row.pose_measured(c))) {
        EXPECT_TRUE(std::isnan(measured[c]));
      } else {
        EXPECT_EQ(measured[c], row.pose_measured(c));
      }
    }
  }
}

TEST(CApiPlant, TheCallersThrustPushesTheVesselAndARestoredPlantRepeatsBitForBit) {
  Plant plant(SeedPlant());
  ASSERT_EQ(moorsim_plant_advance_to(plant.handle, 5.0), MOORSIM_OK) << moorsim_last_error();
  const double push[3] = {1.5e6, 0.0, 0.0};  // body frame, forward
  ASSERT_EQ(moorsim_plant_set_thrust(plant.handle, push), MOORSIM_OK);
  ASSERT_EQ(moorsim_plant_advance_to(plant.handle, 10.0), MOORSIM_OK);
  double commanded[3], delivered[3], loads[30];
  ASSERT_EQ(moorsim_plant_thrust(plant.handle, commanded, delivered), MOORSIM_OK);
  EXPECT_EQ(commanded[0], 1.5e6);
  EXPECT_GT(delivered[0], 0.0);
  ASSERT_EQ(moorsim_plant_loads(plant.handle, loads, 30), MOORSIM_OK);
  EXPECT_EQ(loads[24], delivered[0]);  // the thrust's load, X
  std::size_t size = 0;
  ASSERT_EQ(moorsim_plant_save(plant.handle, nullptr, 0, &size), MOORSIM_OK);
  std::vector<unsigned char> saved(size);
  ASSERT_EQ(moorsim_plant_save(plant.handle, saved.data(), size, &size), MOORSIM_OK);
  ASSERT_EQ(moorsim_plant_advance_to(plant.handle, 20.0), MOORSIM_OK);
  const std::vector<double> on = PlantReadings(plant.handle);

  // A new plant repeats the saved inputs; this one, which went past them, is rebuilt.
  Plant fresh(SeedPlant());
  ASSERT_EQ(moorsim_plant_restore(fresh.handle, saved.data(), size), MOORSIM_OK);
  ASSERT_EQ(moorsim_plant_restore(plant.handle, saved.data(), size), MOORSIM_OK);
  for (moorsim_plant* p : {fresh.handle, plant.handle}) {
    double t = 0.0;
    ASSERT_EQ(moorsim_plant_time(p, &t), MOORSIM_OK);
    EXPECT_EQ(t, 10.0);
    ASSERT_EQ(moorsim_plant_advance_to(p, 20.0), MOORSIM_OK);
    EXPECT_EQ(PlantReadings(p), on);
  }
  // Without the push (the controller throughout), the vessel is elsewhere.
  Plant held(SeedPlant());
  ASSERT_EQ(moorsim_plant_advance_to(held.handle, 20.0), MOORSIM_OK);
  const std::vector<double> still = PlantReadings(held.handle);
  const double heading = on[5];
  EXPECT_GT((on[0] - still[0]) * std::cos(heading) + (on[1] - still[1]) * std::sin(heading), 0.05);
}

TEST(CApiPlant, MisuseIsAnErrorCodeWithAMessage) {
  double values[30];
  std::size_t size = 0;
  EXPECT_REFUSED(moorsim_plant_advance_to(nullptr, 1.0), MOORSIM_ERROR_USAGE, "handle is NULL");
  EXPECT_REFUSED(moorsim_plant_save(nullptr, nullptr, 0, &size), MOORSIM_ERROR_USAGE,
                 "handle is NULL");
  EXPECT_EQ(moorsim_plant_create("/nonexistent/plant.yaml", 1), nullptr);
  EXPECT_NE(std::string(moorsim_last_error()).find("/nonexistent/plant.yaml"), std::string::npos);
  EXPECT_EQ(moorsim_plant_create_from_yaml(Mooring().c_str(), 1), nullptr);  // no vessel
  EXPECT_NE(std::string(moorsim_last_error()).find("vessel"), std::string::npos)
      << moorsim_last_error();
  Plant plant(SeedPlant());
  EXPECT_REFUSED(moorsim_plant_advance_to(plant.handle, -1.0), MOORSIM_ERROR_INPUT, "behind");
  EXPECT_REFUSED(moorsim_plant_advance_to(plant.handle, 1e300), MOORSIM_ERROR_INPUT,
                 "one advance spans at most 86400 s (advance again to go further)");
  EXPECT_REFUSED(moorsim_plant_advance_to(plant.handle, 1e8), MOORSIM_ERROR_INPUT,
                 "time 1e+08 s lies 1e+08 s ahead of the plant's 0 s");
  {
    Plant later(SeedPlant());
    ASSERT_EQ(moorsim_plant_advance_to(later.handle, 3.0), MOORSIM_OK);
    EXPECT_REFUSED(moorsim_plant_advance_to(later.handle, std::nextafter(3.0, 0.0)),
                   MOORSIM_ERROR_INPUT, "time 2.9999999999999996 s is behind the plant's 3 s");
  }
  EXPECT_REFUSED(moorsim_plant_advance_to(plant.handle, NAN), MOORSIM_ERROR_INPUT, "not a number");
  const double bad[3] = {NAN, 0, 0};
  EXPECT_REFUSED(moorsim_plant_set_thrust(plant.handle, bad), MOORSIM_ERROR_INPUT, "not finite");
  EXPECT_REFUSED(moorsim_plant_set_external_load(plant.handle, bad), MOORSIM_ERROR_INPUT,
                 "not finite");
  EXPECT_REFUSED(moorsim_plant_fairlead_tensions(plant.handle, values, 7), MOORSIM_ERROR_USAGE,
                 "expected 8");
  EXPECT_REFUSED(moorsim_plant_loads(plant.handle, values, 6), MOORSIM_ERROR_USAGE, "expected 30");
  EXPECT_REFUSED(moorsim_plant_measured_tensions(plant.handle, values, 8), MOORSIM_ERROR_INPUT,
                 "no load cells");
  ASSERT_EQ(moorsim_plant_save(plant.handle, nullptr, 0, &size), MOORSIM_OK);
  std::vector<unsigned char> saved(size);
  ASSERT_EQ(moorsim_plant_save(plant.handle, saved.data(), size, &size), MOORSIM_OK);
  Plant other_seed(SeedPlant(), 8);
  EXPECT_REFUSED(moorsim_plant_restore(other_seed.handle, saved.data(), size), MOORSIM_ERROR_INPUT,
                 "another model");
  EXPECT_REFUSED(moorsim_plant_restore(plant.handle, saved.data(), size - 1), MOORSIM_ERROR_INPUT,
                 "cut short");
  Lines lines(Mooring());
  InitAtRest(lines.handle);
  std::vector<unsigned char> lines_state(4096);
  ASSERT_EQ(moorsim_lines_save(lines.handle, lines_state.data(), lines_state.size(), &size),
            MOORSIM_OK);
  EXPECT_REFUSED(moorsim_plant_restore(plant.handle, lines_state.data(), size), MOORSIM_ERROR_INPUT,
                 "not a moorsim plant state");
}

// What looks wrong but is done is warned of, once per kind and instance, through the
// program's handler: a fairlead above the water by more than a hundredth of its line's
// length (the lines are modelled submerged), a body faster than a moored body can be.
TEST(CApi, DoubtfulPosesAndMotionsAreWarnedOfOnceAndStillDone) {
  std::vector<std::string> warnings;
  moorsim_set_warning_handler(
      [](const char* message, void* user) {
        static_cast<std::vector<std::string>*>(user)->push_back(message);
      },
      &warnings);
  Lines lines(Mooring());
  double x[6] = {0, 0, -20, 0, 0, 0}, xd[6] = {0}, f[6], t = 0.0, dt = 0.1;
  ASSERT_EQ(moorsim_lines_init(lines.handle, x, xd), MOORSIM_OK) << moorsim_last_error();
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(warnings[0].rfind("moorsim_lines_init: line 1's fairlead is 15 m above the water at "
                              "this pose: the lines are modelled submerged all along",
                              0),
            0u)
      << warnings[0];
  x[2] = 0.0;
  ASSERT_EQ(moorsim_lines_init(lines.handle, x, xd), MOORSIM_OK);
  ASSERT_EQ(moorsim_lines_step(lines.handle, x, xd, f, &t, &dt), MOORSIM_OK);
  EXPECT_EQ(warnings.size(), 1u);  // nothing doubtful
  x[0] = 10.0;                     // 100 m/s
  ASSERT_EQ(moorsim_lines_step(lines.handle, x, xd, f, &t, &dt), MOORSIM_OK);
  ASSERT_EQ(warnings.size(), 2u);
  EXPECT_EQ(warnings[1],
            "moorsim_lines_step: the body moves 10 m and turns 0 rad in a step of 0.1 s at t = "
            "0.1 s, faster than a moored body can (a pose in other units, or a jump?); the lines "
            "follow it as given");
  x[0] = 0.0;  // and back: said once only
  ASSERT_EQ(moorsim_lines_step(lines.handle, x, xd, f, &t, &dt), MOORSIM_OK);
  EXPECT_EQ(warnings.size(), 2u);
  moorsim_set_warning_handler(nullptr, nullptr);
}

// A long call stops on moorsim_*_interrupt from another thread, soon and cleanly: the lines
// as they were before the step, the plant at an instant it would have stopped at anyway,
// both able to go on. A request made between calls stops the next one before it moves.
TEST(CApi, AnInterruptStopsAStepAndLeavesTheLinesAsTheyWere) {
  // Steps of at most 1 ms: a day's step would take hours.
  Lines lines(Mooring(20, 640.0, "solver: {max_step: 0.001}\n"));
  InitAtRest(lines.handle);
  double x[6] = {0}, xd[6] = {0}, f[6], t = 0.0, day = 86400.0;
  std::thread interrupter([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    EXPECT_EQ(moorsim_lines_interrupt(lines.handle), MOORSIM_OK);
  });
  EXPECT_REFUSED(moorsim_lines_step(lines.handle, x, xd, f, &t, &day), MOORSIM_ERROR_INTERRUPTED,
                 "interrupted at t = ");
  interrupter.join();
  EXPECT_EQ(t, 0.0);
  ASSERT_EQ(moorsim_lines_time(lines.handle, &t), MOORSIM_OK);
  EXPECT_EQ(t, 0.0);
  double dt = 0.05;
  EXPECT_EQ(moorsim_lines_step(lines.handle, x, xd, f, &t, &dt), MOORSIM_OK)
      << moorsim_last_error();
  EXPECT_EQ(t, 0.05);
  // Asked between calls: the next step stops before it moves, the one after runs.
  ASSERT_EQ(moorsim_lines_interrupt(lines.handle), MOORSIM_OK);
  EXPECT_EQ(moorsim_lines_step(lines.handle, x, xd, f, &t, &dt), MOORSIM_ERROR_INTERRUPTED);
  EXPECT_EQ(t, 0.05);
  EXPECT_EQ(moorsim_lines_step(lines.handle, x, xd, f, &t, &dt), MOORSIM_OK);
  EXPECT_EQ(moorsim_lines_interrupt(nullptr), MOORSIM_ERROR_USAGE);
}

TEST(CApiPlant, AnInterruptStopsAnAdvanceWhereTheRunWouldHaveStoppedAnyway) {
  Plant plant(SeedPlant());
  std::thread interrupter([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    EXPECT_EQ(moorsim_plant_interrupt(plant.handle), MOORSIM_OK);
  });
  EXPECT_REFUSED(moorsim_plant_advance_to(plant.handle, 86400.0), MOORSIM_ERROR_INTERRUPTED,
                 "interrupted at t = ");
  interrupter.join();
  double reached = 0.0;
  ASSERT_EQ(moorsim_plant_time(plant.handle, &reached), MOORSIM_OK);
  ASSERT_GT(reached, 0.0);
  ASSERT_LT(reached, 86400.0);
  // Going on from there is going there at once: the same plant, bit for bit.
  const double on = std::ceil(reached) + 1.0;
  ASSERT_EQ(moorsim_plant_advance_to(plant.handle, on), MOORSIM_OK) << moorsim_last_error();
  Plant straight(SeedPlant());
  ASSERT_EQ(moorsim_plant_advance_to(straight.handle, on), MOORSIM_OK);
  EXPECT_EQ(PlantReadings(plant.handle), PlantReadings(straight.handle));
  // Asked between calls: the next advance stops before it moves.
  ASSERT_EQ(moorsim_plant_interrupt(plant.handle), MOORSIM_OK);
  EXPECT_EQ(moorsim_plant_advance_to(plant.handle, on + 5.0), MOORSIM_ERROR_INTERRUPTED);
  ASSERT_EQ(moorsim_plant_time(plant.handle, &reached), MOORSIM_OK);
  EXPECT_EQ(reached, on);
  EXPECT_EQ(moorsim_plant_interrupt(nullptr), MOORSIM_ERROR_USAGE);
}

}  // namespace
