// The seabed's depth grid file (mooring.seabed.grid) and the sloping seabed in scenarios:
// the file read as written, each kind of bad grid one line naming the file and the line,
// and the anchors checked against the seabed below them.
#include "scenarios/depth_grid.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "bad_input_cases.h"
#include "core/error.h"
#include "mooring_fem/environment.h"
#include "scenarios/load.h"
#include "tests/support/scratch_directory.h"

namespace moorsim::scenarios {
namespace {

std::string WriteText(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path) << text;
  return path.string();
}

std::string GridError(const std::string& text) {
  const std::string path = WriteText(testing::FreshDirectory("grid") / "grid.csv", text);
  try {
    ReadDepthGrid(path);
  } catch (const InputError& e) {
    // The message without the directory.
    std::string message = e.what();
    return message.substr(message.find("grid.csv"));
  }
  return "(no error)";
}

TEST(DepthGrid, ReadsCommasOrSpacesWithCommentsAndALabel) {
  const std::filesystem::path dir = testing::FreshDirectory("grid_read");
  for (const std::string& text :
       {std::string("# a survey\nx\\y, -100, 0, 250\n-50, 990, 1000, 1010\n"
                    "\n# the second row\n60, 995, 1005, 1020\r\n"),
        std::string("x\\y -100 0 250\n-50 990 1000 1010\n60\t995 1005 1020\n")}) {
    const mooring_fem::DepthGrid grid = ReadDepthGrid(WriteText(dir / "grid.csv", text));
    EXPECT_EQ(grid.x, (std::vector<double>{-50.0, 60.0}));
    EXPECT_EQ(grid.y, (std::vector<double>{-100.0, 0.0, 250.0}));
    EXPECT_EQ(grid.depth, (std::vector<double>{990, 1000, 1010, 995, 1005, 1020}));
  }
}

TEST(DepthGrid, EachBadGridIsOneLineNamingTheFileLineAndValue) {
  EXPECT_EQ(GridError("x\\y, 0, 100\n0, 1000, 1000\n100, 1000, ,\n"),
            "grid.csv:3: 3 depths for 2 y coordinates (a row is x and one depth per y)");
  EXPECT_EQ(GridError("x\\y, 0, 100\n0, 1000, 1000\n100, 1000,\n"),
            "grid.csv:3: no depth at x = 100 m, y = 100 m (a hole in the grid)");
  EXPECT_EQ(GridError("x\\y, 0, 100\n0, 1000, 1000\n100, 1000, deep\n"),
            "grid.csv:3: 'deep' is not a number");
  EXPECT_EQ(GridError("x\\y, 0, 100\n0, 1000, 1000\n-10, 1000, 1000\n"),
            "grid.csv:3: x = -10 m does not follow x = 0 m (the axis must increase)");
  EXPECT_EQ(GridError("x\\y, 100, 0\n0, 1000, 1000\n10, 1000, 1000\n"),
            "grid.csv:1: y = 0 m does not follow y = 100 m (the axis must increase)");
  EXPECT_EQ(GridError("# comment\nx\\y, 0, 100\n0, 1000, 1000\n10, 1000, -3\n"),
            "grid.csv:4: depth -3 m at x = 10 m, y = 100 m is not below the water surface (z "
            "points down)");
  EXPECT_EQ(GridError("x\\y, 0, 100\n0, 1000, 1000\n"),
            "grid.csv:1: the x axis has 1 point(s); a grid needs at least 2");
  EXPECT_EQ(GridError("x\\y, 0\n"),
            "grid.csv:1: the first row must be a label and at least two y coordinates");
  EXPECT_EQ(GridError("# nothing\n"), "grid.csv: no grid (the file has no rows)");
  EXPECT_EQ(GridError("x\\y, 0, 100\n0, 1000, 1000\n10, 1000, 1000, 7\n"),
            "grid.csv:3: 3 depths for 2 y coordinates (a row is x and one depth per y)");
}

// The test scenario with its seabed written as `seabed`.
std::string WithSeabed(const std::string& seabed) {
  return test_cases::Edit(test_cases::kBase, "",
                          "seabed: {stiffness: 3.0e6, damping: 3.0e5, friction_velocity: 0.01}",
                          "seabed: " + seabed);
}

std::string GridScenarioError(const std::filesystem::path& file) {
  try {
    LoadScenario(file.string());
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(DepthGrid, AScenarioReadsItsGridBesideItAndChecksTheAnchorsOnIt) {
  const std::filesystem::path dir = testing::FreshDirectory("grid_scenario");
  // h = 1000 + 1e-5 x y: 1000 m under the test scenario's three anchors (on the axes),
  // deeper and shallower between them.
  WriteText(dir / "survey.csv",
            "x\\y, -3000, 0, 3000\n-3000, 1090, 1000, 910\n0, 1000, 1000, 1000\n"
            "3000, 910, 1000, 1090\n");
  WriteText(dir / "ok.yaml", WithSeabed("{grid: survey.csv}"));
  const Scenario s = LoadScenario((dir / "ok.yaml").string());
  EXPECT_EQ(s.mooring.seabed.grid.x.size(), 3u);
  EXPECT_NEAR(s.mooring.seabed.grid.depth[0], 1090.0, 0.0);

  // A grid 10 m shallower under line 1's anchor: the anchor is in the ground.
  WriteText(dir / "shallow.csv",
            "x\\y, -3000, 0, 3000\n-3000, 1000, 1000, 1000\n0, 1000, 1000, 1000\n"
            "3000, 985, 985, 985\n");
  WriteText(dir / "shallow.yaml", WithSeabed("{grid: shallow.csv}"));
  const std::string shallow = GridScenarioError(dir / "shallow.yaml");
  EXPECT_NE(shallow.find("mooring.lines[1].anchor: z = 1000 m is below the seabed there, at depth "
                         "990.25 m"),
            std::string::npos)
      << shallow;

  // A bad grid file: one line, at the key, naming the file's line.
  WriteText(dir / "holed.csv", "x\\y, -3000, 3000\n-3000, 1000, \n3000, 1000, 1000\n");
  WriteText(dir / "holed.yaml", WithSeabed("{grid: holed.csv}"));
  const std::string holed = GridScenarioError(dir / "holed.yaml");
  EXPECT_NE(holed.find("holed.yaml:4:"), std::string::npos) << holed;
  EXPECT_NE(holed.find("mooring.seabed.grid: "), std::string::npos) << holed;
  EXPECT_NE(holed.find("holed.csv:2: no depth at x = -3000 m, y = 3000 m (a hole in the grid)"),
            std::string::npos)
      << holed;
  EXPECT_EQ(holed.find('\n'), std::string::npos) << holed;

  WriteText(dir / "missing.yaml", WithSeabed("{grid: nowhere.csv}"));
  EXPECT_NE(GridScenarioError(dir / "missing.yaml").find("nowhere.csv: cannot read the depth grid"),
            std::string::npos);

  WriteText(dir / "both.yaml", WithSeabed("{grid: survey.csv, slope_deg: 1}"));
  EXPECT_NE(GridScenarioError(dir / "both.yaml")
                .find("mooring.seabed.grid: a depth grid cannot be combined with slope_deg"),
            std::string::npos);
}

std::string CurrentError(const std::string& text) {
  const std::string path = WriteText(testing::FreshDirectory("flow") / "flow.txt", text);
  try {
    ReadCurrentTable(path);
  } catch (const InputError& e) {
    std::string message = e.what();
    return message.substr(message.find("flow.txt"));
  }
  return "(no error)";
}

constexpr const char* kFlow =
    "# a profile that turns and strengthens in 10 minutes\n"
    "x: 0\ny: 0\ndepth: 0, 50\ntime: 0 600\n"
    "0, 0, 50, 600, 0.3, 0.0, 0.0\n"
    "0, 0,  0,   0, 0.5, 0.0, 0.0\n"
    "0 0 50 0 0.2 0 0\n"
    "0, 0,  0, 600, 0.8, 0.1, -0.01\r\n";

TEST(CurrentTableFile, ReadsItsAxesAndItsPointsInAnyOrder) {
  const mooring_fem::CurrentTable table =
      ReadCurrentTable(WriteText(testing::FreshDirectory("flow_read") / "flow.txt", kFlow));
  EXPECT_EQ(table.z, (std::vector<double>{0.0, 50.0}));
  EXPECT_EQ(table.t, (std::vector<double>{0.0, 600.0}));
  ASSERT_EQ(table.velocity.size(), 4u);
  // ((x y) depth) time order: (0, 0), (0, 600), (50, 0), (50, 600).
  EXPECT_EQ(table.velocity[0], Vec3(0.5, 0.0, 0.0));
  EXPECT_EQ(table.velocity[1], Vec3(0.8, 0.1, -0.01));
  EXPECT_EQ(table.velocity[2], Vec3(0.2, 0.0, 0.0));
  EXPECT_EQ(table.velocity[3], Vec3(0.3, 0.0, 0.0));
}

TEST(CurrentTableFile, EachBadTableIsOneLineNamingTheFileLineAndValue) {
  const std::string axes = "x: 0\ny: 0\ndepth: 0 50\ntime: 0\n";
  EXPECT_EQ(CurrentError("x: 0\ndepth: 0\n"),
            "flow.txt:2: expected the y: axis (the four axes x:, y:, depth:, time: come first, "
            "in this order)");
  EXPECT_EQ(CurrentError("x: 0\ny: 5 5\n"),
            "flow.txt:2: the y: axis must be numbers, strictly increasing");
  EXPECT_EQ(CurrentError("x: 0\ny:\n"), "flow.txt:2: the axis has no values");
  EXPECT_EQ(CurrentError(axes + "0 0 0 0 0.5 0\n"),
            "flow.txt:5: 6 fields; a row is x, y, depth, time and the velocity north, east, "
            "down [m/s]");
  EXPECT_EQ(CurrentError(axes + "0 0 20 0 0.5 0 0\n"),
            "flow.txt:5: depth: 20 is not on the table's depth: axis");
  EXPECT_EQ(CurrentError(axes + "0 0 0 0 0.5 0 0\n0 0 0 0 0.4 0 0\n"),
            "flow.txt:6: the point is given twice (also on line 5)");
  EXPECT_EQ(CurrentError(axes + "0 0 0 0 fast 0 0\n"), "flow.txt:5: 'fast' is not a number");
  EXPECT_EQ(CurrentError(axes + "0 0 0 0 0.5 0 0\n0 0 50 0 6 8 6\n"),
            "flow.txt:6: a current of 11.661903789690601 m/s must be <= 10 m/s (the strongest "
            "tidal races run at about 10 m/s)");
  EXPECT_EQ(CurrentError(axes + "0 0 0 0 0.5 0 0\n"),
            "flow.txt: 1 rows for a grid of 2 points; none for x 0, y 0, depth 50, time 0");
  EXPECT_EQ(CurrentError("x: 0\ny: 0\n"), "flow.txt: the depth: axis is missing");
}

TEST(CurrentTableFile, AScenarioReadsItsTableBesideItAndTheLinesFeelIt) {
  const std::filesystem::path dir = testing::FreshDirectory("flow_scenario");
  WriteText(dir / "flow.txt", kFlow);
  const auto with_current = [](const std::string& current) {
    return test_cases::Edit(test_cases::kBase, "",
                            "current:\n    direction_deg: 90\n    profile:\n      - {depth: 0, "
                            "speed: 0.2}\n      - {depth: 500, speed: 0.1}",
                            "current: " + current);
  };
  WriteText(dir / "ok.yaml", with_current("{file: flow.txt, period: 1200}"));
  const Scenario s = LoadScenario((dir / "ok.yaml").string());
  ASSERT_NE(s.mooring.current.table, nullptr);
  EXPECT_EQ(s.mooring.current.table->period, 1200.0);
  const mooring_fem::CurrentField field(s.mooring.current);
  // Half way in time and in depth; then repeated, and back to the start over the gap.
  EXPECT_LT((field.VelocityAt(300.0, Vec3(40.0, -7.0, 25.0)) -
             0.25 * (Vec3(0.5, 0, 0) + Vec3(0.8, 0.1, -0.01) + Vec3(0.2, 0, 0) + Vec3(0.3, 0, 0)))
                .norm(),
            1e-15);
  EXPECT_LT(
      (field.VelocityAt(1500.0, Vec3(0, 0, 0)) - field.VelocityAt(300.0, Vec3(0, 0, 0))).norm(),
      1e-15);
  EXPECT_LT((field.VelocityAt(900.0, Vec3(0, 0, 0)) - Vec3(0.65, 0.05, -0.005)).norm(), 1e-15);

  WriteText(dir / "short.yaml", with_current("{file: flow.txt, period: 600}"));
  EXPECT_NE(GridScenarioError(dir / "short.yaml")
                .find("mooring.current.period: " + (dir / "flow.txt").string() +
                      ": the period must be longer than the times it repeats (600 s)"),
            std::string::npos)
      << GridScenarioError(dir / "short.yaml");
  WriteText(dir / "missing.yaml", with_current("{file: nowhere.txt}"));
  EXPECT_NE(
      GridScenarioError(dir / "missing.yaml").find("nowhere.txt: cannot read the current table"),
      std::string::npos);
}

TEST(SlopingSeabed, TheAnchorsMustLieOnThePlane) {
  const std::filesystem::path dir = testing::FreshDirectory("slope_scenario");
  // 1 deg deepening toward east: line 2's anchor at y = 1950 is 34 m above the seabed.
  WriteText(dir / "slope.yaml", WithSeabed("{slope_deg: 1, slope_direction_deg: 90}"));
  const std::string error = GridScenarioError(dir / "slope.yaml");
  EXPECT_NE(error.find("mooring.lines[2].anchor: z = 1000 m is above the seabed there, at depth "
                       "1034.04 m"),
            std::string::npos)
      << error;
  WriteText(dir / "steep.yaml", WithSeabed("{slope_deg: 50}"));
  EXPECT_NE(GridScenarioError(dir / "steep.yaml")
                .find("mooring.seabed.slope_deg: 50 deg must be in [0, 45] (steeper than the "
                      "steepest continental slopes)"),
            std::string::npos);
}

}  // namespace
}  // namespace moorsim::scenarios
