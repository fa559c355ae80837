#pragma once
/// The project's seeded random numbers: xoshiro256** seeded by SplitMix64, with our own mapping to
/// doubles (no std:: distributions, whose output differs between standard libraries), so the same
/// seed gives the same numbers on every machine. Wall generators (datasets/) and the surprise
/// obstacles of replanning experiments (experiments/src/replanning.cpp) draw from it.
#include <cstdint>

namespace coverbench {

/// Draws happen in statement order only: never two draws among one call's arguments, whose order
/// C++ leaves to the compiler (gcc evaluates them right to left, clang left to right, so a clang
/// build once generated other walls). The hoisted draws keep the order in which the golden hashes
/// (tests/datasets/datasets_test.cpp) were pinned.
class Rng {
 public:
  explicit Rng(std::uint64_t seed) {
    for (std::uint64_t& word : s_) word = splitmix(seed);
  }
  std::uint64_t next() {
    const std::uint64_t result = rotl(s_[1] * 5, 7) * 9;
    const std::uint64_t t = s_[1] << 17;
    s_[2] ^= s_[0];
    s_[3] ^= s_[1];
    s_[1] ^= s_[2];
    s_[0] ^= s_[3];
    s_[2] ^= t;
    s_[3] = rotl(s_[3], 45);
    return result;
  }
  /// Uniform in [lo, hi).
  double uniform(double lo, double hi) { return lo + (hi - lo) * static_cast<double>(next() >> 11) * 0x1.0p-53; }
  /// Uniform integer in [lo, hi].
  int integer(int lo, int hi) { return lo + static_cast<int>(next() % static_cast<std::uint64_t>(hi - lo + 1)); }
  bool chance(double p) { return uniform(0.0, 1.0) < p; }

  static std::uint64_t splitmix(std::uint64_t& x) {
    std::uint64_t z = (x += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }

 private:
  static std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
  std::uint64_t s_[4];
};

}  // namespace coverbench
