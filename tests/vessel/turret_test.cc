// The turret's bearing moment (vessel/turret.h): its derivatives against central finite
// differences, its limits (Coulomb at high rate, viscous near zero) and the moment of a load
// about the turret axis against the cross product.
#include "vessel/turret.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "core/error.h"

namespace moorsim::vessel {
namespace {

TurretParameters Friction() {
  TurretParameters t;
  t.bearing = TurretBearing::kFriction;
  t.friction_coefficient = 0.01;
  t.bearing_radius = 20.0;
  t.damping = 1.0e8;
  t.slip_rate = 1.0e-3;
  return t;
}

TEST(BearingMoment, DerivativesMatchFiniteDifferences) {
  const TurretParameters t = Friction();
  const Vec3 F(3.0e6, -1.0e6, 4.0e7);
  for (const double rate : {-3e-3, -2e-4, 0.0, 5e-4, 2e-3}) {
    double d_rate = 0.0;
    Vec3 d_force;
    BearingMoment(t, rate, F, &d_rate, &d_force);
    const double h = 1e-7;
    const double numeric =
        (BearingMoment(t, rate + h, F) - BearingMoment(t, rate - h, F)) / (2 * h);
    EXPECT_NEAR(d_rate, numeric, 1e-6 * std::abs(numeric)) << "rate " << rate;
    for (int k = 0; k < 3; ++k) {
      Vec3 p = F, m = F;
      p(k) += 10.0;
      m(k) -= 10.0;
      const double dk = (BearingMoment(t, rate, p) - BearingMoment(t, rate, m)) / 20.0;
      EXPECT_NEAR(d_force(k), dk, 1e-6 * std::abs(dk) + 1e-12) << "rate " << rate << " k " << k;
    }
  }
}

TEST(BearingMoment, CoulombAtHighRateViscousNearZeroNoneLocked) {
  TurretParameters t = Friction();
  t.damping = 0.0;
  const Vec3 F(3.0e6, -4.0e6, 4.0e7);  // |F_h| = 5 MN
  const double coulomb = 0.01 * 20.0 * (4.0e7 + 5.0e6);
  EXPECT_NEAR(BearingMoment(t, 0.1, F), coulomb, 1e-6 * coulomb);  // tanh(100) = 1
  EXPECT_NEAR(BearingMoment(t, -0.1, F), -coulomb, 1e-6 * coulomb);
  EXPECT_EQ(BearingMoment(t, 0.0, F), 0.0);
  // Below the slip rate the moment grows linearly: the breakaway moment over the slip rate.
  EXPECT_NEAR(BearingMoment(t, 1e-6, F), coulomb * 1e-3, 1e-6 * coulomb * 1e-3);
  t.bearing = TurretBearing::kFree;
  t.damping = 2.0e8;
  EXPECT_DOUBLE_EQ(BearingMoment(t, 0.01, F), 2.0e6);
  t.bearing = TurretBearing::kLocked;
  EXPECT_EQ(BearingMoment(t, 0.01, F), 0.0);
}

TEST(MomentAboutTurret, IsTheLoadsMomentAboutTheTurretCentre) {
  TurretParameters t;
  t.x = 60.0;
  t.y = -3.0;
  // A force F at body point r: the moment about the origin is r x F; about the turret
  // centre c it is (r - c) x F.
  const Vec3 r(75.0, 12.0, 10.0), F(2.0e6, -1.0e6, 3.0e6);
  Vec6 tau;
  tau << F, r.cross(F);
  const Vec3 c(t.x, t.y, 0.0);
  EXPECT_NEAR(MomentAboutTurret(t, tau), (r - c).cross(F).z(), 1e-6);
}

TEST(TurretBearing, NamesRoundTripAndUnknownIsNone) {
  for (const TurretBearing b :
       {TurretBearing::kLocked, TurretBearing::kFree, TurretBearing::kFriction}) {
    EXPECT_EQ(ParseChoice<TurretBearing>(ChoiceName(b)), b);
  }
  EXPECT_EQ(ParseChoice<TurretBearing>("sliding"), std::nullopt);
}

}  // namespace
}  // namespace moorsim::vessel
