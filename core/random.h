// Independent, reproducible random streams: one per noise source, derived from the run
// seed and the source's name.
//
// Why one stream per name: the TAPM thesis's simulator fed every DOF's sensor noise from
// one seed, so x, y and psi carried the same noise and its detector results were void
// (docs/design.md section 2). Here each source ("gnss.x", "gnss.y", "gyro.psi",
// "waves.phases", ...) derives its own stream, so adding, removing or reordering sources
// never shifts another source's numbers, and a run is repeated bit for bit from its seed.
//
// Everything is defined here down to the bit, not delegated to <random>: the engine is
// xoshiro256** (Blackman & Vigna, "Scrambled linear pseudorandom number generators",
// ACM TOMS 47(4), 2021), seeded through SplitMix64 (Steele, Lea & Flood, OOPSLA 2014) as
// its authors recommend, and Normal() is Marsaglia's polar method (Marsaglia & Bray,
// SIAM Review 6(3), 1964). std::normal_distribution and friends are
// implementation-defined, so the same seed would give other numbers under another
// standard library (libstdc++ and libc++ already differ). Here the integer sequence and
// Uniform() are exact everywhere; Normal() uses only std::sqrt (correctly rounded under
// IEEE 754) and std::log, so it is bit-identical wherever log is (any glibc build) and
// can differ at most in the last bits under a different libm.
#pragma once

#include <array>
#include <cstdint>
#include <string_view>

namespace moorsim {

/// SplitMix64 output function (Steele, Lea & Flood 2014; the "variant 13" constants of
/// Stafford's Mix13): a bijective 64-bit mixer in which every input bit affects every
/// output bit.
std::uint64_t SplitMix64Mix(std::uint64_t x);

/// 64-bit FNV-1a hash of a byte string (Fowler, Noll & Vo; IETF draft-eastlake-fnv).
std::uint64_t Fnv1a64(std::string_view bytes);

/// One stream of pseudo-random numbers.
///
/// Move-only on purpose: a copied stream would replay the same numbers into a second
/// consumer, which is exactly the correlated-noise fault this type exists to prevent. Two
/// consumers that need the same numbers (a test comparing runs) derive the stream twice.
class RandomStream {
 public:
  /// The stream of the source `name` in the run with seed `run_seed`. The key is
  /// SplitMix64Mix(SplitMix64Mix(run_seed) ^ Fnv1a64(name)): mixing the seed first means
  /// neighbouring seeds (1, 2, 3, ...) and similar names ("gnss.x", "gnss.y") give
  /// unrelated keys, and the 256-bit engine state is then filled by a SplitMix64 sequence
  /// from that key.
  static RandomStream Derive(std::uint64_t run_seed, std::string_view name);

  RandomStream(RandomStream&&) = default;
  RandomStream& operator=(RandomStream&&) = default;
  RandomStream(const RandomStream&) = delete;
  RandomStream& operator=(const RandomStream&) = delete;

  /// Next raw 64-bit output of xoshiro256**.
  std::uint64_t NextU64();

  /// Uniform on [0, 1): the top 53 bits of NextU64() scaled by 2^-53, so every value is a
  /// multiple of 2^-53 and all 2^53 of them are equally likely.
  double Uniform();

  /// Standard normal N(0, 1) by Marsaglia's polar method. Each accepted pair of uniforms
  /// gives two independent normals; the second is kept for the next call.
  double Normal();

 private:
  explicit RandomStream(std::uint64_t key);

  std::array<std::uint64_t, 4> state_{};
  double spare_normal_ = 0.0;
  bool has_spare_normal_ = false;
};

}  // namespace moorsim
