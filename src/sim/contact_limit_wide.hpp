#pragma once
// The contact limit's common cases eight masses at a time (internal), with AVX-512 or AVX,
// whichever constraint_vector_width() says: call it only where that is at least VectorWidth::avx.
// Most masses' steps end free in their anchor's ball, or in the ball of an anchor that holds one
// disc (touching it or not); few need the full test of their cell or have anchors of several
// discs (the shares: bench/README.md, "Constants of the step"). The first two go eight at a time here, at wrapped
// positions too, each lane doing the operations of the one-ring code, in its order, so
// every mass gets the same bits; the rest stay with the scalar code. For the masses inside their
// anchor's one disc the kernel also computes the next collisions' force (the positions and
// velocities do not change in between), while the masses' arrays are in cache: the collisions
// then only add it (collisions_stage).

#include <cstdint>

#include "lane_policy.hpp"

namespace softdrop::lanes {

/// A record's count for a mass inside one disc, the disc above, whose collision force (as
/// collisions_stage would compute it at that position and velocity) is recorded as well.
constexpr std::int32_t kOneDiscWithForce = -1;

/// One ring's contact records (its runtime arrays, by mass).
struct ContactRecords {
  const double *x = nullptr, *y = nullptr;
  /// The anchors: a mass within r2 of (x, y) can only touch or be pushed by the `count` discs.
  const double *clear_x = nullptr, *clear_y = nullptr, *clear_r2 = nullptr;
  const std::int32_t* clear_count = nullptr;
  /// The disc of an anchor that holds one (ContactCache::disc_x and so on).
  const double *disc_x = nullptr, *disc_y = nullptr, *disc_r = nullptr;
  /// The disc's grain, and the entry of the touched set that stands for none (the medium's count).
  const std::int32_t* disc_grain = nullptr;
  std::int32_t no_grain = 0;
  /// For the forces: the previous positions, and DropletParams' kc, cc and 1 / dt.
  const double *px = nullptr, *py = nullptr;
  double kc = 0, cc = 0, inv_dt = 0;
  /// The records for the next collisions: how many discs each mass is inside, at which position;
  /// a record of one disc is the disc above. The collisions' force on each mass recorded
  /// kOneDiscWithForce, and the grain it touches (-0, -0 and no_grain for the others).
  double *contact_x = nullptr, *contact_y = nullptr;
  std::int32_t* contact_count = nullptr;
  double *force_x = nullptr, *force_y = nullptr;
  std::int32_t* touch = nullptr;
  bool periodic = false;
  /// With a periodic medium: its width W, and 0.999999 W, below which (and above 0) the wrapped
  /// x is x itself.
  double width = 0, wrap_below = 0;
};

/// The contact limit's test for the groups of eight masses 8 g to 8 g + 7, g from first to
/// first + groups - 1, inside their anchor's ball: those that the anchor says touch nothing or
/// only its one disc, which does not push them, get their records (count 0, or kOneDiscWithForce
/// with the force and the grain where the scalar code records 1 and leaves them to the
/// collisions; the position; the disc); deepest[b] (eight lanes) becomes std::max(deepest[b],
/// depth) for each mass 8 g + b inside its disc. todo[g - first] gets the others (bit b: mass
/// 8 g + b), and those beyond a wall, whose records it leaves to be overwritten: the caller tests
/// them one by one. max_depth: DropletParams::max_depth.
void limit_groups(const ContactRecords& r, int first, int groups, double max_depth, double* deepest, unsigned* todo);

}  // namespace softdrop::lanes
