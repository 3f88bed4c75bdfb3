#pragma once
// One lane (internal): lanes::scalar has the names of lane_simd.hpp's namespaces for V = double,
// and with them the correction of one spring (length_constraint_kernel.inc) and the force and integration
// stages' kernels (stage_kernels.inc) at width 1, which one droplet's stages run on its own
// arrays. Every operation is the C++ one, so each gives the bits the vector namespaces give a
// lane.

#include <cmath>
#include <cstddef>

#include "lane_layout.hpp"
#include "simd_dispatch.hpp"

#if !defined(_CMP_NEQ_UQ)  // the predicates' values in <immintrin.h>, for processors without it
#define _CMP_LE_OS 0x02
#define _CMP_NEQ_UQ 0x04
#define _CMP_GE_OS 0x0d
#define _CMP_GT_OS 0x0e
#define _CMP_GT_OQ 0x1e
#endif

namespace softdrop::lanes::scalar {

constexpr int kWidth = 1;
using V = double;
using M = bool;

inline V load(const double* p) { return *p; }
inline void store(double* p, V v) { *p = v; }
inline V set1(double d) { return d; }
inline V zero() { return 0.0; }
inline V add(V a, V b) { return a + b; }
inline V sub(V a, V b) { return a - b; }
inline V mul(V a, V b) { return a * b; }
inline V div(V a, V b) { return a / b; }
inline V sqrt(V a) { return std::sqrt(a); }
inline V negate(V a) { return -a; }
/// `a P b` for the predicates the kernels use: _CMP_NEQ_UQ (true if either is NaN, as !=), and
/// the ordered ones (false then, as <=, >= and >).
template <int P>
inline M compare(V a, V b) {
  if constexpr (P == _CMP_NEQ_UQ)
    return a != b;
  else if constexpr (P == _CMP_LE_OS)
    return a <= b;
  else if constexpr (P == _CMP_GE_OS)
    return a >= b;
  else {
    static_assert(P == _CMP_GT_OS || P == _CMP_GT_OQ, "no scalar compare for this predicate");
    return a > b;
  }
}
inline M both(M a, M b) { return a && b; }
/// a and not b.
inline M but_not(M a, M b) { return a && !b; }
inline bool any(M m) { return m; }
inline unsigned bits(M m) { return m ? 1u : 0u; }
/// m ? b : a.
inline V blend(M m, V a, V b) { return m ? b : a; }
/// m ? a : +0.
inline V keep_or_zero(M m, V a) { return m ? a : 0.0; }
/// m ? a + b : a.
inline V add_where(M m, V a, V b) { return m ? a + b : a; }
/// m ? a - b : a.
inline V sub_where(M m, V a, V b) { return m ? a - b : a; }

#define SOFTDROP_LANE_TARGET
#include "length_constraint_kernel.inc"
#include "stage_kernels.inc"
#undef SOFTDROP_LANE_TARGET

}  // namespace softdrop::lanes::scalar
