// The seabed's shape: a plane and a bilinear depth grid against their closed forms, a
// grid's bad values named, and the FEM at rest on a grid that samples a plane equal to the
// FEM on the plane itself.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "core/error.h"
#include "mooring_fem/mooring_system.h"
#include "mooring_fem/seabed.h"
#include "test_support.h"

namespace moorsim::mooring_fem {
namespace {

constexpr double kSlopeDegree = std::numbers::pi / 180.0;

Seabed PlaneSeabed(double slope_deg, double direction_deg) {
  Seabed seabed;
  seabed.slope = slope_deg * kSlopeDegree;
  seabed.slope_direction = direction_deg * kSlopeDegree;
  return seabed;
}

// A grid sampling h(x, y) at the given axes.
template <class Depth>
DepthGrid SampledGrid(std::vector<double> x, std::vector<double> y, Depth h) {
  DepthGrid grid;
  grid.x = std::move(x);
  grid.y = std::move(y);
  for (double xi : grid.x) {
    for (double yj : grid.y) grid.depth.push_back(h(xi, yj));
  }
  return grid;
}

TEST(SeabedSurface, APlaneDeepensAlongItsDirectionByTheTangentOfItsSlope) {
  const SeabedSurface plane(PlaneSeabed(3.0, 60.0), 1000.0);
  const double rate = std::tan(3.0 * kSlopeDegree);
  const double d = 500.0;
  const SeabedPoint p =
      plane.At(d * std::cos(60.0 * kSlopeDegree), d * std::sin(60.0 * kSlopeDegree));
  EXPECT_NEAR(p.depth, 1000.0 + d * rate, 1e-9);
  EXPECT_NEAR(p.dx, rate * std::cos(60.0 * kSlopeDegree), 1e-15);
  EXPECT_NEAR(p.dy, rate * std::sin(60.0 * kSlopeDegree), 1e-15);
  EXPECT_EQ(p.dxy, 0.0);
  // Across the direction the depth does not change.
  EXPECT_NEAR(plane.DepthAt(-d * std::sin(60.0 * kSlopeDegree), d * std::cos(60.0 * kSlopeDegree)),
              1000.0, 1e-9);
  // Rising toward where it gets shallower: from the deep side back toward the origin.
  EXPECT_NEAR(plane.RiseAlong(
                  Vec3(d * std::cos(60.0 * kSlopeDegree), d * std::sin(60.0 * kSlopeDegree), 0.0),
                  Vec3::Zero()),
              3.0 * kSlopeDegree, 1e-12);
  EXPECT_TRUE(SeabedSurface(Seabed{}, 1000.0).flat());
  EXPECT_FALSE(plane.flat());
}

TEST(SeabedSurface, AGridIsBilinearInsideAndHeldAtItsEdgesBeyond) {
  // h = 1000 + 0.01 x - 0.02 y + 4e-6 x y is bilinear: the grid reproduces it, its
  // gradient and its twist exactly, in every cell.
  const auto h = [](double x, double y) { return 1000.0 + 0.01 * x - 0.02 * y + 4e-6 * x * y; };
  Seabed seabed;
  seabed.grid = SampledGrid({-3000.0, -500.0, 3000.0}, {-2000.0, 0.0, 100.0, 2000.0}, h);
  const SeabedSurface grid(seabed, 1000.0);
  for (const auto& [x, y] : std::vector<std::pair<double, double>>{
           {0.0, 0.0}, {-2999.0, 1999.0}, {1234.5, -876.5}, {-500.0, 50.0}}) {
    const SeabedPoint p = grid.At(x, y);
    EXPECT_NEAR(p.depth, h(x, y), 1e-9) << x << ", " << y;
    EXPECT_NEAR(p.dx, 0.01 + 4e-6 * y, 1e-12) << x << ", " << y;
    EXPECT_NEAR(p.dy, -0.02 + 4e-6 * x, 1e-12) << x << ", " << y;
    EXPECT_NEAR(p.dxy, 4e-6, 1e-15) << x << ", " << y;
  }
  // Beyond the grid the nearest edge's depth holds, with no slope across the edge.
  const SeabedPoint beyond = grid.At(5000.0, 1000.0);
  EXPECT_NEAR(beyond.depth, h(3000.0, 1000.0), 1e-9);
  EXPECT_EQ(beyond.dx, 0.0);
  EXPECT_NEAR(beyond.dy, -0.02 + 4e-6 * 3000.0, 1e-12);
  EXPECT_EQ(beyond.dxy, 0.0);
  EXPECT_NEAR(grid.DepthAt(-9000.0, -9000.0), h(-3000.0, -2000.0), 1e-9);
}

TEST(SeabedSurface, ABadGridOrSlopeIsOneMessageNamingIt) {
  const auto bad = [](const DepthGrid& grid) {
    Seabed seabed;
    seabed.grid = grid;
    seabed.grid.source = "bathymetry.csv";
    try {
      SeabedSurface(seabed, 1000.0);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  DepthGrid ok = SampledGrid({0.0, 100.0}, {0.0, 100.0}, [](double, double) { return 900.0; });
  EXPECT_EQ(bad(ok), "accepted");
  DepthGrid g = ok;
  g.x = {100.0, 0.0};
  EXPECT_EQ(
      bad(g),
      "seabed grid bathymetry.csv: x = 0 m does not follow x = 100 m (the axis must increase)");
  g = ok;
  g.depth[3] = std::nan("");
  EXPECT_EQ(bad(g),
            "seabed grid bathymetry.csv: no depth at x = 100 m, y = 100 m (a hole in the grid)");
  g = ok;
  g.depth[1] = -5.0;
  EXPECT_EQ(bad(g),
            "seabed grid bathymetry.csv: depth -5 m at x = 0 m, y = 100 m is not below the water "
            "surface (z points down)");
  g = ok;
  g.y = {0.0};
  EXPECT_EQ(bad(g),
            "seabed grid bathymetry.csv: the y axis has 1 point(s); a grid needs at least 2");
  int row = 7;
  g = ok;
  g.depth[2] = 0.0;
  DepthGridProblem(g, &row);
  EXPECT_EQ(row, 1);  // the second x row
  EXPECT_THROW(SeabedSurface(PlaneSeabed(90.0, 0.0), 1000.0), InputError);
}

// One chain line whose anchor is on the seabed given, settled at rest; the fairlead force.
Vec3 SettledFairleadForce(const Seabed& seabed) {
  MooringParameters spec;
  spec.water.depth = 1000.0;
  spec.seabed = seabed;
  spec.line_types = {testing::ChainType()};
  const double anchor_x = 1800.0;
  const double anchor_z = SeabedSurface(seabed, 1000.0).DepthAt(anchor_x, 300.0);
  spec.lines.push_back(LineParameters::Uniform(
      1, "chain", 2150.0, 60, Vec3(anchor_x, 300.0, anchor_z), Vec3(20.0, 0.0, 12.0)));
  MooringSystem mooring(spec);
  PointKinematics fairlead;
  fairlead.position = Vec3(20.0, 0.0, 12.0);
  const std::vector<Vec3> positions = {fairlead.position};
  std::vector<double> x(mooring.StateSize());
  mooring.CatenaryState(positions, x.data());
  mooring.SettleStatic(positions, x.data());
  const std::vector<PointKinematics> fairleads = {fairlead};
  return mooring.LineLoads(x.data(), fairleads)[0].fairlead_force;
}

TEST(SeabedSurface, TheFemAtRestOnAGridSamplingAPlaneIsTheFemOnThePlane) {
  // A plane 3 deg deep toward 200 deg, sampled on a coarse grid (one cell under the
  // whole line) and on a fine one: the same surface, the same equilibrium.
  const Seabed plane = PlaneSeabed(3.0, 200.0);
  const SeabedSurface surface(plane, 1000.0);
  const Vec3 on_plane = SettledFairleadForce(plane);
  for (const double step : {5000.0, 250.0}) {
    std::vector<double> axis;
    for (double v = -5000.0; v <= 5000.0 + 1e-9; v += step) axis.push_back(v);
    Seabed gridded;
    gridded.grid =
        SampledGrid(axis, axis, [&](double x, double y) { return surface.DepthAt(x, y); });
    const Vec3 on_grid = SettledFairleadForce(gridded);
    EXPECT_LT((on_grid - on_plane).norm(), 1e-6 * on_plane.norm()) << "grid step " << step;
  }
  // And the slope matters: the same line on a flat seabed pulls differently.
  EXPECT_GT((SettledFairleadForce(Seabed{}) - on_plane).norm(), 1e-2 * on_plane.norm());
}

}  // namespace
}  // namespace moorsim::mooring_fem
