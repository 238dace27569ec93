// MoorDyn input files as scenarios (scenarios/moordyn.h): the files are written here, in
// both of MoorDyn's table layouts, with this test's own numbers. What maps must arrive
// converted (frames, the tangential drag's circumference, damping ratios, a composite line
// through a free point written fairlead first, free points where lines meet or end); what
// does not must be one located line each.
#include "scenarios/moordyn.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "core/error.h"
#include "core/format.h"
#include "mooring_fem/environment.h"
#include "mooring_fem/wave_kinematics.h"
#include "scenarios/load.h"
#include "tests/support/moordyn_spread.h"
#include "tests/support/scratch_directory.h"

namespace moorsim::scenarios {
namespace {

namespace fs = std::filesystem;

using moorsim::testing::kMoorDynSpread;
constexpr const char* kSpread = kMoorDynSpread;

fs::path Write(const fs::path& dir, const std::string& name, const std::string& text) {
  const fs::path path = dir / name;
  std::ofstream(path) << text;
  return path;
}

std::string ErrorOf(const fs::path& path) {
  try {
    ImportMoorDyn(path.string(), "test");
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(MoorDynImport, LinesPointsAndOptionsArriveConverted) {
  const fs::path dir = moorsim::testing::FreshDirectory("moordyn_spread");
  const fs::path file = Write(dir, "spread.txt", kSpread);
  const MoorDynImport imported = ImportMoorDyn(file.string(), "test");
  EXPECT_EQ(imported.lines, 3);
  EXPECT_TRUE(imported.warnings.empty());
  const Scenario s = ParseScenario(imported.yaml, "spread.yaml");
  EXPECT_EQ(s.mooring.water.depth, 200.0);
  EXPECT_EQ(s.mooring.water.density, 1020.0);
  EXPECT_EQ(s.mooring.seabed.stiffness, 2.0e6);
  EXPECT_EQ(s.mooring.seabed.damping, 2.0e5);
  ASSERT_EQ(s.mooring.line_types.size(), 2u);
  const mooring_fem::LineType& chain = s.mooring.line_types[0];
  EXPECT_EQ(chain.diameter, 0.1);
  EXPECT_EQ(chain.mass_per_length, 150.0);
  EXPECT_EQ(chain.axial_stiffness, 8.0e8);
  EXPECT_EQ(chain.axial_damping_ratio.value(), 0.6);  // BA/-zeta -0.6: a damping ratio
  EXPECT_EQ(chain.drag_normal, 2.0);
  EXPECT_NEAR(chain.drag_tangential, 0.3 * std::numbers::pi, 1e-15);  // on pi d in MoorDyn
  EXPECT_EQ(chain.added_mass_normal, 0.9);
  EXPECT_EQ(chain.friction_axial, 0.4);
  EXPECT_EQ(chain.friction_lateral, 0.4);
  EXPECT_EQ(s.mooring.line_types[1].axial_damping.value(), 2.0e5);  // BA in N s
  // Frames: (x, y, z) up and to port -> (x, -y, -z) down and to starboard.
  ASSERT_EQ(s.mooring.lines.size(), 3u);
  EXPECT_EQ(s.mooring.lines[1].anchor, Vec3(-300.0, -520.0, 200.0));
  EXPECT_EQ(s.mooring.lines[1].fairlead_body, Vec3(-5.0, -8.66, 15.0));
  EXPECT_EQ(s.mooring.lines[0].sections.size(), 1u);
  EXPECT_EQ(s.mooring.lines[0].Segments(), 30);
  // Lines 4 and 3 in series through point 7, from the anchor (point 3) up; the clump on
  // their joint.
  const LineSpec& composite = s.mooring.lines[2];
  EXPECT_EQ(composite.anchor, Vec3(-300.0, 520.0, 200.0));
  EXPECT_EQ(composite.fairlead_body, Vec3(-5.0, 8.66, 15.0));
  ASSERT_EQ(composite.sections.size(), 2u);
  EXPECT_EQ(composite.sections[0].type, "chain");
  EXPECT_EQ(composite.sections[0].length, 350.0);
  EXPECT_EQ(composite.sections[1].type, "wire");
  EXPECT_EQ(composite.sections[1].segments, 15);
  ASSERT_EQ(composite.joints.size(), 1u);
  EXPECT_EQ(composite.joints[0].mass, 5000.0);
  EXPECT_EQ(composite.joints[0].volume, 0.64);
  EXPECT_EQ(composite.joints[0].added_mass, 0.8);
  EXPECT_EQ(composite.joints[0].drag_area, 1.5);
  // Where each value came from is said beside it.
  EXPECT_NE(imported.yaml.find("# MoorDyn lines 4, 3: point 3 -> 7 -> 6"), std::string::npos)
      << imported.yaml;
  EXPECT_NE(imported.yaml.find("dtM 0.001"), std::string::npos);
  fs::remove_all(dir);
}

// MoorDyn's water depth: WtrDpth, deepened to a point below it (with a warning), and the
// deepest point's depth when the file gives none.
TEST(MoorDynImport, TheWaterDepthIsWtrDpthOrTheDeepestPointsAsInMoorDyn) {
  const fs::path dir = moorsim::testing::FreshDirectory("moordyn_depth");
  std::string deeper = kSpread;
  deeper.replace(deeper.find("200           WtrDpth"), 3, "150");
  const fs::path shallow = Write(dir, "shallow.txt", deeper);
  const MoorDynImport below = ImportMoorDyn(shallow.string(), "test");
  ASSERT_EQ(below.warnings.size(), 1u);
  EXPECT_EQ(below.warnings[0], shallow.string() +
                                   ":11: point 1 lies below the water depth WtrDpth (150 m): the "
                                   "depth is taken to it (200 m), as MoorDyn does");
  EXPECT_EQ(ParseScenario(below.yaml, "shallow.yaml").mooring.water.depth, 200.0);
  std::string none = kSpread;
  none.erase(none.find("200           WtrDpth"),
             std::string("200           WtrDpth       water depth (m)\n").size());
  ASSERT_EQ(none.find("WtrDpth"), std::string::npos);
  const MoorDynImport deepest = ImportMoorDyn(Write(dir, "none.txt", none).string(), "test");
  EXPECT_TRUE(deepest.warnings.empty());
  EXPECT_EQ(ParseScenario(deepest.yaml, "none.yaml").mooring.water.depth, 200.0);
  EXPECT_NE(deepest.yaml.find("# the deepest point's depth (line 11), as MoorDyn takes it"),
            std::string::npos)
      << deepest.yaml;
  // No depth given and nothing under water: nothing to take it from.
  std::string dry = none;
  for (std::size_t at; (at = dry.find("-200")) != std::string::npos;) dry.replace(at, 4, "0");
  for (std::size_t at; (at = dry.find("-190")) != std::string::npos;) dry.replace(at, 4, "0");
  for (std::size_t at; (at = dry.find("-15 ")) != std::string::npos;) dry.replace(at, 4, "0  ");
  const fs::path dry_file = Write(dir, "dry.txt", dry);
  EXPECT_EQ(
      ErrorOf(dry_file),
      dry_file.string() + ":1: no WtrDpth option and no point below the water: no water depth");
  fs::remove_all(dir);
}

// WaveKin 1 says the coupling program gives the waves through MoorDyn's API: the file holds
// none, so the model imports in still water with a warning. MoorDyn's node approaches
// (WaveKin 4 to 6, Currents 3 and 4), which it does not implement either, are refused, and
// a wave input whose file is missing is one located line.
TEST(MoorDynImport, WavesFromTheApiImportAsStillWaterAndUnknownInputsAreRefused) {
  const fs::path dir = moorsim::testing::FreshDirectory("moordyn_wavekin");
  std::string text = kSpread;
  text.replace(text.find("200           WtrDpth"), 0, "1             WaveKin       from the API\n");
  const fs::path api = Write(dir, "api.txt", text);
  const MoorDynImport imported = ImportMoorDyn(api.string(), "test");
  ASSERT_EQ(imported.warnings.size(), 1u);
  EXPECT_EQ(imported.warnings[0],
            api.string() +
                ":30: option WaveKin 1: the wave kinematics come from the coupling program "
                "through MoorDyn's API; the imported model sees still water (or moorsim's own "
                "waves, environment.waves with on_lines)");
  EXPECT_FALSE(ParseScenario(imported.yaml, "api.yaml").environment.waves.enabled);
  text.replace(text.find("1             WaveKin"), 1, "4");
  const fs::path node = Write(dir, "node.txt", text);
  EXPECT_EQ(ErrorOf(node), node.string() +
                               ":30: option WaveKin 4 is not supported (WaveKin 0, 1, 2, 3 or 7 "
                               "and Currents 0, 1, 2 or 5 are: MoorDyn v2.7.1 does not implement "
                               "its node approaches either)");
  text.replace(text.find("4             WaveKin"), 1, "7");
  const fs::path missing = Write(dir, "missing.txt", text);
  EXPECT_EQ(ErrorOf(missing), missing.string() +
                                  ":30: WaveKin 7: wave_frequencies.txt: not found beside the "
                                  "input file or in a folder above it");
  fs::remove_all(dir);
}

// MoorDyn's seabed pushes back linearly from the first touch: the import narrows moorsim's
// smooth contact ramp to a tenth of the shallowest resting penetration w / (kBot d) of the
// sinking line types (the wire: (40 - 1020 pi 0.08^2 / 4) 9.81 = 342.1 N/m), between 1 cm
// and 0.5 m, so the lines rest as deep as in MoorDyn.
TEST(MoorDynImport, TheSeabedContactIsAsSharpAsMoorDyns) {
  const fs::path dir = moorsim::testing::FreshDirectory("moordyn_contact");
  const Scenario stiff = ParseScenario(
      ImportMoorDyn(Write(dir, "stiff.txt", kSpread).string(), "test").yaml, "stiff.yaml");
  EXPECT_EQ(stiff.mooring.seabed.contact_smoothing, 0.01);  // 2.1 mm deep: the floor
  std::string text = kSpread;
  text.replace(text.find("2.0e6         kBot"), 5, "1.0e4");
  const Scenario soft =
      ParseScenario(ImportMoorDyn(Write(dir, "soft.txt", text).string(), "test").yaml, "soft.yaml");
  EXPECT_EQ(soft.mooring.seabed.contact_smoothing, 0.043);  // 0.428 m deep
  fs::remove_all(dir);
}

// A fixed point above the seabed holds its line's end in the water (a jumper's base): here
// every anchor, in water 80 m deeper than they lie.
TEST(MoorDynImport, AFixedPointInMidWaterHoldsItsLineThere) {
  const fs::path dir = moorsim::testing::FreshDirectory("moordyn_jumper");
  std::string text = kSpread;
  text.replace(text.find("200           WtrDpth"), 3, "280");
  const MoorDynImport imported = ImportMoorDyn(Write(dir, "jumper.txt", text).string(), "test");
  EXPECT_NE(imported.yaml.find("anchor_in_water: true  # 80 m above the seabed"), std::string::npos)
      << imported.yaml;
  const Scenario s = ParseScenario(imported.yaml, "jumper.yaml");
  for (const LineSpec& line : s.mooring.lines) {
    EXPECT_EQ(line.anchor_in_water, line.lower_point < 0) << line.id;
  }
  EXPECT_EQ(s.mooring.lines[1].anchor, Vec3(-300.0, -520.0, 200.0));
  fs::remove_all(dir);
}

// Some of MoorDyn's own files name the damping column cIntDamp: it is BA/-zeta.
TEST(MoorDynImport, TheDampingColumnNamedCIntDampIsBa) {
  const fs::path dir = moorsim::testing::FreshDirectory("moordyn_cintdamp");
  std::string text = kSpread;
  text.replace(text.find("BA/-zeta"), 8, "cIntDamp");
  const Scenario s = ParseScenario(
      ImportMoorDyn(Write(dir, "damping.txt", text).string(), "test").yaml, "damping.yaml");
  EXPECT_EQ(s.mooring.line_types[0].axial_damping_ratio.value(), 0.6);
  fs::remove_all(dir);
}

// The test spread with one more option line before WtrDpth (line 30).
std::string WithOption(const std::string& option) {
  std::string text = kSpread;
  text.replace(text.find("200           WtrDpth"), 0, option + "\n");
  return text;
}

// The finite-depth wave number, omega^2 = g k tanh(k h), by bisection: this test's own.
double WaveNumberOf(double omega, double depth, double g) {
  double low = 0.0, high = 10.0 * omega * omega / g + 10.0;
  for (int i = 0; i < 200; ++i) {
    const double k = 0.5 * (low + high);
    (g * k * std::tanh(k * depth) < omega * omega ? low : high) = k;
  }
  return 0.5 * (low + high);
}

// MoorDyn's waves: WaveKin 7 sums wave_frequencies.txt's rows (omega, re, im, direction) as
// |A| sin(omega t - k (x cos(beta) + y sin(beta)) + arg A); the imported sea, in moorsim's
// frame (y and the direction mirrored), has the same elevation everywhere. WaveKin 2 puts
// the rows on an even grid first; WaveKin 3 takes the Fourier components of
// wave_elevation.txt sampled every dtWave.
TEST(MoorDynImport, WaveInputsBecomeTheSameRegularWaves) {
  const fs::path dir = moorsim::testing::FreshDirectory("moordyn_waves");
  const double h = 200.0, g = 9.81;
  Write(dir, "wave_frequencies.txt", "0.0 0.0 0.0\n0.4 0.3 -0.4 0.5\n0.9 0.0 0.2\n");
  const MoorDynImport summed =
      ImportMoorDyn(Write(dir, "sum.txt", WithOption("7 WaveKin")).string(), "test");
  const Scenario s = ParseScenario(summed.yaml, "sum.yaml");
  ASSERT_EQ(s.environment.waves.trains.size(), 2u);
  EXPECT_TRUE(s.environment.waves.on_lines);
  const auto elevation_of = [&](const Scenario& scenario) {
    std::vector<mooring_fem::WaveTrain> trains;
    for (const vessel::WaveComponent& c : scenario.environment.waves.trains) {
      trains.push_back({c.omega, c.amplitude, c.phase, c.direction});
    }
    return mooring_fem::WaveKinematics(trains, h, g, mooring_fem::WaveStretching::kWheeler);
  };
  const mooring_fem::WaveKinematics sum = elevation_of(s);
  for (const auto& [t, x, y] : {std::tuple{0.0, 0.0, 0.0}, std::tuple{13.7, 40.0, -25.0},
                                std::tuple{101.2, -300.0, 180.0}}) {
    const double k1 = WaveNumberOf(0.4, h, g), k2 = WaveNumberOf(0.9, h, g);
    const double moordyn = 0.5 * std::sin(0.4 * t - k1 * (x * std::cos(0.5) + y * std::sin(0.5)) +
                                          std::atan2(-0.4, 0.3)) +
                           0.2 * std::sin(0.9 * t - k2 * x + std::numbers::pi / 2.0);
    EXPECT_NEAR(sum.Elevation(t, x, -y), moordyn, 1e-9) << t;
  }

  // On the even grid of the smallest spacing (0.25 rad/s): the row at 0.5 rad/s lies half
  // way between the given ones; the top bin (0.75) takes half its real part: none here.
  Write(dir, "wave_frequencies.txt", "0.0 0.0 0.0\n0.25 0.5 0.0\n0.75 0.0 0.5\n");
  const Scenario even = ParseScenario(
      ImportMoorDyn(Write(dir, "even.txt", WithOption("2 WaveKin")).string(), "test").yaml,
      "even.yaml");
  ASSERT_EQ(even.environment.waves.trains.size(), 2u);
  EXPECT_NEAR(even.environment.waves.trains[0].omega, 0.25, 1e-15);
  EXPECT_NEAR(even.environment.waves.trains[0].amplitude, 0.5, 1e-15);
  EXPECT_NEAR(even.environment.waves.trains[1].omega, 0.5, 1e-15);
  EXPECT_NEAR(even.environment.waves.trains[1].amplitude, std::hypot(0.25, 0.25), 1e-15);
  EXPECT_NEAR(even.environment.waves.trains[1].phase, std::numbers::pi / 4.0, 1e-15);

  // 0.5 cos(2 pi t / 10) + 0.2 sin(2 pi t / 4) over 40 s: at dtWave 0.5 s, 80 samples,
  // both periods whole in the record: exactly two waves, toward MoorDyn's x (north).
  std::string series;
  const auto zeta = [](double t) {
    return 0.5 * std::cos(2.0 * std::numbers::pi * t / 10.0) +
           0.2 * std::sin(2.0 * std::numbers::pi * t / 4.0);
  };
  for (int i = 0; i <= 160; ++i) {
    series += FormatNumber(0.25 * i) + " " + FormatNumber(zeta(0.25 * i)) + "\n";
  }
  Write(dir, "wave_elevation.txt", series);
  const Scenario record = ParseScenario(
      ImportMoorDyn(Write(dir, "record.txt", WithOption("3 WaveKin\n0.5 dtWave")).string(), "test")
          .yaml,
      "record.yaml");
  ASSERT_EQ(record.environment.waves.trains.size(), 2u);
  const mooring_fem::WaveKinematics waves = elevation_of(record);
  // A record whose transform would take minutes is refused, not run: 2e5 s at 0.5 s.
  Write(dir, "wave_elevation.txt", "0 0\n200000 0\n");
  const fs::path long_record = Write(dir, "long.txt", WithOption("3 WaveKin\n0.5 dtWave"));
  EXPECT_EQ(ErrorOf(long_record), long_record.string() +
                                      ":30: WaveKin 3: wave_elevation.txt: 400000 samples at "
                                      "dtWave 0.5 s keep 100000 frequencies: more than moorsim "
                                      "transforms (samples x frequencies <= 1e8); give a shorter "
                                      "record");
  const double k10 = WaveNumberOf(2.0 * std::numbers::pi / 10.0, h, g);
  const double k4 = WaveNumberOf(2.0 * std::numbers::pi / 4.0, h, g);
  for (const auto& [t, x] : {std::pair{0.0, 0.0}, std::pair{3.3, 0.0}, std::pair{17.1, 30.0}}) {
    const double expected = 0.5 * std::cos(2.0 * std::numbers::pi * t / 10.0 - k10 * x) +
                            0.2 * std::sin(2.0 * std::numbers::pi * t / 4.0 - k4 * x);
    EXPECT_NEAR(waves.Elevation(t, x, 12.0), expected, 1e-9) << t;
  }
  fs::remove_all(dir);
}

// MoorDyn's currents: a steady profile of one direction is moorsim's profile (points above
// the surface left out, the surface's value added); a dynamic profile (Currents 2) and a
// 4-D grid (Currents 5) are a table beside the scenario, in moorsim's frame, repeating as
// MoorDyn repeats them.
TEST(MoorDynImport, CurrentInputsBecomeAProfileOrATable) {
  const fs::path dir = moorsim::testing::FreshDirectory("moordyn_currents");
  Write(dir, "current_profile.txt",
        "--- steady ---\nheader\nz ux uy uz\n-200 0.1 -0.1 0\n-100 0.3 -0.3 0\n2 0.5 -0.5 0\n");
  const Scenario steady = ParseScenario(
      ImportMoorDyn(Write(dir, "steady.txt", WithOption("1 Currents")).string(), "test").yaml,
      "steady.yaml");
  const mooring_fem::CurrentProfile& profile = steady.mooring.current;
  EXPECT_EQ(profile.table, nullptr);
  EXPECT_NEAR(profile.direction, std::numbers::pi / 4.0, 1e-15);  // MoorDyn's (1, -1): NE
  EXPECT_EQ(profile.depth, (std::vector<double>{0.0, 100.0, 200.0}));
  ASSERT_EQ(profile.speed.size(), 3u);
  EXPECT_NEAR(profile.speed[0], (0.3 + 0.2 * 100.0 / 102.0) * std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(profile.speed[2], 0.1 * std::sqrt(2.0), 1e-15);

  // Rows "t ux(z) uy(z) uz(z)" at z = -200, -100, 0.
  Write(dir, "current_profile_dynamic.txt",
        "--- dynamic ---\nheader\n2\n3\n-200 -100 0\n\n"
        "0  0.1 0.2 0.3  0.0 0.0 0.0  0.0 0.0 0.0\n"
        "10 0.3 0.4 0.5  0.1 0.1 0.1  0.0 0.01 0.0\n"
        "20 0.1 0.2 0.3  0.0 0.0 0.0  0.0 0.0 0.0\n");
  const fs::path dynamic_file = Write(dir, "dynamic.txt", WithOption("2 Currents"));
  const MoorDynImport dynamic = ImportMoorDyn(dynamic_file.string(), "test");
  ASSERT_EQ(dynamic.files.size(), 1u);
  EXPECT_EQ(dynamic.files[0].first, "dynamic_current.txt");
  Write(dir, dynamic.files[0].first, dynamic.files[0].second);
  Write(dir, "dynamic.yaml", dynamic.yaml);
  const Scenario with_table = LoadScenario((dir / "dynamic.yaml").string());
  ASSERT_NE(with_table.mooring.current.table, nullptr);
  EXPECT_EQ(with_table.mooring.current.table->period, 30.0);  // 3 steps of 10 s
  const mooring_fem::CurrentField field(with_table.mooring.current);
  // Depth 50 (z -50) at 5 s: half way between z -100 and 0 and between 0 and 10 s.
  EXPECT_LT((field.VelocityAt(5.0, Vec3(7.0, 3.0, 50.0)) -
             Vec3(0.25 * (0.2 + 0.3 + 0.4 + 0.5), -0.25 * (0.1 + 0.1), -0.25 * 0.01))
                .norm(),
            1e-15);
  EXPECT_LT(
      (field.VelocityAt(35.0, Vec3(0, 0, 50.0)) - field.VelocityAt(5.0, Vec3(0, 0, 50.0))).norm(),
      1e-15);

  // A 4-D grid of u = (0.01 x + 0.1 t, 0.02 y, 0.001 z), which the table holds exactly.
  std::string grid = "2 2 2 2\n-10 10\n-5 5\n-50 0\n0 5\n";
  for (double x : {-10.0, 10.0}) {
    for (double y : {-5.0, 5.0}) {
      for (double z : {-50.0, 0.0}) {
        for (double t : {0.0, 5.0}) {
          grid += FormatNumber(x) + " " + FormatNumber(y) + " " + FormatNumber(z) + " " +
                  FormatNumber(t) + " " + FormatNumber(0.01 * x + 0.1 * t) + " " +
                  FormatNumber(0.02 * y) + " " + FormatNumber(0.001 * z) + "\n";
        }
      }
    }
  }
  Write(dir, "current_profile_4d.txt", grid);
  const MoorDynImport four_d =
      ImportMoorDyn(Write(dir, "four_d.txt", WithOption("5 Currents")).string(), "test");
  Write(dir, four_d.files[0].first, four_d.files[0].second);
  Write(dir, "four_d.yaml", four_d.yaml);
  const mooring_fem::CurrentField grid_field(
      LoadScenario((dir / "four_d.yaml").string()).mooring.current);
  // moorsim's (2, -3, depth 20) is MoorDyn's (2, 3, -20).
  EXPECT_LT((grid_field.VelocityAt(1.0, Vec3(2.0, -3.0, 20.0)) - Vec3(0.12, -0.06, 0.02)).norm(),
            1e-15);
  fs::remove_all(dir);
}

// MoorDyn v1's layout: other column names and order, CONNECTION PROPERTIES with Connect
// points, LINE PROPERTIES; EI is left out with a warning.
TEST(MoorDynImport, TheOlderLayoutReadsByColumnName) {
  const fs::path dir = moorsim::testing::FreshDirectory("moordyn_v1");
  const fs::path file =
      Write(dir, "v1.txt", R"(--------------------- MoorDyn Input File --------------------
v1 layout
---------------------- LINE DICTIONARY ---------------------------------------------
LineType  Diam    MassDenInAir   EA        BA/-zeta    Can     Cat    Cdn     Cdt   EI
(-)       (m)     (kg/m)        (N)       (Pa-s/-)    (-)     (-)    (-)     (-)   (N-m^2)
rope      0.12    30            2.0E8      -0.8        1.0     0.5    1.6     0.05  10
---------------------- CONNECTION PROPERTIES --------------------------------
Node  Type      X        Y         Z        M        V        FX       FY      FZ     CdA   CA
(-)   (-)       (m)      (m)       (m)      (kg)     (m^3)    (kN)     (kN)    (kN)   (m^2) (-)
1     Fixed     500      0         -150     0        0        0        0       0      0     0
2     Vessel    12       0         -10      0        0        0        0       0      0     0
---------------------- LINE PROPERTIES --------------------------------------
Line     LineType  UnstrLen  NumSegs   NodeAnch  NodeFair  Flags/Outputs
(-)      (-)       (m)       (-)       (-)       (-)       (-)
1        rope      560       20        1         2         -
---------------------- SOLVER OPTIONS ---------------------------------------
150      WtrDpth
9.80665  g
)");
  const MoorDynImport imported = ImportMoorDyn(file.string(), "test");
  const Scenario s = ParseScenario(imported.yaml, "v1.yaml");
  const mooring_fem::LineType& rope = s.mooring.line_types.at(0);
  EXPECT_EQ(rope.mass_per_length, 30.0);
  EXPECT_EQ(rope.drag_normal, 1.6);
  EXPECT_EQ(rope.added_mass_normal, 1.0);
  EXPECT_NEAR(rope.drag_tangential, 0.05 * std::numbers::pi, 1e-15);
  EXPECT_EQ(s.mooring.water.gravity, 9.80665);
  EXPECT_EQ(s.mooring.lines.at(0).Length(), 560.0);
  EXPECT_EQ(rope.added_mass_tangential, 0.5);  // Cat
  ASSERT_EQ(imported.warnings.size(), 1u);
  EXPECT_EQ(imported.warnings[0].rfind(file.string() + ":6: line type rope: bending", 0), 0u)
      << imported.warnings[0];
  fs::remove_all(dir);
}

// A free point where three lines meet (a bridle's apex, here with its clump weight) becomes
// one of moorsim's free points, the lines running from and to it; a line's free end too.
TEST(MoorDynImport, FreePointsWhereLinesMeetOrEndArriveAsPoints) {
  const fs::path dir = moorsim::testing::FreshDirectory("moordyn_bridle");
  std::string text = kSpread;
  text.replace(text.find("4     chain      7        3"), 0,
               "5     chain      7        1         300       10      p\n"
               "6     wire       5        8         40        8       p\n");
  text.replace(text.find("---------------------- LINES"), 0,
               "8     Free      -5      20      -40     0      2.0     1.0    1.0\n");
  const fs::path file = Write(dir, "bridle.txt", text);
  const MoorDynImport imported = ImportMoorDyn(file.string(), "test");
  const std::string& y = imported.yaml;
  EXPECT_EQ(imported.lines, 6);
  EXPECT_NE(y.find("  points:\n    - {name: point_7, position: [-150, 260, 190], mass: 5000, "
                   "volume: 0.64, added_mass: 0.8, drag_area: 1.5}  # point 7 (line 17)"),
            std::string::npos)
      << y;
  EXPECT_NE(y.find("{name: point_8, position: [-5, -20, 40]"), std::string::npos) << y;
  // The wire from the vessel down to the apex runs from the apex up; the chains from the
  // fixed points up to it; the buoy's pendant from the buoy (the deeper end) up to the
  // vessel point.
  EXPECT_NE(y.find("MoorDyn line 3: point 7 -> 6\n      from: point_7  # point 7 (line 17)\n"
                   "      fairlead: [-5, 8.66, 15]"),
            std::string::npos)
      << y;
  EXPECT_NE(y.find("MoorDyn line 4: point 3 -> 7\n      anchor: [-300, 520, 200]  # point 3 "
                   "(line 13)\n      to: point_7"),
            std::string::npos)
      << y;
  EXPECT_NE(y.find("MoorDyn line 5: point 1 -> 7\n"), std::string::npos) << y;
  const Scenario s = ParseScenario(y, "bridle.yaml");
  EXPECT_EQ(s.mooring.points.size(), 2u);
  fs::remove_all(dir);
}

// MoorDyn's visco-elastic rope (EA_s|EA_D, BA_s|BA_D; Hall et al. 2023): its segment is the
// dynamic spring EA_D, damped by BA_D, in series with the static spring EA_D EA_s / (EA_D -
// EA_s) damped by BA_s. That is moorsim's dynamic spring in series with its creep spring
// and dashpot: the dynamic stiffness is EA_D and the creep time BA_s over the static
// spring. BA_D damps moorsim's whole segment instead, with a warning.
TEST(MoorDynImport, AViscoElasticRopeArrivesWithItsDynamicStiffnessAndCreepTime) {
  const fs::path dir = moorsim::testing::FreshDirectory("moordyn_visco");
  std::string text = kSpread;
  text.replace(text.find("5.0e8      2.0e5"), 16, "2.0e8|5.0e8 2.0e9|1.0e5");
  const fs::path file = Write(dir, "visco.txt", text);
  const MoorDynImport imported = ImportMoorDyn(file.string(), "test");
  const std::string& y = imported.yaml;
  EXPECT_NE(
      y.find("      axial_stiffness: 2e+08\n      dynamic_axial_stiffness: 5e+08  # EA_s|EA_D"),
      std::string::npos)
      << y;
  // 2e9 / (5e8 x 2e8 / (5e8 - 2e8)) = 6 s.
  const Scenario s = ParseScenario(y, "visco.yaml");
  EXPECT_NEAR(s.mooring.line_types[1].visco_elastic->creep_time, 6.0, 1e-12);
  EXPECT_NE(y.find("      axial_damping: 1e+05  # BA_D [N s]"), std::string::npos) << y;
  ASSERT_EQ(imported.warnings.size(), 1u);
  EXPECT_NE(imported.warnings[0].find("BA_D 1e+05 damps the whole segment's stretch"),
            std::string::npos)
      << imported.warnings[0];
  // Without BA_D the dynamic spring is undamped, as in MoorDyn; a static damping that is not a
  // coefficient (MoorDyn's -zeta) is one located line.
  std::string undamped = kSpread;
  undamped.replace(undamped.find("5.0e8      2.0e5"), 16, "2.0e8|5.0e8 2.0e9");
  EXPECT_TRUE(
      ImportMoorDyn(Write(dir, "undamped.txt", undamped).string(), "test").warnings.empty());
  // EA_s|EA_Dc|EA_D_Lm: the dynamic stiffness rises with the mean load; the creep time is
  // the unloaded rope's.
  std::string stiffening = kSpread;
  stiffening.replace(stiffening.find("5.0e8      2.0e5"), 16, "2.0e8|5.0e8|30 2.0e9");
  const std::string ys =
      ImportMoorDyn(Write(dir, "stiffening.txt", stiffening).string(), "test").yaml;
  EXPECT_NE(ys.find("      dynamic_axial_stiffness: 5e+08  # EA_s|EA_Dc|EA_D_Lm 2e+08|5e+08|30\n"
                    "      dynamic_axial_stiffness_slope: 30  # EA_D_Lm"),
            std::string::npos)
      << ys;
  const Scenario st = ParseScenario(ys, "stiffening.yaml");
  EXPECT_EQ(st.mooring.line_types[1].visco_elastic->dynamic_stiffness_slope, 30.0);
  EXPECT_NEAR(st.mooring.line_types[1].visco_elastic->creep_time, 6.0, 1e-12);
  std::string ratio = kSpread;
  ratio.replace(ratio.find("5.0e8      2.0e5"), 16, "2.0e8|5.0e8 -0.5");
  const fs::path bad = Write(dir, "ratio.txt", ratio);
  EXPECT_EQ(ErrorOf(bad), bad.string() +
                              ":7: line type wire: BA '-0.5': a visco-elastic rope's static "
                              "damping BA_s (moorsim's creep dashpot) must be > 0 and its BA_D "
                              ">= 0, both in N s");
  fs::remove_all(dir);
}

// EA as a file (MoorDyn's nonlinear stiffness: three header lines, then rows "strain
// tension"): the line type's tension_strain, its first row at the origin left out (moorsim's
// curve starts there). A row that does not increase is one located line.
TEST(MoorDynImport, AStiffnessTableArrivesAsATensionStrainCurve) {
  const fs::path dir = moorsim::testing::FreshDirectory("moordyn_ea_table");
  std::string text = kSpread;
  text.replace(text.find("8.0e8"), 5, "chain_ea.txt");
  Write(dir, "chain_ea.txt",
        "Chain stiffness\nStrain Tension\n(-) (N)\n0 0\n0.005 4e6\n0.01 1e7\n");
  const MoorDynImport imported = ImportMoorDyn(Write(dir, "table.txt", text).string(), "test");
  EXPECT_NE(imported.yaml.find("      tension_strain:  # EA table chain_ea.txt"), std::string::npos)
      << imported.yaml;
  const Scenario s = ParseScenario(imported.yaml, "table.yaml");
  const std::vector<mooring_fem::StrainTension>& curve = s.mooring.line_types[0].tension_strain;
  ASSERT_EQ(curve.size(), 2u);
  EXPECT_EQ(curve[0].strain, 0.005);
  EXPECT_EQ(curve[0].tension, 4e6);
  EXPECT_EQ(curve[1].strain, 0.01);
  EXPECT_EQ(curve[1].tension, 1e7);
  const fs::path table = Write(dir, "chain_ea.txt", "a\nb\nc\n0.005 4e6\n0.004 5e6\n");
  const fs::path bad = Write(dir, "bad.txt", text);
  EXPECT_EQ(ErrorOf(bad), fs::absolute(table).string() +
                              ":5: strain 0.004 and tension 5e+06 N must both exceed the row "
                              "before's (0.005 and 4e+06 N)");
  fs::remove_all(dir);
}

// A line driven at its end from far away (a Coupled point given where it starts, 1360 m
// from MoorDyn's origin): the model moves so that the vessel point is the vessel's
// reference point, and says so.
TEST(MoorDynImport, AFarVesselPointMovesTheModelToIt) {
  const fs::path dir = moorsim::testing::FreshDirectory("moordyn_far");
  std::string text = kSpread;
  text.replace(text.find("4     Vessel    10 "), 18, "4     Vessel    1360 ");
  text.replace(text.find("5     Vessel    -5 "), 18, "5     Vessel    1345 ");
  text.replace(text.find("6     Vessel    -5 "), 18, "6     Vessel    1345 ");
  text.replace(text.find("1     Fixed     600 "), 19, "1     Fixed     1950 ");
  text.replace(text.find("2     Fixed     -300"), 20, "2     Fixed     1050");
  text.replace(text.find("3     Fixed     -300"), 20, "3     Fixed     1050");
  text.replace(text.find("7     Free      -150"), 20, "7     Free      1200");
  const fs::path file = Write(dir, "far.txt", text);
  const std::string y = ImportMoorDyn(file.string(), "test").yaml;
  EXPECT_NE(y.find("every point is moved by (-1350, 0) m in MoorDyn's x and y"), std::string::npos)
      << y;
  EXPECT_NE(y.find("anchor: [600, 0, 200]"), std::string::npos) << y;
  EXPECT_NE(y.find("fairlead: [10, 0, 15]"), std::string::npos) << y;
  fs::remove_all(dir);
}

// MoorDyn's bathymetry file, named relative to a folder above the input file (MoorDyn reads
// it from its working directory): a depth grid beside the scenario, y reversed (MoorDyn's
// y points to port) and heights made depths; a file that does not hold its points is one
// located line.
TEST(MoorDynImport, ASeafloorFileArrivesAsADepthGrid) {
  const fs::path dir = moorsim::testing::FreshDirectory("moordyn_seafloor");
  fs::create_directories(dir / "Mooring" / "floor");
  Write(dir / "Mooring" / "floor", "bottom.txt",
        "2 3\n-1000 1000\n-800 0 800\n"
        "-1000 -800 -200\n-1000 0 -200.2\n-1000 800 -200.4\n"
        "1000 -800 -200.1\n1000 0 -200.3\n1000 800 -200.5\n");
  std::string text = kSpread;
  text.replace(text.find("0.4           FrictionCoefficient"), 0,
               "Mooring/floor/bottom.txt    SeafloorFile    bathymetry\n");
  const fs::path file = Write(dir / "Mooring", "floor.txt", text);
  const MoorDynImport imported = ImportMoorDyn(file.string(), "test", "field");
  ASSERT_EQ(imported.files.size(), 1u);
  EXPECT_EQ(imported.files[0].first, "field_seabed.csv");
  const std::string& grid = imported.files[0].second;
  EXPECT_NE(grid.find("x\\y, -800, 0, 800\n-1000, 200.4, 200.2, 200\n1000, 200.5, 200.3, 200.1\n"),
            std::string::npos)
      << grid;
  EXPECT_NE(imported.yaml.find("grid: field_seabed.csv}"), std::string::npos) << imported.yaml;
  // Eight numbers short.
  Write(dir / "Mooring" / "floor", "bottom.txt", "2 3\n-1000 1000\n-800 0 800\n");
  EXPECT_EQ(ErrorOf(file), file.string() +
                               ":31: SeafloorFile Mooring/floor/bottom.txt: holds 7 numbers "
                               "where 2 x 3 points need 25");
  fs::remove_all(dir / "Mooring" / "floor");
  EXPECT_NE(ErrorOf(file).find(
                ":31: SeafloorFile Mooring/floor/bottom.txt: not found beside the input file"),
            std::string::npos);
  fs::remove_all(dir);
}

// Grid counts too large for any file (2^63 would wrap the count of numbers they need
// around to a small one; 1e300 is no size at all) are refused with the counts as written.
TEST(MoorDynImport, SeafloorCountsBeyondAnySizeAreRefusedAsWritten) {
  const fs::path dir = moorsim::testing::FreshDirectory("moordyn_seafloor_counts");
  std::string text = kSpread;
  text.replace(text.find("0.4           FrictionCoefficient"), 0,
               "bottom.txt    SeafloorFile    bathymetry\n");
  const fs::path file = Write(dir, "floor.txt", text);
  const std::string where = file.string() + ":31: SeafloorFile bottom.txt: holds ";
  Write(dir, "bottom.txt", "9223372036854775808 9223372036854777856\n0 0 0\n");
  EXPECT_EQ(ErrorOf(file), where +
                               "5 numbers where 9223372036854775808 x "
                               "9223372036854777856 points need 2.5521177519070392e+38");
  Write(dir, "bottom.txt", "1e300 2\n0 0 0\n");
  EXPECT_EQ(ErrorOf(file), where + "5 numbers where 1e+300 x 2 points need 7e+300");
  fs::remove_all(dir);
}

// What the loader refuses in the imported model is said of the MoorDyn file: the line and
// field each value came from, here a section of a composite line and the clump weight on
// its joint.
TEST(MoorDynImport, WhatTheModelBreaksIsSaidOfTheMoorDynLineAndField) {
  const fs::path dir = moorsim::testing::FreshDirectory("moordyn_located");
  std::string text = kSpread;
  text.replace(text.find("350       15"), 3, "0  ");
  text.replace(text.find("5000   0.64"), 4, "-5000");
  const fs::path file = Write(dir, "located.txt", text);
  const std::string f = file.string();
  EXPECT_EQ(ErrorOf(file), f +
                               ":24: line 4, UnstrLen: 0 m must be > 0 (the scenario's "
                               "mooring.lines[3].sections[1].length)\n" +
                               f +
                               ":17: point 7, Mass: -5000 kg must be >= 0 (the scenario's "
                               "mooring.lines[3].bodies[1].mass)");
  fs::remove_all(dir);
}

// A byte that is not UTF-8 (a Latin-1 name) is refused at its line of the MoorDyn file.
TEST(MoorDynImport, AByteThatIsNotUtf8IsRefusedAtItsLine) {
  const fs::path dir = moorsim::testing::FreshDirectory("moordyn_latin1");
  std::string text = kSpread;
  text.replace(text.find("wire       0.08"), 4, "w\xe9re");
  const fs::path file = Write(dir, "latin1.txt", text);
  EXPECT_EQ(ErrorOf(file),
            file.string() + ":7: not valid UTF-8 (byte 0xE9); save the file as UTF-8");
  fs::remove_all(dir);
}

// A point, line or line type given twice is refused where it is given again: importing
// would keep one of the two rows and drop the other unseen.
TEST(MoorDynImport, ANameGivenTwiceIsRefusedWhereItRepeats) {
  const fs::path dir = moorsim::testing::FreshDirectory("moordyn_twice");
  std::string text = kSpread;
  text.replace(text.find("7     Free"), 0,
               "6     Fixed     0       600     -200    0      0       0      0\n");
  text.replace(text.find("4     chain      7        3"), 0,
               "3     chain      2        5         680       30      p\n");
  text.replace(
      text.find("wire       0.08"), 0,
      "chain      0.1     150        8.0e8      -0.6        0    2.0    0.9    0.3     0.0\n");
  const fs::path file = Write(dir, "twice.txt", text);
  const std::string f = file.string();
  EXPECT_EQ(ErrorOf(file), f + ":7: line type chain is given twice (first on line 6)\n" + f +
                               ":18: point 6 is given twice (first on line 17)\n" + f +
                               ":26: line 3 is given twice (first on line 25)");
  fs::remove_all(dir);
}

// What moorsim cannot represent: one located line each, all of them at once.
TEST(MoorDynImport, WhatDoesNotMapIsOneLocatedLineEach) {
  const fs::path dir = moorsim::testing::FreshDirectory("moordyn_refused");
  std::string text = kSpread;
  // A bridle: a third line at the free point; a SYROPE rope; a rod.
  text.replace(text.find("4     chain      7        3"), 0,
               "5     chain      7        1         300       10      p\n");
  text.replace(text.find("8.0e8"), 5, "SYROPE:rope.dat|1.5e8|23");
  text.replace(text.find("---------------------- POINTS"), 0,
               "---------------------- RODS ----\nID RodType Attachment\n(#) (-) (-)\n"
               "1 pipe Fixed\n");
  const fs::path file = Write(dir, "refused.txt", text);
  const std::string error = ErrorOf(file);
  const std::string f = file.string();
  EXPECT_NE(error.find(f + ":6: EA 'SYROPE:rope.dat|1.5e8|23': a SYROPE rope"), std::string::npos)
      << error;
  EXPECT_NE(error.find(f + ":11: rods are not supported"), std::string::npos) << error;
  EXPECT_EQ(std::count(error.begin(), error.end(), '\n'), 1) << error;  // two lines so far
  // Lines that run between two vessel points.
  std::string between = kSpread;
  between.replace(between.find("4     chain      7        3"), 0,
                  "5     chain      4        5         30        10      p\n");
  const fs::path second = Write(dir, "between.txt", between);
  EXPECT_EQ(ErrorOf(second), second.string() + ":24: line 5 runs between vessel points 4 and 5");
  // Not a MoorDyn file at all.
  EXPECT_NE(ErrorOf(Write(dir, "other.txt", "hello\n")).find("no LINE TYPES, POINTS or LINES"),
            std::string::npos);
  EXPECT_NE(ErrorOf(dir / "missing.txt").find("missing.txt"), std::string::npos);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace moorsim::scenarios
