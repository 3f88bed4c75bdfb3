#pragma once
// The length constraint's correction of one spring (Provot's): a spring longer than dmax or shorter
// than dmin is brought back to that limit, both ends moved by half the excess along the spring.
// Written once for one spring and once for two (SSE2); the four- and eight-spring forms are in
// lane_simd.hpp. Every form does the same operations in the same order, so they agree to the bit.
// Internal to the simulator (length_constraint.cpp, interleaved_constraint.cpp).

#include <cmath>

#include "simd_dispatch.hpp"

namespace softdrop::constraint_detail {

// Brings the spring between (xi, yi) and (xj, yj) back inside [dmin, dmax]; returns 1 if it moved
// its ends.
inline int constrain_ends(double* xi, double* yi, double* xj, double* yj, double dmin, double dmax) {
  const double dx = *xj - *xi, dy = *yj - *yi;
  const double d2 = dx * dx + dy * dy, dmax2 = dmax * dmax;
  if (d2 <= dmax2 && d2 >= dmin * dmin) return 0;
  const double d = std::sqrt(d2);
  if (d == 0) return 0;
  // Stretched or compressed is decided on d2, as the test above was: a d2 just above dmax^2 can
  // have a square root that rounds to dmax, and "d > dmax" would then call it compressed and pull
  // the spring down to dmin.
  const double target = d2 > dmax2 ? dmax : dmin;
  // > 0 pulls the ends together, < 0 pushes apart. (d - target) / (d + d) is 0.5 (d - target) / d
  // to the bit (halving and doubling are exact), with the halving off the chain of dependent
  // operations.
  const double c = (d - target) / (d + d);
  *xi += c * dx;
  *yi += c * dy;
  *xj -= c * dx;
  *yj -= c * dy;
  return 1;
}

inline int constrain(double* x, double* y, int i, int j, double dmin, double dmax) {
  return constrain_ends(x + i, y + i, x + j, y + j, dmin, dmax);
}

#if defined(__SSE2__)
// Two springs at once, lane by lane the operations of constrain_ends() in the same order on the
// same values, so the bits are those of the scalar code. Returns the lanes whose spring moved, as
// _mm_movemask_pd gives them (bit 0: low lane, bit 1: high lane).
struct PairLimits {
  __m128d dmax = {}, dmin = {}, dmax2 = {}, dmin2 = {};
  PairLimits(double lo, double hi)
      : dmax(_mm_set1_pd(hi)), dmin(_mm_set1_pd(lo)), dmax2(_mm_set1_pd(hi * hi)), dmin2(_mm_set1_pd(lo * lo)) {}
};
inline int constrain_two(const PairLimits& l, __m128d* xi, __m128d* yi, __m128d* xj, __m128d* yj) {
  const __m128d dx = _mm_sub_pd(*xj, *xi), dy = _mm_sub_pd(*yj, *yi);
  const __m128d d2 = _mm_add_pd(_mm_mul_pd(dx, dx), _mm_mul_pd(dy, dy));
  // Out of limits (NaN included, as in the scalar test) and not of zero length.
  const __m128d inside = _mm_and_pd(_mm_cmple_pd(d2, l.dmax2), _mm_cmpge_pd(d2, l.dmin2));
  const __m128d out = _mm_andnot_pd(inside, _mm_cmpneq_pd(d2, _mm_setzero_pd()));
  const int mask = _mm_movemask_pd(out);
  if (mask == 0) return 0;
  const __m128d d = _mm_sqrt_pd(d2);
  const __m128d longer = _mm_cmpgt_pd(d2, l.dmax2);
  const __m128d target = _mm_or_pd(_mm_and_pd(longer, l.dmax), _mm_andnot_pd(longer, l.dmin));
  const __m128d c = _mm_div_pd(_mm_sub_pd(d, target), _mm_add_pd(d, d));
  const __m128d cx = _mm_and_pd(out, _mm_mul_pd(c, dx)), cy = _mm_and_pd(out, _mm_mul_pd(c, dy));
  // Lanes in limits add -0 and subtract +0, which leave every double (-0 included) as it is.
  const __m128d keep = _mm_andnot_pd(out, _mm_set1_pd(-0.0));
  *xi = _mm_add_pd(*xi, _mm_or_pd(cx, keep));
  *yi = _mm_add_pd(*yi, _mm_or_pd(cy, keep));
  *xj = _mm_sub_pd(*xj, cx);
  *yj = _mm_sub_pd(*yj, cy);
  return mask;
}
#endif

}  // namespace softdrop::constraint_detail
