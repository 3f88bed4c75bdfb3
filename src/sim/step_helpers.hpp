#pragma once
// Small helpers of the step's stages and of the run's book-keeping, shared by their files.
#include <bit>
#include <cmath>
#include <cstdint>

namespace softdrop::step_detail {

// Equal to the bit (unlike ==, which does not tell -0 from +0, and NaN from itself).
inline bool same_bits(double a, double b) { return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b); }

// x - W floor(x / W), the position of x in [0, W). Inside the box (0 < x < 0.999999 W) that
// expression is x exactly (the quotient rounds below 1, so the floor is 0), so the division is
// skipped there: same bits, a division fewer per mass in the common case.
inline double wrap_periodic(double x, double W) { return x > 0 && x < 0.999999 * W ? x : x - W * std::floor(x / W); }

// A mass at x needs no wall force: the medium is periodic, or x is within [0, W] (NaN included, as
// the walls' tests `x < 0` and `x > W` are false for it).
inline bool within_walls(double x, bool periodic, double W) { return periodic || !(x < 0 || x > W); }

// Length of the segment from (ax, ay) to (bx, by).
inline double distance(double ax, double ay, double bx, double by) { return std::hypot(bx - ax, by - ay); }

// The length of a polyline's part inside the medium, 0 <= y < H, its crossings of y = H and y = 0
// interpolated: the path length of a run's centre of mass.
struct PathInMedium {
  double length = 0;
  bool entered = false;  // a point was below H

  // The segment from (px, py) to (x, y).
  void add(double px, double py, double x, double y, double H) { add(px, py, x, y, H, distance(px, py, x, y)); }
  // The same, given the segment's whole length, distance(px, py, x, y): a caller that needs that
  // length too computes it once (the same double either way).
  void add(double px, double py, double x, double y, double H, double whole) {
    if (!entered && y < H) {
      entered = true;
      const double f = (py - H) / (py - y);
      length += distance(px + f * (x - px), H, x, y);
    } else if (entered) {
      if (y < 0) {
        const double f = py / (py - y);
        length += distance(px, py, px + f * (x - px), 0);
      } else {
        length += whole;
      }
    }
  }
};

}  // namespace softdrop::step_detail
