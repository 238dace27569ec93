// The standards' design tensions and checks (analysis/design_tension.h), worked by hand.
#include "analysis/design_tension.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace moorsim::analysis {
namespace {

TEST(DesignCheck, ApiRp2skSafetyFactorsOnTheMpm) {
  const LineExtreme line{.mpm = 6.0e6, .mean = 4.0e6, .mbl = 1.2e7};
  const DesignCheck intact = CheckLine(line, DesignStandard::kApiRp2sk, DesignCondition::kIntact);
  EXPECT_EQ(intact.design_tension, 6.0e6);
  EXPECT_DOUBLE_EQ(intact.safety_factor, 2.0);
  EXPECT_DOUBLE_EQ(intact.required_factor, 1.67);
  EXPECT_DOUBLE_EQ(intact.utilisation, 1.67 / 2.0);
  EXPECT_TRUE(intact.pass);
  const LineExtreme heavy{.mpm = 1.0e7, .mean = 4.0e6, .mbl = 1.2e7};
  EXPECT_FALSE(
      CheckLine(heavy, DesignStandard::kApiRp2sk, DesignCondition::kDamaged).pass);  // 1.2 < 1.25
  EXPECT_TRUE(
      CheckLine(heavy, DesignStandard::kApiRp2sk, DesignCondition::kTransient).pass);  // 1.2 > 1.05
}

TEST(DesignCheck, DnvOsE301PartialFactorsOnMeanAndDynamicTension) {
  const LineExtreme line{.mpm = 6.0e6, .mean = 4.0e6, .mbl = 1.2e7};
  // ULS, class 1: 1.1 * 4 + 1.5 * 2 = 7.4 MN against 0.95 * 12 = 11.4 MN.
  const DesignCheck uls = CheckLine(line, DesignStandard::kDnvOsE301, DesignCondition::kIntact, 1);
  EXPECT_NEAR(uls.design_tension, 7.4e6, 1e-6);
  EXPECT_NEAR(uls.utilisation, 7.4 / 11.4, 1e-12);
  EXPECT_TRUE(uls.pass);
  // Class 2: 1.4 * 4 + 2.1 * 2 = 9.8 MN.
  EXPECT_NEAR(
      CheckLine(line, DesignStandard::kDnvOsE301, DesignCondition::kIntact, 2).design_tension,
      9.8e6, 1e-6);
  // ALS, class 2: 1.0 * 4 + 1.25 * 2 = 6.5 MN.
  EXPECT_NEAR(
      CheckLine(line, DesignStandard::kDnvOsE301, DesignCondition::kDamaged, 2).design_tension,
      6.5e6, 1e-6);
  EXPECT_THROW(CheckLine(line, DesignStandard::kDnvOsE301, DesignCondition::kIntact, 3),
               std::invalid_argument);
  EXPECT_THROW(CheckLine({.mpm = 1.0, .mean = 1.0, .mbl = 0.0}, DesignStandard::kApiRp2sk,
                         DesignCondition::kIntact),
               std::invalid_argument);
}

}  // namespace
}  // namespace moorsim::analysis
