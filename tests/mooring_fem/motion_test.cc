// The prescribed rigid-body motion that drives the lines alone (line_simulation.h): the
// fairleads' velocity and acceleration are the time derivatives of their position (central
// differences), for harmonics in all six degrees of freedom and for a sampled series; the
// natural cubic spline through samples of a smooth motion follows it.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/error.h"
#include "mooring_fem/line_simulation.h"

namespace moorsim::mooring_fem {
namespace {

// Velocity and acceleration against central differences of the position (h = 1e-4 s:
// truncation ~h^2, round-off ~1e-16 / h^2 of the position).
void ExpectDerivativesOfThePosition(const PrescribedMotion& motion, double t, const Vec3& body) {
  const double h = 1e-4;
  const PointKinematics k = motion.FairleadAt(t, body);
  const Vec3 plus = motion.FairleadAt(t + h, body).position;
  const Vec3 minus = motion.FairleadAt(t - h, body).position;
  const Vec3 velocity = (plus - minus) / (2.0 * h);
  const Vec3 acceleration = (plus - 2.0 * k.position + minus) / (h * h);
  EXPECT_LT((k.velocity - velocity).norm(), 1e-6 * (1.0 + velocity.norm())) << "t " << t;
  EXPECT_LT((k.acceleration - acceleration).norm(), 2e-4 * (1.0 + acceleration.norm()))
      << "t " << t << "\n"
      << k.acceleration.transpose() << "\n"
      << acceleration.transpose();
}

TEST(PrescribedMotion, SixDegreesOfFreedomMoveTheFairleadsConsistently) {
  PrescribedMotion motion;
  motion.mean = {3.0, -2.0, 0.4};
  motion.components[PrescribedMotion::kSurge] = {{4.0, 80.0}};
  motion.components[PrescribedMotion::kSway] = {{2.0, 60.0}, {0.5, 9.0}};
  motion.components[PrescribedMotion::kHeave] = {{1.5, 11.0}};
  motion.components[PrescribedMotion::kRoll] = {{0.05, 13.0}};
  motion.components[PrescribedMotion::kPitch] = {{0.03, 10.0}};
  motion.components[PrescribedMotion::kYaw] = {{0.1, 120.0}};
  const Vec3 fairlead(60.0, -12.0, 14.0);
  for (const double t : {0.0, 3.7, 21.0, 64.5}) ExpectDerivativesOfThePosition(motion, t, fairlead);
  // At t = 0 every sine is zero: the fairlead where the mean pose puts it.
  EXPECT_LT(
      (motion.FairleadAt(0.0, fairlead).position - FairleadPosition(motion.mean, fairlead)).norm(),
      1e-12);
  // A positive roll (about x: the starboard side down) lowers a starboard fairlead (+z).
  PrescribedMotion roll;
  roll.components[PrescribedMotion::kRoll] = {{0.1, 40.0}};
  const Vec3 starboard(0.0, 20.0, 10.0);
  const PointKinematics k = roll.FairleadAt(10.0, starboard);  // roll 0.1 rad
  EXPECT_NEAR(k.position.z(), 10.0 * std::cos(0.1) + 20.0 * std::sin(0.1), 1e-12);
}

TEST(PrescribedMotion, ASampledSeriesFollowsTheMotionItSamples) {
  // 0.5 s samples of a heave and a yaw harmonic: the spline between them within 1e-4 of
  // the motion (h^4 error of the natural spline away from its ends).
  PrescribedMotion exact;
  exact.components[PrescribedMotion::kHeave] = {{2.0, 12.0}};
  exact.components[PrescribedMotion::kYaw] = {{0.05, 30.0}};
  MotionSeries series;
  for (int k = 0; k <= 240; ++k) {
    const double t = 0.5 * k;
    series.time.push_back(t);
    const double w = 2.0 * std::numbers::pi;
    const double values[6] = {0, 0, 2.0 * std::sin(w * t / 12.0),
                              0, 0, 0.05 * std::sin(w * t / 30.0)};
    for (int d = 0; d < 6; ++d) series.values[d].push_back(values[d]);
  }
  PrescribedMotion sampled;
  sampled.path = std::make_shared<const MotionSpline>(series);
  const Vec3 fairlead(20.0, 0.0, 12.0);
  for (const double t : {30.25, 47.1, 90.7}) {
    const PointKinematics a = sampled.FairleadAt(t, fairlead);
    const PointKinematics b = exact.FairleadAt(t, fairlead);
    EXPECT_LT((a.position - b.position).norm(), 1e-4) << t;
    EXPECT_LT((a.velocity - b.velocity).norm(), 1e-3) << t;
    EXPECT_LT((a.acceleration - b.acceleration).norm(), 1e-2) << t;
    ExpectDerivativesOfThePosition(sampled, t, fairlead);
  }
  // Held at the end values outside the samples.
  const PointKinematics after = sampled.FairleadAt(500.0, fairlead);
  EXPECT_EQ(after.velocity, Vec3::Zero());
  EXPECT_LT((after.position - sampled.FairleadAt(120.0, fairlead).position).norm(), 1e-12);
}

TEST(PrescribedMotion, ASeriesThatCannotBeInterpolatedIsRefused) {
  MotionSeries series;
  series.time = {0.0};
  for (auto& channel : series.values) channel = {0.0};
  EXPECT_THROW(MotionSpline{series}, InputError);
  series.time = {0.0, 1.0, 1.0};
  for (auto& channel : series.values) channel = {0.0, 0.0, 0.0};
  EXPECT_THROW(MotionSpline{series}, InputError);
}

}  // namespace
}  // namespace moorsim::mooring_fem
