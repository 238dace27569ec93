// The vectorised sin and cos kernel against the C library.
#include "core/sincos.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

namespace moorsim::internal {
namespace {

TEST(SinCos, MatchesTheLibraryToRounding) {
  // glibc's sin and cos are within 1 ulp of the exact values; the kernel's documented bound
  // is 2.3e-16 absolute (≤ 2 ulp of values up to 1), over angles inside the exact reduction
  // (up to 1.6e6 rad), just past it and far beyond (std::sin fallback).
  std::mt19937_64 engine(42);
  for (const double range : {1.0, 100.0, 4e4, 1.6e6, 1e7, 1e12}) {
    std::uniform_real_distribution<double> uniform(-range, range);
    std::vector<double> angle(4096);
    for (double& value : angle) value = uniform(engine);
    std::vector<double> sine(angle.size());
    std::vector<double> cosine(angle.size());
    SinCos(angle.data(), sine.data(), cosine.data(), static_cast<int>(angle.size()));
    for (std::size_t l = 0; l < angle.size(); ++l) {
      ASSERT_NEAR(sine[l], std::sin(angle[l]), 2.3e-16) << angle[l];
      ASSERT_NEAR(cosine[l], std::cos(angle[l]), 2.3e-16) << angle[l];
    }
  }
  const double special[] = {0.0,
                            std::numbers::pi / 4.0,
                            std::numbers::pi / 2.0,
                            -std::numbers::pi,
                            std::numeric_limits<double>::quiet_NaN(),
                            std::numeric_limits<double>::infinity()};
  double sine[6];
  double cosine[6];
  SinCos(special, sine, cosine, 6);
  for (int l = 0; l < 4; ++l) {
    EXPECT_NEAR(sine[l], std::sin(special[l]), 2.3e-16) << special[l];
    EXPECT_NEAR(cosine[l], std::cos(special[l]), 2.3e-16) << special[l];
  }
  for (int l = 4; l < 6; ++l) {
    EXPECT_TRUE(std::isnan(sine[l]) && std::isnan(cosine[l])) << special[l];
  }
}

}  // namespace
}  // namespace moorsim::internal
