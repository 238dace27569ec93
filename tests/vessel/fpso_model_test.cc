// The seed FPSO's low-frequency model from its WAMIT data: free-decay periods in heave,
// roll and pitch against sqrt((M + A) / C), and the damping rule.
#include "vessel/fpso_model.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <numbers>

#include "free_vessel.h"
#include "tests/vessel/fpso_hydro.h"

namespace moorsim::vessel {
namespace {

using test_data::Fpso;

TEST(FpsoModel, FreeDecayPeriodsMatchTheDiagonalEstimate) {
  const VesselParameters p = LowFrequencyVessel(Fpso(), SeedFpsoMass());
  const VesselModel model(p);
  const Mat6 M = model.mass();
  for (int dof : {2, 3, 4}) {  // heave, roll, pitch
    const double estimate = 2.0 * std::numbers::pi * std::sqrt(M(dof, dof) / p.restoring(dof, dof));
    Vec6 eta0 = Vec6::Zero();
    eta0(dof) = dof == 2 ? 0.2 : 0.01;  // 0.2 m or 0.6 deg: linear range
    const double period = testing::DecayPeriod(model, eta0, dof, 12.0 * estimate);
    // The bar: 3 %. Couplings (heave-pitch through C35 and A35, roll-sway through the
    // CG height and A24) and the damping (10 % of critical lengthens a period by 0.5 %)
    // move the decay period off the one-DOF estimate by less than that.
    EXPECT_NEAR(period, estimate, 0.03 * estimate) << "DOF " << dof + 1;
    RecordProperty("period_dof" + std::to_string(dof + 1), std::to_string(period));
  }
}

TEST(FpsoModel, DampingRuleOfTheReferenceSheet) {
  const VesselParameters p = LowFrequencyVessel(Fpso(), SeedFpsoMass());
  const Mat6 M = p.rigid_body_mass + p.added_mass;
  EXPECT_DOUBLE_EQ(p.linear_damping(0, 0), M(0, 0) / 50.0);
  EXPECT_DOUBLE_EQ(p.linear_damping(1, 1), M(1, 1) / 100.0);
  EXPECT_DOUBLE_EQ(p.linear_damping(5, 5), M(5, 5) / 20.0);
  // Roll at 7 % of critical.
  EXPECT_NEAR(p.linear_damping(3, 3) / (2.0 * std::sqrt(M(3, 3) * p.restoring(3, 3))), 0.07, 1e-12);
  // Mass: rho x displaced volume (docs/design.md section 9: 1.0041e8 kg).
  EXPECT_NEAR(SeedFpsoMass().mass, 1.0041e8, 1e4);
}

}  // namespace
}  // namespace moorsim::vessel
