// Rainflow counting (analysis/rainflow.h) against ASTM E1049-85's worked example and against
// an independent count written here: the four-point method, whose residue is then counted
// as half cycles.
#include "analysis/rainflow.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <stdexcept>
#include <vector>

namespace moorsim::analysis {
namespace {

// Counts by range (rounded to 1e-9), full and half cycles together.
std::map<long long, double> ByRange(const std::vector<RainflowCycle>& cycles) {
  std::map<long long, double> counts;
  for (const RainflowCycle& c : cycles) counts[std::llround(c.range * 1e9)] += c.count;
  return counts;
}

TEST(Rainflow, TheStandardsWorkedExample) {
  // ASTM E1049-85, Fig. 6: peaks and valleys -2 1 -3 5 -1 3 -4 4 -2, with points between
  // them that are not turning points.
  const std::vector<double> history = {-2, 0, 1, -3, 0, 5, 2, -1, 3, -4, 0, 4, -2};
  EXPECT_EQ(TurningPoints(history), (std::vector<double>{-2, 1, -3, 5, -1, 3, -4, 4, -2}));
  const std::map<long long, double> counts = ByRange(Rainflow(history));
  const std::map<long long, double> table = {{3'000'000'000, 0.5},
                                             {4'000'000'000, 1.5},
                                             {6'000'000'000, 0.5},
                                             {8'000'000'000, 1.0},
                                             {9'000'000'000, 0.5}};
  EXPECT_EQ(counts, table);
  // The closed loop -1..3 (range 4) has mean 1.
  const std::vector<RainflowCycle> cycles = Rainflow(history);
  const auto loop = std::find_if(cycles.begin(), cycles.end(), [](const RainflowCycle& c) {
    return c.count == 1.0 && c.range == 4;
  });
  ASSERT_NE(loop, cycles.end());
  EXPECT_EQ(loop->mean, 1.0);
}

// The four-point method: with four consecutive turning points a b c d, the inner range
// |b - c| is a closed cycle when it lies within |a - b| and |c - d|; b and c are removed.
// What stays is the residue, each of its ranges half a cycle.
std::vector<RainflowCycle> FourPoint(const std::vector<double>& points) {
  std::vector<RainflowCycle> cycles;
  std::vector<double> stack;
  for (double p : points) {
    stack.push_back(p);
    while (stack.size() >= 4) {
      const std::size_t n = stack.size();
      const double a = stack[n - 4], b = stack[n - 3], c = stack[n - 2], d = stack[n - 1];
      const double inner = std::abs(b - c);
      if (inner <= std::abs(a - b) && inner <= std::abs(c - d)) {
        cycles.push_back({inner, (b + c) / 2.0, 1.0});
        stack.erase(stack.end() - 3, stack.end() - 1);
      } else {
        break;
      }
    }
  }
  for (std::size_t i = 1; i < stack.size(); ++i) {
    cycles.push_back({std::abs(stack[i] - stack[i - 1]), (stack[i] + stack[i - 1]) / 2.0, 0.5});
  }
  return cycles;
}

TEST(Rainflow, EqualsTheFourPointMethodOnRandomHistories) {
  std::mt19937_64 random(1049);
  std::normal_distribution<double> noise;
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<double> history(50 + trial * 10);
    // A slow swell with noise on it: loops within loops.
    for (std::size_t i = 0; i < history.size(); ++i) {
      history[i] = 3.0 * std::sin(0.05 * static_cast<double>(i)) + noise(random);
    }
    const std::vector<RainflowCycle> cycles = Rainflow(history);
    const std::vector<RainflowCycle> reference = FourPoint(TurningPoints(history));
    EXPECT_EQ(ByRange(cycles), ByRange(reference)) << "trial " << trial;
    // Every range between turning points is counted once: half the number of ranges.
    double total = 0.0;
    for (const RainflowCycle& c : cycles) total += c.count;
    EXPECT_DOUBLE_EQ(total, (TurningPoints(history).size() - 1) / 2.0);
  }
}

TEST(Rainflow, ConstantAmplitudeIsOneCycleAPeriodAndNonFiniteIsRefused) {
  std::vector<double> sine;
  for (int i = 0; i <= 1000; ++i)
    sine.push_back(5.0 + 2.0 * std::sin(2.0 * M_PI * i / 100.0 + 0.3));
  // Ten periods: ten cycles of range 4 about 5 (as pairs of half cycles, the ranges never
  // growing), less the part-ranges at the record's ends.
  double count = 0.0;
  for (const RainflowCycle& c : Rainflow(sine)) {
    if (c.range < 3.9) continue;
    count += c.count;
    EXPECT_NEAR(c.range, 4.0, 2e-3);
    EXPECT_NEAR(c.mean, 5.0, 2e-3);
  }
  EXPECT_NEAR(count, 9.5, 0.5);
  EXPECT_TRUE(Rainflow(std::vector<double>{}).empty());
  EXPECT_TRUE(Rainflow(std::vector<double>{1.0, 1.0}).empty());
  EXPECT_THROW(Rainflow(std::vector<double>{1.0, NAN, 2.0}), std::invalid_argument);
}

}  // namespace
}  // namespace moorsim::analysis
