// Thrust allocation and thruster dynamics.
#include "vessel/thrusters.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"

namespace moorsim::vessel {
namespace {

TEST(ThrustAllocation, SeedLayoutProducesDemandsWithinItsRatings) {
  const ThrustAllocator allocator(SeedThrusters());
  // The aft pair's yaw lever is only +-8 m, so sway from the bow tunnel (90 m lever) must
  // be balanced in yaw by them: pure sway tops out near 0.11 MN. Demands inside that.
  for (const Vec3& tau : {Vec3(5e5, 0, 0), Vec3(0, 1e5, 0), Vec3(0, 0, 5e6), Vec3(-2e5, 5e4, -2e6),
                          Vec3(1e5, -5e4, 1e6)}) {
    const Allocation a = allocator.Allocate(tau);
    EXPECT_FALSE(a.saturated) << tau.transpose();
    // Three thrusters for three DOF: the pseudo-inverse is the inverse, tau is exact.
    EXPECT_LT((a.achieved - tau).norm(), 1e-6 * (1.0 + tau.norm())) << tau.transpose();
  }
}

TEST(ThrustAllocation, SurgeSplitsEquallyBetweenTheAftThrusters) {
  const Allocation a = ThrustAllocator(SeedThrusters()).Allocate(Vec3(8e5, 0, 0));
  EXPECT_NEAR(a.thrust(0), 4e5, 1e-3);
  EXPECT_NEAR(a.thrust(1), 4e5, 1e-3);
  EXPECT_NEAR(a.thrust(2), 0.0, 1e-3);
}

TEST(ThrustAllocation, SaturationClipsToTheRatings) {
  const ThrustAllocator allocator(SeedThrusters());
  const Allocation a = allocator.Allocate(Vec3(5e6, 0, 0));  // 2.5x what the aft pair gives
  EXPECT_TRUE(a.saturated);
  EXPECT_NEAR(a.thrust(0), 1e6, 1e-6);
  EXPECT_NEAR(a.thrust(1), 1e6, 1e-6);
  EXPECT_NEAR(a.achieved.x(), 2e6, 1e-3);
  const Allocation astern = allocator.Allocate(Vec3(-5e6, 0, 0));
  EXPECT_NEAR(astern.thrust(0), -0.6e6, 1e-6);
}

TEST(ThrustAllocation, SaturationKeepsTheDirectionOfTheCommand) {
  // A 5 MN sway command needs far more than the bow tunnel's 0.6 MN: everything is scaled
  // down together, so no yaw moment or surge force appears that was not asked for.
  const ThrustAllocator allocator(SeedThrusters());
  // Within each DOF's own capacity, but not all three together.
  const Vec3 cap(allocator.Capacity(Vec3::UnitX()).x(), allocator.Capacity(Vec3::UnitY()).y(),
                 allocator.Capacity(Vec3::UnitZ()).z());
  // Surge and yaw both load the aft pair: 90 % of each together overloads one of them.
  const Vec3 tau(0.9 * cap.x(), 0.0, 0.9 * cap.z());
  const Allocation a = allocator.Allocate(tau);
  EXPECT_TRUE(a.saturated);
  EXPECT_NEAR(a.achieved.y(), 0.0, 1e-6);
  const double s = a.achieved.x() / tau.x();
  EXPECT_GT(s, 0.0);
  EXPECT_LT(s, 1.0);
  EXPECT_NEAR(a.achieved.z(), s * tau.z(), 1e-6 * std::abs(tau.z()));
  double largest_ratio = 0.0;
  const std::vector<ThrusterSpec> thrusters = SeedThrusters();
  for (int i = 0; i < 3; ++i) {
    const ThrusterSpec& t = thrusters[i];
    largest_ratio = std::max(
        largest_ratio, a.thrust(i) > 0 ? a.thrust(i) / t.max_thrust : a.thrust(i) / t.min_thrust);
    EXPECT_LE(a.thrust(i), t.max_thrust * (1 + 1e-12));
    EXPECT_GE(a.thrust(i), t.min_thrust * (1 + 1e-12));
  }
  EXPECT_NEAR(largest_ratio, 1.0, 1e-12);  // the binding thruster is exactly at its rating
}

TEST(ThrustAllocation, AHugeSwayCommandDoesNotStarveSurge) {
  // The seed layout's pure sway capacity is ~0.11 MN (the bow tunnel's yaw moment must be
  // balanced by the aft pair's 16 m lever). A 50 MN sway command is clamped to it first, so
  // the surge part still gets through.
  const ThrustAllocator allocator(SeedThrusters());
  const double sway = allocator.Capacity(Vec3::UnitY()).y();
  EXPECT_GT(sway, 0.05e6);
  EXPECT_LT(sway, 0.2e6);
  const Allocation a = allocator.Allocate(Vec3(3e5, 5e7, 0.0));
  EXPECT_NEAR(a.achieved.y(), sway, 1e-6 * sway);
  EXPECT_NEAR(a.achieved.x(), 3e5, 1.0);
  EXPECT_NEAR(a.achieved.z(), 0.0, 1.0);
}

TEST(ThrustAllocation, WeightsShiftWorkBetweenRedundantThrusters) {
  // Four azimuths: redundant, so the weights decide. The weighted pseudo-inverse minimises
  // sum w_i |f_i|^2: doubling one thruster's weight halves its share relative to its twin.
  std::vector<ThrusterSpec> t;
  for (int i = 0; i < 4; ++i) {
    ThrusterSpec s;
    s.name = "az" + std::to_string(i);
    s.x = (i < 2 ? -80.0 : 80.0);
    s.y = (i % 2 == 0 ? -10.0 : 10.0);
    s.azimuth = true;
    s.max_thrust = 1e6;
    t.push_back(s);
  }
  t[1].weight = 2.0;
  const ThrustAllocator allocator(t);
  const Allocation a = allocator.Allocate(Vec3(3e5, 1e5, 0.0));
  EXPECT_LT((a.achieved - Vec3(3e5, 1e5, 0.0)).norm(), 1e-6 * 3e5);
  EXPECT_LT(a.thrust(1), a.thrust(0));
}

TEST(ThrustAllocation, RejectsBadLayouts) {
  std::vector<ThrusterSpec> t = SeedThrusters();
  t[0].max_thrust = -1.0;
  EXPECT_THROW(ThrustAllocator{t}, InputError);
  std::vector<ThrusterSpec> surge_only = SeedThrusters();
  surge_only.pop_back();  // no bow tunnel: nothing pushes sideways
  EXPECT_THROW(ThrustAllocator{surge_only}, InputError);
}

TEST(ThrusterDynamics, RateLimitedCommandAndFirstOrderResponse) {
  const std::vector<ThrusterSpec> t = SeedThrusters();
  ThrusterDynamics d(t);
  Eigen::VectorXd target = Eigen::VectorXd::Constant(3, 1e6);
  d.Step(target, 1.0);  // 0.2 MN/s rate limit: 0.2 MN after one second
  EXPECT_NEAR(d.command()(0), 0.2e6, 1e-6);
  for (int i = 0; i < 10; ++i) d.Step(target, 1.0);
  EXPECT_NEAR(d.command()(0), 1e6, 1e-6);
  // Delivered thrust relaxes toward the command with the 5 s time constant: integrate
  // exactly over one time constant and compare with 1 - exp(-1).
  Eigen::VectorXd f = Eigen::VectorXd::Zero(3);
  const double dt = 1e-3;
  for (int k = 0; k < 5000; ++k) f += dt * d.Derivative(f + 0.5 * dt * d.Derivative(f));
  EXPECT_NEAR(f(0) / 1e6, 1.0 - std::exp(-1.0), 1e-6);
}

}  // namespace
}  // namespace moorsim::vessel
