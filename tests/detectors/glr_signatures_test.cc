// The GLR signatures computed from the hypothesis models point the way physics says: after
// line k parts the vessel drifts away from anchor k, so the intact observer's innovation
// (measured minus predicted) points away from that anchor.
#include "detectors/glr_signatures.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/error.h"
#include "scenarios/convert.h"
#include "scenarios/load.h"
#include "tests/detectors/observer_test_support.h"

namespace moorsim::detectors {
namespace {

TEST(GlrSignatures, PointAwayFromTheFailedLinesAnchor) {
  const mooring_fem::MooringParameters mooring = testing::SeedMooring();
  HypothesisBankOptions options;
  options.moored_heave = 0.47;
  const HypothesisBank bank(mooring, options);
  const std::vector<Vec3> sig =
      GlrSignatures(bank, SeedLowFrequencyModel(), EkfOptions{}, Vec3::Zero(), 1.0, 50);
  ASSERT_EQ(sig.size(), 8u);
  for (int k = 1; k <= 8; ++k) {
    const Vec3 anchor = mooring.lines[k - 1].anchor;
    const double away = std::atan2(-anchor.y(), -anchor.x());
    const Vec3& v = sig[k - 1];
    // The x-y part of the whitened innovation: S is near-isotropic in x and y for this
    // symmetric mooring, so whitening keeps the direction to within a few degrees; 15 deg
    // allows for the yaw coupling through the turret.
    double diff = std::atan2(v.y(), v.x()) - away;
    diff = std::remainder(diff, 2 * M_PI);
    EXPECT_LT(std::abs(diff), 15.0 * M_PI / 180.0) << "line " << k;
    // Large enough to matter: many whitened standard deviations on average over 50 samples.
    EXPECT_GT(v.head<2>().norm(), 0.5) << "line " << k;
  }
  // Opposite lines, opposite signatures (the mooring is symmetric).
  EXPECT_LT((sig[0].head<2>() + sig[2].head<2>()).norm(), 0.05 * sig[0].head<2>().norm());
  EXPECT_LT((sig[4].head<2>() + sig[6].head<2>()).norm(), 0.05 * sig[4].head<2>().norm());
}

TEST(GlrSignatures, BadArgumentsThrow) {
  const HypothesisBank bank(testing::SeedMooring());
  EXPECT_THROW(GlrSignatures(bank, SeedLowFrequencyModel(), {}, Vec3::Zero(), 0.0, 50), InputError);
  EXPECT_THROW(GlrSignatures(bank, SeedLowFrequencyModel(), {}, Vec3::Zero(), 1.0, 0), InputError);
}

}  // namespace
}  // namespace moorsim::detectors
