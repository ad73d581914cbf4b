// Deterministic random streams. Every pixel sample draws from a stream keyed by
// (seed, pixel x, pixel y), so an image does not depend on threads, tiles or schedule.
#pragma once

#include <cstdint>

namespace prism {

// 64-bit finaliser of MurmurHash3 / SplitMix64: a cheap, well-mixed hash for stream keys.
inline uint64_t mix64(uint64_t x) {
  x ^= x >> 33;
  x *= 0xff51afd7ed558ccdULL;
  x ^= x >> 33;
  x *= 0xc4ceb9fe1a85ec53ULL;
  x ^= x >> 33;
  return x;
}

// PCG32 (O'Neill 2014, pcg-random.org, "XSH RR" output): small state, good statistics.
class Pcg32 {
 public:
  Pcg32(uint64_t seed, uint64_t stream) : increment_((stream << 1u) | 1u) {
    nextUint();
    state_ += seed;
    nextUint();
  }

  // Keyed by up to three integers, e.g. (seed, x, y).
  static Pcg32 forKey(uint64_t seed, uint64_t a, uint64_t b) {
    return Pcg32(mix64(seed ^ mix64(a + 0x9e3779b97f4a7c15ULL)), mix64(b + 0x632be59bd9b4e019ULL));
  }

  uint32_t nextUint() {
    const uint64_t old = state_;
    state_ = old * 6364136223846793005ULL + increment_;
    const uint32_t xorshifted = static_cast<uint32_t>(((old >> 18u) ^ old) >> 27u);
    const uint32_t rot = static_cast<uint32_t>(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((~rot + 1u) & 31u));
  }

  // Uniform in [0, 1): 24 random mantissa bits, so the result never rounds up to 1.
  float nextFloat() { return static_cast<float>(nextUint() >> 8) * 0x1p-24f; }

 private:
  uint64_t state_ = 0;
  uint64_t increment_;
};

}  // namespace prism
