#include "core/sincos.h"

#include <cmath>
#include <cstdint>
#include <cstring>

namespace moorsim::internal {

namespace {

// Bit patterns by memcpy rather than std::bit_cast: GCC 12 does not vectorise loops holding
// the latter.
inline std::uint64_t BitsOf(double value) {
  std::uint64_t bits;
  std::memcpy(&bits, &value, sizeof bits);
  return bits;
}

inline double DoubleOf(std::uint64_t bits) {
  double value;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}

}  // namespace

void SinCos(const double* angle, double* sine, double* cosine, int count) {
  // π/2 split into three parts of 33 significant bits each (fdlibm e_rem_pio2.c): q times
  // the first is exact for |q| < 2^20, so x − q π/2 loses nothing to cancellation and the
  // error of the reduction is q times the 8.5e-32 left of π/2 after the third part.
  constexpr double kTwoOverPi = 6.36619772367581382433e-01;
  constexpr double kHalfPi1 = 1.57079632673412561417e+00;
  constexpr double kHalfPi2 = 6.07710050630396597660e-11;
  constexpr double kHalfPi3 = 2.02226624871116645580e-21;
  constexpr double kReductionLimit = 1.6e6;  // |q| < 2^20 = 1.05e6
  // Adding 1.5 · 2^52 rounds to an integer and leaves it, two's complement, in the low
  // mantissa bits (|v| < 2^51).
  constexpr double kRoundingShift = 0x1.8p52;
  // fdlibm k_sin.c: sin r = r + r³ (S1 + r² S2 + … + r¹⁰ S6) on [−π/4, π/4].
  constexpr double kS1 = -1.66666666666666324348e-01;
  constexpr double kS2 = 8.33333333332248946124e-03;
  constexpr double kS3 = -1.98412698298579493134e-04;
  constexpr double kS4 = 2.75573137070700676789e-06;
  constexpr double kS5 = -2.50507602534068634195e-08;
  constexpr double kS6 = 1.58969099521155010221e-10;
  // fdlibm k_cos.c: cos r = 1 − r²/2 + r⁴ (C1 + r² C2 + … + r¹⁰ C6).
  constexpr double kC1 = 4.16666666666666019037e-02;
  constexpr double kC2 = -1.38888888888741095749e-03;
  constexpr double kC3 = 2.48015872894767294178e-05;
  constexpr double kC4 = -2.75573143513906633035e-07;
  constexpr double kC5 = 2.08757232129817482790e-09;
  constexpr double kC6 = -1.13596475577881948265e-11;

  for (int l = 0; l < count; ++l) {
    const double x = angle[l];
    const double shifted = x * kTwoOverPi + kRoundingShift;
    const double q = shifted - kRoundingShift;
    const std::uint64_t quadrant = BitsOf(shifted);  // q mod 4 in the two lowest bits
    const double r = ((x - q * kHalfPi1) - q * kHalfPi2) - q * kHalfPi3;
    const double z = r * r;
    const double sin_r =
        r + r * z * (kS1 + z * (kS2 + z * (kS3 + z * (kS4 + z * (kS5 + z * kS6)))));
    const double cos_r =
        1.0 - 0.5 * z + z * z * (kC1 + z * (kC2 + z * (kC3 + z * (kC4 + z * (kC5 + z * kC6)))));
    // x = q π/2 + r: quadrant 0 (sin r, cos r), 1 (cos r, −sin r), 2 (−sin r, −cos r),
    // 3 (−cos r, sin r). Swap and signs as bit operations: no branch, no select.
    const std::uint64_t odd = std::uint64_t{0} - (quadrant & 1u);  // all ones when odd
    const std::uint64_t sin_bits = BitsOf(sin_r);
    const std::uint64_t cos_bits = BitsOf(cos_r);
    const std::uint64_t sin_sign = (quadrant & 2u) << 62;
    const std::uint64_t cos_sign = ((quadrant + 1u) & 2u) << 62;
    sine[l] = DoubleOf(((cos_bits & odd) | (sin_bits & ~odd)) ^ sin_sign);
    cosine[l] = DoubleOf(((sin_bits & odd) | (cos_bits & ~odd)) ^ cos_sign);
  }
  // Non-finite angles already gave NaN above, as std::sin would.
  for (int l = 0; l < count; ++l) {
    if (std::abs(angle[l]) > kReductionLimit && std::isfinite(angle[l])) {
      sine[l] = std::sin(angle[l]);
      cosine[l] = std::cos(angle[l]);
    }
  }
}

}  // namespace moorsim::internal
