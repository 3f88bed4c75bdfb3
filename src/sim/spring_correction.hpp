#pragma once
// The length constraint's correction of one spring (Provot's): a spring longer than dmax or shorter
// than dmin is brought back to that limit, both ends moved by half the excess along the spring.
// This is the one-spring form, whose branches suit the sequential order's chain of dependent
// springs; spring_kernel.inc is the same correction on every lane of a vector, with the same
// operations in the same order, so the two agree to the bit. Internal to the simulator.

#include <cmath>

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

}  // namespace softdrop::constraint_detail
