#pragma once
// The length constraint's correction of one spring (Provot's): a spring longer than dmax or shorter
// than dmin is brought back to that limit, both ends moved by half the excess along the spring.
// This is length_constraint_kernel.inc, the correction written once for every vector width, at width 1
// (lane_scalar.hpp): the one-ring constraints' scalar springs (the sequential order's chain, and
// the red-black order's last springs) and every vector lane agree to the bit. Internal to the
// simulator.

#include "lane_scalar.hpp"

namespace softdrop::constraint_detail {

// Brings the spring between (xi, yi) and (xj, yj) back inside [dmin, dmax]; returns 1 if it moved
// its ends (a spring of no length is left as it is; a NaN length counts as out of the limits).
inline int constrain_ends(double* xi, double* yi, double* xj, double* yj, double dmin, double dmax) {
  lanes::scalar::Limits l;
  lanes::scalar::set_limits(&l, dmin, dmax);
  return lanes::scalar::constrain_springs(l, xi, yi, xj, yj) ? 1 : 0;
}

inline int constrain(double* x, double* y, int i, int j, double dmin, double dmax) {
  return constrain_ends(x + i, y + i, x + j, y + j, dmin, dmax);
}

}  // namespace softdrop::constraint_detail
