// A current given as a table over north, east, depth and time (mooring_fem::CurrentTable
// through CurrentField): quadrilinear interpolation reproduces a field that is linear in
// each coordinate exactly, with its gradient; the table is held beyond its ends; with a
// period it repeats, closing the gap from its last time back to its first; a bad table
// is refused naming its source.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>

#include "core/error.h"
#include "mooring_fem/environment.h"

namespace moorsim::mooring_fem {
namespace {

// A field multilinear in (x, y, z, t): what quadrilinear interpolation holds exactly.
Vec3 Field(double x, double y, double z, double t) {
  return Vec3(0.5 + 1e-3 * x - 2e-3 * z + 1e-6 * x * z + 0.01 * t,
              -0.2 + 4e-3 * y + 1e-5 * y * z - 1e-4 * x * t,
              1e-3 * z - 5e-4 * y + 2e-7 * x * y * z);
}

std::shared_ptr<CurrentTable> TableOf(double period) {
  auto table = std::make_shared<CurrentTable>();
  table->x = {-100.0, 0.0, 250.0};
  table->y = {-50.0, 50.0};
  table->z = {0.0, 30.0, 80.0, 200.0};
  table->t = {0.0, 10.0, 30.0};
  for (double x : table->x) {
    for (double y : table->y) {
      for (double z : table->z) {
        for (double t : table->t) table->velocity.push_back(Field(x, y, z, t));
      }
    }
  }
  table->period = period;
  table->source = "test table";
  return table;
}

CurrentField FieldOf(std::shared_ptr<CurrentTable> table) {
  CurrentProfile profile;
  profile.table = std::move(table);
  return CurrentField(profile);
}

TEST(CurrentTable, ReproducesAMultilinearFieldAndItsGradient) {
  const CurrentField field = FieldOf(TableOf(0.0));
  EXPECT_FALSE(field.empty());
  for (const Vec3& r : {Vec3(-70.0, 12.0, 5.0), Vec3(130.0, -49.0, 150.0), Vec3(0.0, 0.0, 30.0),
                        Vec3(249.0, 20.0, 79.0)}) {
    for (double t : {0.0, 4.0, 17.5, 29.0}) {
      const Vec3 expected = Field(r.x(), r.y(), r.z(), t);
      EXPECT_LT((field.VelocityAt(t, r) - expected).norm(), 1e-12) << r.transpose() << " " << t;
      // The gradient against central differences of the field itself (exact for a field
      // linear along each axis, away from the cell edges).
      const Mat3 gradient = field.GradientAt(t, r + Vec3(1e-3, 1e-3, 1e-3));
      for (int d = 0; d < 3; ++d) {
        Vec3 h = Vec3::Zero();
        h(d) = 1e-4;
        const Vec3 p = r + Vec3(1e-3, 1e-3, 1e-3);
        const Vec3 fd = (Field(p.x() + h.x(), p.y() + h.y(), p.z() + h.z(), t) -
                         Field(p.x() - h.x(), p.y() - h.y(), p.z() - h.z(), t)) /
                        2e-4;
        EXPECT_LT((gradient.col(d) - fd).norm(), 1e-9) << d;
      }
    }
  }
}

TEST(CurrentTable, IsHeldBeyondItsEnds) {
  const CurrentField field = FieldOf(TableOf(0.0));
  EXPECT_LT(
      (field.VelocityAt(-5.0, Vec3(-500.0, 80.0, -3.0)) - Field(-100.0, 50.0, 0.0, 0.0)).norm(),
      1e-12);
  EXPECT_LT(
      (field.VelocityAt(99.0, Vec3(900.0, -70.0, 600.0)) - Field(250.0, -50.0, 200.0, 30.0)).norm(),
      1e-12);
  // Nothing changes with position beyond the ends: the gradient's columns are zero there.
  EXPECT_EQ(field.GradientAt(99.0, Vec3(900.0, -70.0, 600.0)), Mat3::Zero());
}

TEST(CurrentTable, RepeatsWithItsPeriod) {
  const CurrentField field = FieldOf(TableOf(40.0));
  const Vec3 r(10.0, 5.0, 50.0);
  for (double t : {3.0, 12.0, 29.0}) {
    EXPECT_LT((field.VelocityAt(t + 40.0, r) - field.VelocityAt(t, r)).norm(), 1e-12);
    EXPECT_LT((field.VelocityAt(t - 80.0, r) - field.VelocityAt(t, r)).norm(), 1e-12);
  }
  // From the last time (30 s) back to the first over the gap to the period's end (40 s).
  const Vec3 last = Field(r.x(), r.y(), r.z(), 30.0);
  const Vec3 first = Field(r.x(), r.y(), r.z(), 0.0);
  EXPECT_LT((field.VelocityAt(35.0, r) - 0.5 * (last + first)).norm(), 1e-12);
  EXPECT_LT((field.VelocityAt(40.0, r) - first).norm(), 1e-12);
}

TEST(CurrentTable, ABadTableIsRefusedNamingItsSource) {
  const auto message = [](const CurrentTable& table) {
    try {
      CheckCurrentTable(table);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  EXPECT_EQ(message(*TableOf(0.0)), "(no error)");
  CurrentTable table = *TableOf(0.0);
  table.z = {0.0, 30.0, 30.0, 200.0};
  EXPECT_EQ(message(table),
            "test table: the depth axis must hold finite values, strictly increasing");
  table = *TableOf(0.0);
  table.velocity.pop_back();
  EXPECT_EQ(message(table), "test table: 71 velocities for a grid of 72 points");
  table = *TableOf(30.0);
  EXPECT_EQ(message(table),
            "test table: the period must be longer than the times it repeats (30 s)");
  table = *TableOf(0.0);
  table.velocity[5].y() = std::nan("");
  EXPECT_EQ(message(table), "test table: a velocity is not finite");
  table = *TableOf(0.0);
  table.velocity[7] = Vec3(3.0, 4.0, 12.0);
  EXPECT_EQ(message(table),
            "test table: a current of 13 m/s must be <= 10 m/s (the strongest tidal races run at "
            "about 10 m/s)");
}

}  // namespace
}  // namespace moorsim::mooring_fem
