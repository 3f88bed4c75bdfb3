#pragma once
// Lanes of doubles, each namespace named for its lane count and instruction set (internal):
// `x8_avx512` (eight lanes in one register) and `x8_avx` (eight in two, as low and high halves)
// have a lane-by-lane step. Both have the same names: V (eight doubles), M (which lanes), C (eight
// counters), their operations, a few on eight int32 lanes in memory (equal_lanes,
// store_minus_ones, select_lanes), and Limits and constrain_springs (one spring on each lane,
// length_constraint_kernel.inc). `x2_sse2` and `x4_avx` have the operations of that kernel on two
// and four lanes, for the one-ring red-black constraint; lane_scalar.hpp has one lane. src/sim/stage_kernels.inc,
// lane_kernels.inc and contact_limit_kernels.inc are written against these names and compiled once for each. Every
// operation gives each lane the bits the scalar one gives, so both instruction sets, and the one-ring code, agree to
// the bit. Call these only where constraint_vector_width() has the instruction set. These wrappers of intrinsics are
// the one place where code is written once per instruction set, so they are alike by design.

#include <cstdint>

#include "simd_dispatch.hpp"
#include "softdrop/droplet.hpp"

#if defined(SOFTDROP_AVX_DISPATCH)
namespace softdrop::lanes {

/// Which of the two the dispatchers call: x8_avx512 if the width in use has it, else x8_avx.
inline bool avx512_in_use() { return constraint_vector_width() == VectorWidth::avx512; }

// Two and four lanes, for the one-ring constraints (length_constraint.cpp, length_constraint_wide.cpp):
// only the operations length_constraint_kernel.inc needs.
namespace x2_sse2 {
constexpr int kWidth = 2;  // lanes of a V
using V = __m128d;
using M = __m128d;  // all bits set in a lane that is in
inline V set1(double d) { return _mm_set1_pd(d); }
inline V zero() { return _mm_setzero_pd(); }
inline V add(V a, V b) { return _mm_add_pd(a, b); }
inline V sub(V a, V b) { return _mm_sub_pd(a, b); }
inline V mul(V a, V b) { return _mm_mul_pd(a, b); }
inline V div(V a, V b) { return _mm_div_pd(a, b); }
inline V sqrt(V a) { return _mm_sqrt_pd(a); }
/// Lanes where `a P b`, P one of the _CMP_ predicates the kernels use (SSE2 has one compare each).
template <int P>
inline M compare(V a, V b) {
  if constexpr (P == _CMP_LE_OS)
    return _mm_cmple_pd(a, b);
  else if constexpr (P == _CMP_GE_OS)
    return _mm_cmpge_pd(a, b);
  else if constexpr (P == _CMP_GT_OS)
    return _mm_cmpgt_pd(a, b);
  else {
    static_assert(P == _CMP_NEQ_UQ, "no SSE2 compare for this predicate");
    return _mm_cmpneq_pd(a, b);
  }
}
inline M both(M a, M b) { return _mm_and_pd(a, b); }
/// a and not b.
inline M but_not(M a, M b) { return _mm_andnot_pd(b, a); }
inline bool any(M m) { return _mm_movemask_pd(m) != 0; }
/// Lanes in m, as bits (bit b: lane b).
inline unsigned bits(M m) { return static_cast<unsigned>(_mm_movemask_pd(m)); }
/// m ? b : a, lane by lane.
inline V blend(M m, V a, V b) { return _mm_or_pd(_mm_and_pd(m, b), _mm_andnot_pd(m, a)); }
/// m ? a + b : a, lane by lane (a lane not in m adds -0, which leaves every double as it is).
inline V add_where(M m, V a, V b) { return _mm_add_pd(a, blend(m, _mm_set1_pd(-0.0), b)); }
/// m ? a - b : a, lane by lane (a lane not in m subtracts +0).
inline V sub_where(M m, V a, V b) { return _mm_sub_pd(a, _mm_and_pd(m, b)); }
#define SOFTDROP_LANE_TARGET
#include "length_constraint_kernel.inc"
#undef SOFTDROP_LANE_TARGET
}  // namespace x2_sse2

namespace x4_avx {
constexpr int kWidth = 4;  // lanes of a V
using V = __m256d;
using M = __m256d;  // all bits set in a lane that is in
SOFTDROP_AVX inline V set1(double d) { return _mm256_set1_pd(d); }
SOFTDROP_AVX inline V zero() { return _mm256_setzero_pd(); }
SOFTDROP_AVX inline V add(V a, V b) { return _mm256_add_pd(a, b); }
SOFTDROP_AVX inline V sub(V a, V b) { return _mm256_sub_pd(a, b); }
SOFTDROP_AVX inline V mul(V a, V b) { return _mm256_mul_pd(a, b); }
SOFTDROP_AVX inline V div(V a, V b) { return _mm256_div_pd(a, b); }
SOFTDROP_AVX inline V sqrt(V a) { return _mm256_sqrt_pd(a); }
template <int P>
SOFTDROP_AVX inline M compare(V a, V b) {
  return _mm256_cmp_pd(a, b, P);
}
SOFTDROP_AVX inline M both(M a, M b) { return _mm256_and_pd(a, b); }
SOFTDROP_AVX inline M but_not(M a, M b) { return _mm256_andnot_pd(b, a); }
SOFTDROP_AVX inline bool any(M m) { return _mm256_movemask_pd(m) != 0; }
SOFTDROP_AVX inline unsigned bits(M m) { return static_cast<unsigned>(_mm256_movemask_pd(m)); }
/// m ? b : a, lane by lane, as bits: (m & b) | (~m & a), which is vblendvpd's choice for the
/// masks of compare() (each lane all ones or all zeros). Not _mm256_blendv_pd: GCC 12 turns it
/// into a select on the lanes' sign, which AVX without AVX2 has no 256-bit integer test for, and
/// does it one lane at a time through general registers and branches (in the contact kernel and
/// the forces' spring loop, about 40 instructions a blend).
SOFTDROP_AVX inline V blend(M m, V a, V b) { return _mm256_or_pd(_mm256_and_pd(m, b), _mm256_andnot_pd(m, a)); }
/// m ? a + b : a, lane by lane (a lane not in m adds -0, which leaves every double as it is).
SOFTDROP_AVX inline V add_where(M m, V a, V b) { return _mm256_add_pd(a, blend(m, _mm256_set1_pd(-0.0), b)); }
SOFTDROP_AVX inline V sub_where(M m, V a, V b) { return _mm256_sub_pd(a, _mm256_and_pd(m, b)); }
#define SOFTDROP_LANE_TARGET SOFTDROP_AVX
#include "length_constraint_kernel.inc"
#undef SOFTDROP_LANE_TARGET
}  // namespace x4_avx

namespace x8_avx {

constexpr int kWidth = 8;  // lanes of a V
struct V {
  __m256d lo, hi;  // lanes 0-3, 4-7
};
struct M {
  __m256d lo, hi;  // all bits set in a lane that is in
};
using C = V;  // counts as doubles (AVX has no 256-bit integer adds)

SOFTDROP_AVX inline V load(const double* p) { return {_mm256_loadu_pd(p), _mm256_loadu_pd(p + 4)}; }
SOFTDROP_AVX inline void store(double* p, V v) {
  _mm256_storeu_pd(p, v.lo);
  _mm256_storeu_pd(p + 4, v.hi);
}
SOFTDROP_AVX inline V set1(double d) { return {_mm256_set1_pd(d), _mm256_set1_pd(d)}; }
SOFTDROP_AVX inline V zero() { return {_mm256_setzero_pd(), _mm256_setzero_pd()}; }
SOFTDROP_AVX inline V add(V a, V b) { return {_mm256_add_pd(a.lo, b.lo), _mm256_add_pd(a.hi, b.hi)}; }
SOFTDROP_AVX inline V sub(V a, V b) { return {_mm256_sub_pd(a.lo, b.lo), _mm256_sub_pd(a.hi, b.hi)}; }
SOFTDROP_AVX inline V mul(V a, V b) { return {_mm256_mul_pd(a.lo, b.lo), _mm256_mul_pd(a.hi, b.hi)}; }
SOFTDROP_AVX inline V div(V a, V b) { return {_mm256_div_pd(a.lo, b.lo), _mm256_div_pd(a.hi, b.hi)}; }
SOFTDROP_AVX inline V sqrt(V a) { return {_mm256_sqrt_pd(a.lo), _mm256_sqrt_pd(a.hi)}; }
/// std::floor lane by lane (exact, as it is).
SOFTDROP_AVX inline V floor(V a) { return {_mm256_floor_pd(a.lo), _mm256_floor_pd(a.hi)}; }
/// -a to the bit (the sign flipped, as C++'s unary minus does).
SOFTDROP_AVX inline V negate(V a) {
  const __m256d sign = _mm256_set1_pd(-0.0);
  return {_mm256_xor_pd(a.lo, sign), _mm256_xor_pd(a.hi, sign)};
}
/// Lanes where `a P b` (P a _CMP_ predicate).
template <int P>
SOFTDROP_AVX inline M compare(V a, V b) {
  return {_mm256_cmp_pd(a.lo, b.lo, P), _mm256_cmp_pd(a.hi, b.hi, P)};
}
/// Lanes in m, as bits (bit b: lane b).
SOFTDROP_AVX inline unsigned bits(M m) {
  return static_cast<unsigned>(_mm256_movemask_pd(m.lo) | (_mm256_movemask_pd(m.hi) << 4));
}
/// m ? b : a, lane by lane, as bits (x4_avx::blend on each half).
SOFTDROP_AVX inline V blend(M m, V a, V b) {
  return {x4_avx::blend(m.lo, a.lo, b.lo), x4_avx::blend(m.hi, a.hi, b.hi)};
}
/// m ? a : +0.
SOFTDROP_AVX inline V keep_or_zero(M m, V a) { return {_mm256_and_pd(m.lo, a.lo), _mm256_and_pd(m.hi, a.hi)}; }
/// Lanes b < 8 where p[b] == v, as bits (SSE2's integer compares: AVX has no 256-bit ones).
SOFTDROP_AVX inline unsigned equal_lanes(const std::int32_t* p, std::int32_t v) {
  const __m128i want = _mm_set1_epi32(v);
  const __m128i lo = _mm_cmpeq_epi32(_mm_loadu_si128(reinterpret_cast<const __m128i*>(p)), want);
  const __m128i hi = _mm_cmpeq_epi32(_mm_loadu_si128(reinterpret_cast<const __m128i*>(p + 4)), want);
  return static_cast<unsigned>(_mm_movemask_ps(_mm_castsi128_ps(lo)) | (_mm_movemask_ps(_mm_castsi128_ps(hi)) << 4));
}
/// Lanes 4 h to 4 h + 3 of `lanes` (bit b: lane b) as four int32 lanes, -1 where in, 0 elsewhere.
SOFTDROP_AVX inline __m128i int32_mask(unsigned lanes, int h) {
  const __m128i bit = h == 0 ? _mm_setr_epi32(1, 2, 4, 8) : _mm_setr_epi32(16, 32, 64, 128);
  return _mm_cmpeq_epi32(_mm_and_si128(_mm_set1_epi32(static_cast<int>(lanes)), bit), bit);
}
/// p[b] = (bit b of `lanes`) ? -1 : 0 for b < 8.
SOFTDROP_AVX inline void store_minus_ones(std::int32_t* p, unsigned lanes) {
  for (int h = 0; h < 2; ++h) _mm_storeu_si128(reinterpret_cast<__m128i*>(p + 4 * h), int32_mask(lanes, h));
}
/// out[b] = (bit b of `lanes`) ? a[b] : other for b < 8 (SSE4.1's blends, two halves).
SOFTDROP_AVX inline void select_lanes(unsigned lanes, const std::int32_t* a, std::int32_t other, std::int32_t* out) {
  for (int h = 0; h < 2; ++h) {
    const __m128i in = _mm_loadu_si128(reinterpret_cast<const __m128i*>(a + 4 * h));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(out + 4 * h),
                     _mm_blendv_epi8(_mm_set1_epi32(other), in, int32_mask(lanes, h)));
  }
}
/// Lanes of `all` (a set1 of a lane set) whose bit is b0 or b1, as 64-bit lanes of all ones.
SOFTDROP_AVX inline __m128i two_lanes_of(__m128i all, long long b0, long long b1) {
  const __m128i bit = _mm_set_epi64x(b1, b0);
  return _mm_cmpeq_epi64(_mm_and_si128(all, bit), bit);
}
/// The lanes of `lanes` (bit b: lane b) as a mask.
SOFTDROP_AVX inline M mask_of(unsigned lanes) {
  const __m128i all = _mm_set1_epi64x(static_cast<long long>(lanes));
  return {_mm256_castsi256_pd(_mm256_setr_m128i(two_lanes_of(all, 1, 2), two_lanes_of(all, 4, 8))),
          _mm256_castsi256_pd(_mm256_setr_m128i(two_lanes_of(all, 16, 32), two_lanes_of(all, 64, 128)))};
}
/// a > b ? a : b lane by lane (maxpd), which is std::max(b, a) to the bit, NaN and signed zeros
/// included.
SOFTDROP_AVX inline V max(V a, V b) { return {_mm256_max_pd(a.lo, b.lo), _mm256_max_pd(a.hi, b.hi)}; }
SOFTDROP_AVX inline C no_counts() { return zero(); }
/// c + 1 in the lanes of m.
SOFTDROP_AVX inline C count(C c, M m) { return add(c, keep_or_zero(m, set1(1.0))); }
/// Adds the lanes of c to counts[0..8); whether any is not 0.
SOFTDROP_AVX inline bool add_counts(C c, int* counts) {
  alignas(32) double lanes[8];
  _mm256_store_pd(lanes, c.lo);
  _mm256_store_pd(lanes + 4, c.hi);
  bool any = false;
  for (int b = 0; b < 8; ++b) counts[b] += static_cast<int>(lanes[b]), any = any || lanes[b] != 0;
  return any;
}
SOFTDROP_AVX inline M both(M a, M b) { return {_mm256_and_pd(a.lo, b.lo), _mm256_and_pd(a.hi, b.hi)}; }
/// a and not b.
SOFTDROP_AVX inline M but_not(M a, M b) { return {_mm256_andnot_pd(b.lo, a.lo), _mm256_andnot_pd(b.hi, a.hi)}; }
SOFTDROP_AVX inline bool any(M m) { return bits(m) != 0; }
/// m ? a + b : a, lane by lane (a lane not in m adds -0, which leaves every double as it is).
SOFTDROP_AVX inline V add_where(M m, V a, V b) {
  return {x4_avx::add_where(m.lo, a.lo, b.lo), x4_avx::add_where(m.hi, a.hi, b.hi)};
}
/// m ? a - b : a, lane by lane (a lane not in m subtracts +0).
SOFTDROP_AVX inline V sub_where(M m, V a, V b) {
  return {x4_avx::sub_where(m.lo, a.lo, b.lo), x4_avx::sub_where(m.hi, a.hi, b.hi)};
}
#define SOFTDROP_LANE_TARGET SOFTDROP_AVX
#include "length_constraint_kernel.inc"
#undef SOFTDROP_LANE_TARGET

}  // namespace x8_avx

namespace x8_avx512 {

constexpr int kWidth = 8;  // lanes of a V
using V = __m512d;
using M = __mmask8;
using C = __m512i;

SOFTDROP_AVX512 inline V load(const double* p) { return _mm512_loadu_pd(p); }
SOFTDROP_AVX512 inline void store(double* p, V v) { _mm512_storeu_pd(p, v); }
SOFTDROP_AVX512 inline V set1(double d) { return _mm512_set1_pd(d); }
SOFTDROP_AVX512 inline V zero() { return _mm512_setzero_pd(); }
SOFTDROP_AVX512 inline V add(V a, V b) { return _mm512_add_pd(a, b); }
SOFTDROP_AVX512 inline V sub(V a, V b) { return _mm512_sub_pd(a, b); }
SOFTDROP_AVX512 inline V mul(V a, V b) { return _mm512_mul_pd(a, b); }
SOFTDROP_AVX512 inline V div(V a, V b) { return _mm512_div_pd(a, b); }
// All lanes (GCC 12's _mm512_sqrt_pd warns).
SOFTDROP_AVX512 inline V sqrt(V a) { return _mm512_mask_sqrt_pd(a, 0xFF, a); }
/// std::floor lane by lane (exact, as it is; all lanes, as sqrt).
SOFTDROP_AVX512 inline V floor(V a) {
  return _mm512_mask_roundscale_pd(a, 0xFF, a, _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC);
}
/// -a to the bit (the sign flipped, as C++'s unary minus does), with AVX-512F alone.
SOFTDROP_AVX512 inline V negate(V a) {
  return _mm512_castsi512_pd(
      _mm512_xor_si512(_mm512_castpd_si512(a), _mm512_set1_epi64(static_cast<long long>(0x8000000000000000ULL))));
}
template <int P>
SOFTDROP_AVX512 inline M compare(V a, V b) {
  return _mm512_cmp_pd_mask(a, b, P);
}
SOFTDROP_AVX512 inline unsigned bits(M m) { return m; }
SOFTDROP_AVX512 inline V blend(M m, V a, V b) { return _mm512_mask_blend_pd(m, a, b); }
SOFTDROP_AVX512 inline V keep_or_zero(M m, V a) { return _mm512_maskz_mov_pd(m, a); }
/// Lanes b < 8 where p[b] == v, as bits (AVX2's compare, which AVX-512F processors have).
SOFTDROP_AVX512 inline unsigned equal_lanes(const std::int32_t* p, std::int32_t v) {
  const __m256i eq = _mm256_cmpeq_epi32(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(p)), _mm256_set1_epi32(v));
  return static_cast<unsigned>(_mm256_movemask_ps(_mm256_castsi256_ps(eq)));
}
/// `lanes` (bit b: lane b) as eight int32 lanes, -1 where in, 0 elsewhere.
SOFTDROP_AVX512 inline __m256i int32_mask(unsigned lanes) {
  const __m256i bit = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
  return _mm256_cmpeq_epi32(_mm256_and_si256(_mm256_set1_epi32(static_cast<int>(lanes)), bit), bit);
}
/// p[b] = (bit b of `lanes`) ? -1 : 0 for b < 8.
SOFTDROP_AVX512 inline void store_minus_ones(std::int32_t* p, unsigned lanes) {
  _mm256_storeu_si256(reinterpret_cast<__m256i*>(p), int32_mask(lanes));
}
/// out[b] = (bit b of `lanes`) ? a[b] : other for b < 8.
SOFTDROP_AVX512 inline void select_lanes(unsigned lanes, const std::int32_t* a, std::int32_t other, std::int32_t* out) {
  const __m256i in = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(a));
  _mm256_storeu_si256(reinterpret_cast<__m256i*>(out),
                      _mm256_blendv_epi8(_mm256_set1_epi32(other), in, int32_mask(lanes)));
}
SOFTDROP_AVX512 inline M mask_of(unsigned lanes) { return static_cast<M>(lanes); }
/// a > b ? a : b lane by lane (maxpd), which is std::max(b, a) to the bit, NaN and signed zeros
/// included. All lanes (GCC 12's _mm512_max_pd warns, as sqrt).
SOFTDROP_AVX512 inline V max(V a, V b) { return _mm512_mask_max_pd(a, 0xFF, a, b); }
SOFTDROP_AVX512 inline C no_counts() { return _mm512_setzero_si512(); }
SOFTDROP_AVX512 inline C count(C c, M m) { return _mm512_mask_add_epi64(c, m, c, _mm512_set1_epi64(1)); }
SOFTDROP_AVX512 inline bool add_counts(C c, int* counts) {
  alignas(64) long long lanes[8];
  _mm512_store_si512(lanes, c);
  long long sum = 0;
  for (int b = 0; b < 8; ++b) counts[b] += static_cast<int>(lanes[b]), sum += lanes[b];
  return sum != 0;
}
SOFTDROP_AVX512 inline M both(M a, M b) { return static_cast<M>(a & b); }
/// a and not b.
SOFTDROP_AVX512 inline M but_not(M a, M b) { return static_cast<M>(a & ~b); }
SOFTDROP_AVX512 inline bool any(M m) { return m != 0; }
/// m ? a + b : a, lane by lane.
SOFTDROP_AVX512 inline V add_where(M m, V a, V b) { return _mm512_mask_add_pd(a, m, a, b); }
/// m ? a - b : a, lane by lane.
SOFTDROP_AVX512 inline V sub_where(M m, V a, V b) { return _mm512_mask_sub_pd(a, m, a, b); }
#define SOFTDROP_LANE_TARGET SOFTDROP_AVX512
#include "lane_policy.hpp"
#include "length_constraint_kernel.inc"
#undef SOFTDROP_LANE_TARGET

}  // namespace x8_avx512

}  // namespace softdrop::lanes
#endif
