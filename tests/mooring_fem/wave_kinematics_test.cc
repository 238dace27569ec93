// The lines' wave kinematics against closed forms written here: the finite-depth dispersion
// relation, a single AiryWave wave's velocity and acceleration from its potential (cosh/sinh as
// the textbook writes them), the deep- and shallow-water limits, incompressibility, the
// acceleration as the time derivative of the velocity, Wheeler stretching's surface and
// seabed, and the gradients against finite differences.
#include "mooring_fem/wave_kinematics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "core/error.h"

namespace moorsim::mooring_fem {
namespace {

constexpr double kWaveGravity = 9.81;

TEST(WaveNumber, SolvesTheFiniteDepthDispersionRelationWithItsLimits) {
  for (const double depth : {5.0, 30.0, 150.0, 1000.0}) {
    for (const double omega : {0.1, 0.3, 0.7, 1.5, 3.0}) {
      const double k = WaveKinematics::WaveNumber(omega, depth, kWaveGravity);
      EXPECT_NEAR(kWaveGravity * k * std::tanh(k * depth), omega * omega, 1e-12 * omega * omega)
          << depth << " m, " << omega << " rad/s";
    }
  }
  // Deep water: omega^2 / g to the bit where tanh(k h) is 1 in double precision.
  EXPECT_EQ(WaveKinematics::WaveNumber(0.45, 1000.0, kWaveGravity), 0.45 * 0.45 / kWaveGravity);
  // Shallow water: k -> omega / sqrt(g h) (k h = 0.02 here: within 0.01 %).
  EXPECT_NEAR(WaveKinematics::WaveNumber(0.01, 40.0, kWaveGravity),
              0.01 / std::sqrt(kWaveGravity * 40.0), 1e-4 * 0.01 / std::sqrt(kWaveGravity * 40.0));
}

// One wave of amplitude a, frequency w, toward `direction`: its velocity potential
// phi = -g a / w cosh(k (zeta + h)) / cosh(k h) sin(chi), zeta up from the mean surface
// (Faltinsen 1990, table 2.1), and the water's velocity as phi's gradient by central
// differences. The potential itself is pinned by the linear free-surface conditions
// (OneWavesPotentialMeetsTheFreeSurfaceConditions).
struct AiryWave {
  double a, w, direction, phase, h;
  double k() const { return WaveKinematics::WaveNumber(w, h, kWaveGravity); }
  double Chi(double t, double x, double y) const {
    return w * t - k() * (x * std::cos(direction) + y * std::sin(direction)) + phase;
  }
  double Elevation(double t, double x, double y) const { return a * std::cos(Chi(t, x, y)); }
  double Potential(double t, double x, double y, double zeta) const {
    return -kWaveGravity * a / w * std::cosh(k() * (zeta + h)) / std::cosh(k() * h) *
           std::sin(Chi(t, x, y));
  }
  // NED velocity at r: (d phi/dx, d phi/dy, -d phi/dzeta).
  Vec3 Velocity(double t, const Vec3& r) const {
    const double e = 1e-4;
    const double zeta = -r.z();
    return Vec3(
        (Potential(t, r.x() + e, r.y(), zeta) - Potential(t, r.x() - e, r.y(), zeta)) / (2 * e),
        (Potential(t, r.x(), r.y() + e, zeta) - Potential(t, r.x(), r.y() - e, zeta)) / (2 * e),
        -(Potential(t, r.x(), r.y(), zeta + e) - Potential(t, r.x(), r.y(), zeta - e)) / (2 * e));
  }
};

TEST(WaveKinematics, OneWavesPotentialMeetsTheFreeSurfaceConditions) {
  // Linearised at the mean surface: d eta/dt = d phi/d zeta (kinematic) and
  // g eta = -d phi/dt (dynamic).
  const AiryWave wave{1.5, 0.5, 0.7, 0.3, 30.0};
  const double e = 1e-5;
  for (const double t : {0.0, 2.0, 7.5}) {
    const double deta_dt = (wave.Elevation(t + e, 3, 4) - wave.Elevation(t - e, 3, 4)) / (2 * e);
    const double dphi_dz = (wave.Potential(t, 3, 4, e) - wave.Potential(t, 3, 4, -e)) / (2 * e);
    const double dphi_dt =
        (wave.Potential(t + e, 3, 4, 0) - wave.Potential(t - e, 3, 4, 0)) / (2 * e);
    EXPECT_NEAR(deta_dt, dphi_dz, 1e-8);
    EXPECT_NEAR(kWaveGravity * wave.Elevation(t, 3, 4), -dphi_dt, 1e-7);
  }
}

TEST(WaveKinematics, OneWaveIsTheGradientOfItsPotential) {
  // Shallow (h = 30 m, k h = 0.6) and deep (h = 1000 m) water, stretching off, points below
  // the trough.
  for (const double h : {30.0, 1000.0}) {
    const AiryWave wave{1.5, 0.5, 0.7, 0.3, h};
    const WaveKinematics kin({{wave.w, wave.a, wave.phase, wave.direction}}, h, kWaveGravity,
                             WaveStretching::kNone);
    for (const Vec3& r : {Vec3(10.0, -40.0, 3.0), Vec3(-200.0, 75.0, 12.0), Vec3(0, 0, h - 1)}) {
      for (const double t : {0.0, 3.7, 101.2}) {
        const WaterMotion m = kin.At(t, r, false);
        const Vec3 expected = wave.Velocity(t, r);
        // Below 1e-5 m/s a component is left out (at 999 m in 1000 m of water).
        EXPECT_LT((m.velocity - expected).norm(), 1e-5 * (1.0 + expected.norm()))
            << h << " m deep at z = " << r.z() << ", t = " << t;
        // The acceleration is d/dt of the velocity at the point (central difference).
        const double dt = 1e-3;
        const Vec3 dudt = (wave.Velocity(t + dt, r) - wave.Velocity(t - dt, r)) / (2.0 * dt);
        EXPECT_LT((m.acceleration - dudt).norm(), 1e-6 * (1.0 + dudt.norm()));
      }
    }
  }
}

TEST(WaveKinematics, DeepWaterDecaysAsExpKzAndTheSeabedStopsVerticalMotion) {
  const double a = 1.0, w = 0.9;
  const WaveKinematics deep({{w, a, 0.0, 0.0}}, 1000.0, kWaveGravity, WaveStretching::kNone);
  const double k = w * w / kWaveGravity;
  for (const double z : {0.0, 10.0, 50.0, 120.0}) {
    // At chi = 0 (t = 0 at the origin): horizontal velocity a w e^{-k z}.
    EXPECT_NEAR(deep.At(0.0, Vec3(0, 0, z), false).velocity.x(), a * w * std::exp(-k * z), 1e-12);
  }
  // Below where every component is negligible the water is still (nothing computed).
  EXPECT_EQ(deep.At(0.0, Vec3(0, 0, 900.0), false).velocity, Vec3::Zero());
  // A shallow seabed: no vertical velocity on it, at any phase.
  const WaveKinematics shallow({{0.6, 1.0, 0.0, 0.0}}, 25.0, kWaveGravity,
                               WaveStretching::kWheeler);
  for (const double t : {0.0, 1.0, 2.5, 4.0}) {
    EXPECT_NEAR(shallow.At(t, Vec3(5.0, 0.0, 25.0), false).velocity.z(), 0.0, 1e-12);
  }
}

// A three-component short-crested sea in 60 m of water.
std::vector<WaveTrain> ThreeComponentSea() {
  return {{0.5, 1.2, 0.1, 0.2}, {0.8, 0.7, 2.0, -0.4}, {1.3, 0.3, 4.0, 0.9}};
}

TEST(WaveKinematics, WheelerStretchingPutsTheMeanSurfaceValuesAtTheCrest) {
  const WaveKinematics stretched(ThreeComponentSea(), 60.0, kWaveGravity, WaveStretching::kWheeler);
  const WaveKinematics linear(ThreeComponentSea(), 60.0, kWaveGravity, WaveStretching::kNone);
  int crests = 0;
  for (double t = 0.0; t < 20.0; t += 0.5) {
    const double eta = stretched.Elevation(t, 12.0, -7.0);
    // Just under the instantaneous surface, stretched = linear at the mean surface (which
    // is in the water where the surface is above it).
    if (eta > 0.0) {
      ++crests;
      const Vec3 at_surface(12.0, -7.0, -eta + 1e-9);
      const Vec3 at_mean(12.0, -7.0, 0.0);
      EXPECT_LT(
          (stretched.At(t, at_surface, false).velocity - linear.At(t, at_mean, false).velocity)
              .norm(),
          1e-8);
    }
    // Above the surface the water does not move the point.
    EXPECT_EQ(stretched.At(t, Vec3(12.0, -7.0, -eta - 0.01), false).velocity, Vec3::Zero());
  }
  EXPECT_GE(crests, 10);
}

TEST(WaveKinematics, TheVelocityIsDivergenceFreeAndTheGradientsAreTheFiniteDifferences) {
  for (const WaveStretching stretching : {WaveStretching::kNone, WaveStretching::kWheeler}) {
    const WaveKinematics kin(ThreeComponentSea(), 60.0, kWaveGravity, stretching);
    for (const Vec3& r : {Vec3(3.0, 4.0, 5.0), Vec3(-30.0, 12.0, 25.0), Vec3(7.0, 7.0, 55.0)}) {
      const double t = 3.3;
      const WaterMotion m = kin.At(t, r, true);
      if (stretching == WaveStretching::kNone) {
        // Linear theory below the trough: incompressible.
        EXPECT_NEAR(m.d_velocity.trace(), 0.0, 1e-12) << r.transpose();
      }
      for (int j = 0; j < 3; ++j) {
        const double step = 1e-5;
        Vec3 plus = r, minus = r;
        plus[j] += step;
        minus[j] -= step;
        const WaterMotion p = kin.At(t, plus, false);
        const WaterMotion q = kin.At(t, minus, false);
        const Vec3 dv = (p.velocity - q.velocity) / (2.0 * step);
        const Vec3 da = (p.acceleration - q.acceleration) / (2.0 * step);
        EXPECT_LT((m.d_velocity.col(j) - dv).norm(), 1e-8) << r.transpose() << " column " << j;
        EXPECT_LT((m.d_acceleration.col(j) - da).norm(), 1e-8) << r.transpose() << " column " << j;
      }
    }
  }
}

TEST(WaveKinematics, BadComponentsAreRefused) {
  EXPECT_THROW(WaveKinematics({{0.0, 1.0, 0.0, 0.0}}, 100.0, kWaveGravity, WaveStretching::kNone),
               InputError);
  EXPECT_THROW(WaveKinematics({{1.0, -1.0, 0.0, 0.0}}, 100.0, kWaveGravity, WaveStretching::kNone),
               InputError);
  EXPECT_THROW(WaveKinematics(ThreeComponentSea(), 0.0, kWaveGravity, WaveStretching::kNone),
               InputError);
}

}  // namespace
}  // namespace moorsim::mooring_fem
