// T-N fatigue (analysis/fatigue.h): the presets' numbers, Miner's sum on constant-amplitude
// cycles, the mean-load term, and the damage of a narrow-band Gaussian process against its
// closed form D = nu0 T (2 sqrt 2 sigma)^m Gamma(1 + m/2) / a_D.
#include "analysis/fatigue.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

namespace moorsim::analysis {
namespace {

TEST(TnCurve, ThePresetsAreTheStandardsCurves) {
  EXPECT_EQ(TnCurveOf(TnPreset::kStudlessChain).a, 6.0e10);
  EXPECT_EQ(TnCurveOf(TnPreset::kStudlinkChain).a, 1.2e11);
  EXPECT_EQ(TnCurveOf(TnPreset::kSixStrandRope).m, 4.0);
  EXPECT_EQ(TnCurveOf(TnPreset::kSpiralRope).a, 1.7e17);
  EXPECT_EQ(TnCurveOf(TnPreset::kPolyester).range, TnCurve::Range::kNormalised);
  EXPECT_EQ(TnCurveOf(TnPreset::kPolyester).m, 5.2);
  EXPECT_EQ(ParseChoice<TnPreset>("spiral_rope"), TnPreset::kSpiralRope);
  // A 100 mm studless chain: two bars of 7854 mm^2; 1 MN of range is 63.662 MPa, which the
  // curve allows 6e10 / 63.662^3 = 232 547 times.
  const double area = NominalArea(TnPreset::kStudlessChain, 0.1);
  EXPECT_NEAR(area, 2.0 * std::numbers::pi * 0.05 * 0.05, 1e-15);
  EXPECT_NEAR(TnCurveOf(TnPreset::kStudlessChain).CyclesToFailure(1.0e6, 0.0, area, 0.0), 232547.0,
              1.0);
  // Polyester: R = 0.1 of the breaking strength, N = 25000 / 0.1^5.2.
  EXPECT_NEAR(TnCurveOf(TnPreset::kPolyester).CyclesToFailure(1.0e6, 0.0, 0.0, 1.0e7),
              25000.0 * std::pow(10.0, 5.2), 1e-6 * 25000.0 * std::pow(10.0, 5.2));
}

TEST(Miner, ConstantAmplitudeCyclesSumTheirFractionsAndTheMeanLoadShortensTheLife) {
  FatigueComponent chain{TnCurveOf(TnPreset::kStudlinkChain),
                         NominalArea(TnPreset::kStudlinkChain, 0.12), 1.2e7};
  std::vector<double> history;
  for (int i = 0; i < 1000; ++i) history.push_back(i % 2 == 0 ? 3.0e6 : 5.0e6);
  // 499 full cycles of 2 MN and two half cycles... every range is 2 MN: 999 halves.
  const double per_cycle =
      1.0 / chain.curve.CyclesToFailure(2.0e6, 4.0e6, chain.area, chain.breaking);
  EXPECT_NEAR(MinerDamage(history, chain), 999.0 / 2.0 * per_cycle, 1e-12 * 999.0 * per_cycle);
  // A mean-load term: log10 a = log10 a0 - c L_m.
  TnCurve rope{TnRange::kNormalised, 231.0, 4.09, 2.79};
  const double n0 = rope.CyclesToFailure(1.0e6, 0.0, 0.0, 1.0e7);
  const double n3 = rope.CyclesToFailure(1.0e6, 3.0e6, 0.0, 1.0e7);
  EXPECT_NEAR(n3 / n0, std::pow(10.0, -2.79 * 0.3), 1e-12);
}

TEST(Miner, ANarrowBandGaussianProcessHasTheClosedFormsDamage) {
  // A narrow-band Gaussian process: white noise through a resonance of damping 0.005 at a
  // 1 s period (an AR(2) recursion), 80 samples a period, 2e5 periods (1.6e7 samples) after
  // a settling start. Its damage on a studless chain curve (m = 3), rainflow-counted, is the
  // closed form's with the record's own sigma and zero-upcrossing rate nu0 within 2 %: the
  // rainflow count of a process this narrow is the Rayleigh peaks' count to about 1 %
  // (with 1e5 periods, eight seeds gave 0.987 to 1.000), and sampling the peaks at
  // 80 points a period lowers the ranges by 0.1 % at most.
  const double zeta = 0.005, per_period = 80.0, periods = 2.0e5;
  const double omega = 2.0 * std::numbers::pi, dt = 1.0 / per_period;
  const double r = std::exp(-zeta * omega * dt);
  const double theta = omega * dt * std::sqrt(1.0 - zeta * zeta);
  const double phi1 = 2.0 * r * std::cos(theta), phi2 = -r * r;
  std::mt19937_64 random(301);
  std::normal_distribution<double> noise;
  const auto samples = static_cast<std::size_t>(periods * per_period);
  std::vector<double> tension(samples);
  double x1 = 0.0, x2 = 0.0;
  for (std::size_t k = 0; k < samples + 20000; ++k) {
    const double x = phi1 * x1 + phi2 * x2 + noise(random);
    x2 = x1;
    x1 = x;
    if (k >= 20000) tension[k - 20000] = x;
  }
  double square = 0.0;
  long upcrossings = 0;
  for (std::size_t k = 0; k < samples; ++k) {
    square += tension[k] * tension[k];
    if (k > 0 && tension[k - 1] < 0.0 && tension[k] >= 0.0) ++upcrossings;
  }
  const double sigma_units = std::sqrt(square / static_cast<double>(samples));
  const double duration = static_cast<double>(samples) * dt;
  const double nu0 = static_cast<double>(upcrossings) / duration;
  // In newtons: sigma 100 kN about a mean of 2 MN, on a 100 mm chain.
  const double scale = 1.0e5 / sigma_units;
  for (double& t : tension) t = 2.0e6 + scale * t;
  const FatigueComponent chain{TnCurveOf(TnPreset::kStudlessChain),
                               NominalArea(TnPreset::kStudlessChain, 0.1), 8.0e6};
  const double m = chain.curve.m;
  const double sigma_mpa = 1.0e5 / chain.area / 1.0e6;
  const double closed = nu0 * duration * std::pow(2.0 * std::sqrt(2.0) * sigma_mpa, m) *
                        std::tgamma(1.0 + m / 2.0) / chain.curve.a;
  const double damage = MinerDamage(tension, chain);
  EXPECT_NEAR(damage / closed, 1.0, 0.02) << damage << " against " << closed;
}

}  // namespace
}  // namespace moorsim::analysis
