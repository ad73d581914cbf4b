// The one place Prism's kernels meet SIMD. Lanes are GCC/Clang vector extensions, so the
// compiler emits whatever the build targets allow: SSE2 on any x86-64 (an 8-wide vector is then
// two 4-wide registers), AVX2 or AVX-512 when the build asks for them (-DPRISM_ARCH, see
// docs/performance.md), NEON on ARM, or plain scalar code elsewhere. No instruction set is
// required at run time beyond what the build was told to use.
//
// Minimum and maximum follow the x86 rule: when either operand is NaN the second one is
// returned. Kernels pass the value that may be NaN first so a NaN never decides a test.
#pragma once

#include <cstdint>
#include <cstring>

#if defined(__SSE2__)
#include <immintrin.h>
#endif

namespace prism::simd {

using Float4 = float __attribute__((vector_size(16)));
using Int4 = int32_t __attribute__((vector_size(16)));
using Float8 = float __attribute__((vector_size(32)));
using Int8 = int32_t __attribute__((vector_size(32)));

// The vector of the packet walks' tests (accel/PacketWalk.cpp): eight rays where AVX2 compares
// them in one instruction, else four (GCC splits an eight-lane comparison without AVX into one
// scalar comparison per lane). A kernel compiled per instruction set gets its set's width.
#if defined(__AVX2__)
using PacketVector = Float8;
#else
using PacketVector = Float4;
#endif

template <class V>
inline V load(const float* p) {
  V v;
  std::memcpy(&v, p, sizeof(V));
  return v;
}

// x in every lane, bit for bit: a -0 stays -0. (`V{} + x`, the obvious spelling, is an addition
// to +0 that the compiler must keep, an instruction a broadcast, and turns -0 into +0; a loop
// over the lanes compiles to a chain of inserts.)
template <class V>
inline V broadcast(float x) {
  static_assert(sizeof(V) == 16 || sizeof(V) == 32);
#if defined(__AVX__)
  if constexpr (sizeof(V) == 32) return reinterpret_cast<V>(_mm256_set1_ps(x));
#endif
#if defined(__SSE2__)
  const Float4 half = reinterpret_cast<Float4>(_mm_set1_ps(x));
#else
  const Float4 half = {x, x, x, x};
#endif
  if constexpr (sizeof(V) == 16) {
    return half;
  } else {
    return __builtin_shufflevector(half, half, 0, 1, 2, 3, 0, 1, 2, 3);
  }
}

// Written with intrinsics where the vector width has them: GCC does not turn a vector `?:`
// wider than the target's registers into paired min/max instructions but into one scalar
// comparison per lane.
inline Float4 minLanes(Float4 a, Float4 b) {
#if defined(__SSE2__)
  return reinterpret_cast<Float4>(
      _mm_min_ps(reinterpret_cast<__m128>(a), reinterpret_cast<__m128>(b)));
#else
  return a < b ? a : b;
#endif
}

inline Float4 maxLanes(Float4 a, Float4 b) {
#if defined(__SSE2__)
  return reinterpret_cast<Float4>(
      _mm_max_ps(reinterpret_cast<__m128>(a), reinterpret_cast<__m128>(b)));
#else
  return a > b ? a : b;
#endif
}

inline Float8 minLanes(Float8 a, Float8 b) {
#if defined(__AVX__)
  return reinterpret_cast<Float8>(
      _mm256_min_ps(reinterpret_cast<__m256>(a), reinterpret_cast<__m256>(b)));
#else
  return a < b ? a : b;  // targets without AVX (WideBvh.h uses 8 lanes only with AVX)
#endif
}

inline Float8 maxLanes(Float8 a, Float8 b) {
#if defined(__AVX__)
  return reinterpret_cast<Float8>(
      _mm256_max_ps(reinterpret_cast<__m256>(a), reinterpret_cast<__m256>(b)));
#else
  return a > b ? a : b;
#endif
}

// The low and high halves of an eight-lane vector, and back: eight-lane operations on targets
// without AVX. Shuffles, not copies through memory: the AVX2 walks (compiled with the build's
// preprocessor view, so through these fallbacks) otherwise stored two halves and loaded the
// whole at once, which stalls on store forwarding.
template <class Half, class Whole>
inline void splitHalves(const Whole& whole, Half& low, Half& high) {
  static_assert(2 * sizeof(Half) == sizeof(Whole) && sizeof(Whole) / sizeof(whole[0]) == 8);
  low = __builtin_shufflevector(whole, whole, 0, 1, 2, 3);
  high = __builtin_shufflevector(whole, whole, 4, 5, 6, 7);
}

template <class Whole, class Half>
inline Whole joinHalves(const Half& low, const Half& high) {
  static_assert(2 * sizeof(Half) == sizeof(Whole) && sizeof(Half) / sizeof(low[0]) == 4);
  return __builtin_shufflevector(low, high, 0, 1, 2, 3, 4, 5, 6, 7);
}

// Correctly rounded square roots, as std::sqrt gives them lane by lane.
inline Float4 sqrtLanes(Float4 a) {
#if defined(__SSE2__)
  return reinterpret_cast<Float4>(_mm_sqrt_ps(reinterpret_cast<__m128>(a)));
#else
  for (int i = 0; i < 4; ++i) a[i] = __builtin_sqrtf(a[i]);
  return a;
#endif
}

inline Float8 sqrtLanes(Float8 a) {
#if defined(__AVX__)
  return reinterpret_cast<Float8>(_mm256_sqrt_ps(reinterpret_cast<__m256>(a)));
#else
  Float4 low, high;
  splitHalves(a, low, high);
  return joinHalves<Float8>(sqrtLanes(low), sqrtLanes(high));
#endif
}

// Rows to columns: afterwards a holds the first lanes of the old a, b, c, d, b the second...
inline void transpose(Float4& a, Float4& b, Float4& c, Float4& d) {
  const Float4 ab0 = __builtin_shufflevector(a, b, 0, 4, 1, 5);
  const Float4 cd0 = __builtin_shufflevector(c, d, 0, 4, 1, 5);
  const Float4 ab1 = __builtin_shufflevector(a, b, 2, 6, 3, 7);
  const Float4 cd1 = __builtin_shufflevector(c, d, 2, 6, 3, 7);
  a = __builtin_shufflevector(ab0, cd0, 0, 1, 4, 5);
  b = __builtin_shufflevector(ab0, cd0, 2, 3, 6, 7);
  c = __builtin_shufflevector(ab1, cd1, 0, 1, 4, 5);
  d = __builtin_shufflevector(ab1, cd1, 2, 3, 6, 7);
}

template <class V>
inline void store(float* p, V v) {
  std::memcpy(p, &v, sizeof(V));
}

// The comparison result (integer lanes) of each float vector.
template <class V>
struct MaskFor;
template <>
struct MaskFor<Float4> {
  using Type = Int4;
};
template <>
struct MaskFor<Float8> {
  using Type = Int8;
};
template <class V>
using MaskOf = typename MaskFor<V>::Type;

// |magnitude| with the sign of sign, lane by lane (std::copysign).
template <class V>
inline V copySign(V magnitude, V sign) {
  using M = MaskOf<V>;
  const M signBit = M{} + static_cast<int32_t>(0x80000000u);
  return reinterpret_cast<V>((reinterpret_cast<M>(magnitude) & ~signBit) |
                             (reinterpret_cast<M>(sign) & signBit));
}

// Lane by lane, a where m is all ones and b where it is zero (m: a comparison's result).
template <class V>
inline V select(MaskOf<V> m, V a, V b) {
  using M = MaskOf<V>;
  return reinterpret_cast<V>((reinterpret_cast<M>(a) & m) | (reinterpret_cast<M>(b) & ~m));
}

template <class M>
inline M selectInt(M m, M a, M b) {
  return (a & m) | (b & ~m);
}

// Lane i all ones where bit i of `bits` is set: laneMask's inverse. The bits go to every lane
// at once, each lane keeps its own and compares it with zero (three vector instructions, where
// building the lanes one by one took four scalar ones a lane).
template <class M>
inline M lanesOf(uint32_t bits) {
  constexpr int kLanes = static_cast<int>(sizeof(M) / sizeof(int32_t));
  static_assert(kLanes == 4 || kLanes == 8);
  M own;
  if constexpr (kLanes == 4) {
    own = M{1, 2, 4, 8};
  } else {
    own = M{1, 2, 4, 8, 16, 32, 64, 128};
  }
  return ((M{} + static_cast<int32_t>(bits)) & own) != 0;
}

// Bit i is set when lane i of the comparison result is true (all ones).
inline uint32_t laneMask(Int4 m) {
#if defined(__SSE2__)
  return static_cast<uint32_t>(_mm_movemask_ps(reinterpret_cast<__m128>(m)));
#else
  uint32_t bits = 0;
  for (int i = 0; i < 4; ++i) bits |= (m[i] != 0 ? 1u : 0u) << i;
  return bits;
#endif
}

inline uint32_t laneMask(Int8 m) {
#if defined(__AVX__)
  return static_cast<uint32_t>(_mm256_movemask_ps(reinterpret_cast<__m256>(m)));
#else
  Int4 low, high;
  splitHalves(m, low, high);
  return laneMask(low) | (laneMask(high) << 4);
#endif
}

// Index of the lowest set bit; mask must not be zero.
inline int firstLane(uint32_t mask) {
  return __builtin_ctz(mask);
}

// Number of set bits. The baseline x86-64 build has no popcnt instruction, and there
// __builtin_popcount calls libgcc's table-driven routine (0.4 % of the default frame's samples,
// a call per packet); the bit-parallel sum stays inline.
inline int laneCount(uint32_t mask) {
#if defined(__POPCNT__)
  return __builtin_popcount(mask);
#else
  mask = mask - ((mask >> 1) & 0x55555555u);
  mask = (mask & 0x33333333u) + ((mask >> 2) & 0x33333333u);
  return static_cast<int>((((mask + (mask >> 4)) & 0x0f0f0f0fu) * 0x01010101u) >> 24);
#endif
}

// The instruction sets this binary was compiled for, for reports and the start-up check.
inline const char* compiledInstructionSet() {
#if defined(__AVX512F__)
  return "avx512";
#elif defined(__AVX2__)
  return "avx2";
#elif defined(__AVX__)
  return "avx";
#elif defined(__SSE2__)
  return "sse2";
#else
  return "scalar";
#endif
}

// Whether this CPU has the instruction sets the build assumed (PRISM_ARCH): checked at start-up
// so a binary built for AVX2 says so on an older machine instead of dying of SIGILL.
inline bool cpuRunsThisBuild() {
#if defined(__x86_64__) || defined(__i386__)
#if defined(__AVX512F__)
  if (!__builtin_cpu_supports("avx512f")) return false;
#endif
#if defined(__AVX2__)
  if (!__builtin_cpu_supports("avx2")) return false;
#endif
#if defined(__AVX__)
  if (!__builtin_cpu_supports("avx")) return false;
#endif
#endif
  return true;
}

}  // namespace prism::simd
