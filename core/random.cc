#include "core/random.h"

#include <cmath>

namespace moorsim {
namespace {

// SplitMix64's Weyl increment, 2^64 / golden ratio (Steele, Lea & Flood 2014).
constexpr std::uint64_t kGoldenGamma = 0x9e3779b97f4a7c15ULL;

constexpr std::uint64_t RotateLeft(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }

}  // namespace

std::uint64_t SplitMix64Mix(std::uint64_t x) {
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

std::uint64_t Fnv1a64(std::string_view bytes) {
  std::uint64_t hash = 0xcbf29ce484222325ULL;  // FNV-1a 64-bit offset basis
  for (const char c : bytes) {
    hash ^= static_cast<unsigned char>(c);
    hash *= 0x100000001b3ULL;  // FNV 64-bit prime
  }
  return hash;
}

RandomStream RandomStream::Derive(std::uint64_t run_seed, std::string_view name) {
  return RandomStream(SplitMix64Mix(SplitMix64Mix(run_seed) ^ Fnv1a64(name)));
}

RandomStream::RandomStream(std::uint64_t key) {
  // Seeding xoshiro from a SplitMix64 sequence is what its authors recommend: it never
  // yields the forbidden all-zero state in practice and decorrelates the four words.
  std::uint64_t weyl = key;
  for (std::uint64_t& word : state_) {
    weyl += kGoldenGamma;
    word = SplitMix64Mix(weyl);
  }
}

std::uint64_t RandomStream::NextU64() {
  // xoshiro256** 1.0 (Blackman & Vigna 2021, reference implementation at prng.di.unimi.it).
  const std::uint64_t result = RotateLeft(state_[1] * 5, 7) * 9;
  const std::uint64_t t = state_[1] << 17;
  state_[2] ^= state_[0];
  state_[3] ^= state_[1];
  state_[1] ^= state_[2];
  state_[0] ^= state_[3];
  state_[2] ^= t;
  state_[3] = RotateLeft(state_[3], 45);
  return result;
}

double RandomStream::Uniform() { return static_cast<double>(NextU64() >> 11) * 0x1.0p-53; }

double RandomStream::Normal() {
  if (has_spare_normal_) {
    has_spare_normal_ = false;
    return spare_normal_;
  }
  // Polar method: a point uniform in the unit disc, (u, v) / sqrt(s) is a uniform
  // direction and -2 ln s an independent chi-square(2) radius squared. Acceptance is
  // pi/4, so about 1.27 pairs of uniforms per pair of normals.
  double u = 0.0;
  double v = 0.0;
  double s = 0.0;
  do {
    u = 2.0 * Uniform() - 1.0;
    v = 2.0 * Uniform() - 1.0;
    s = u * u + v * v;
  } while (s >= 1.0 || s == 0.0);
  const double factor = std::sqrt(-2.0 * std::log(s) / s);
  spare_normal_ = v * factor;
  has_spare_normal_ = true;
  return u * factor;
}

}  // namespace moorsim
