#pragma once
// What the contact limit of one step leaves for the next step's collisions and contact limit, per
// mass of one droplet (part of its DropletRuntime; its stages fill and read it). Positions
// do not move between the contact limit and the next collisions, so a record is used only for a
// mass still at the recorded position to the bit, and every other writer of the droplet's state
// clears `current`.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "media/grain_grid.hpp"

namespace softdrop {

struct ContactCache {
  /// The discs each mass was inside at the end of the last step: up to `capacity` a mass in
  /// `discs`, `count` how many, at position (x, y) (NaN: no record). A mass inside more discs than
  /// the capacity, pushed, or moved since is looked up again.
  std::vector<GrainGrid::Disc> discs;
  std::vector<std::int32_t> count;
  std::vector<double> x, y;
  std::size_t capacity = 0;
  /// Each mass's anchor: within sqrt(clear_r2) of (clear_x, clear_y), where the contact limit last
  /// tested it against its cell, no disc can hold or push the mass, by DropletModel::clearance_margin
  /// (which covers rounding), except the clear_count discs it was inside there (clear_discs, up to
  /// `capacity` a mass, in the cell's order). The ball stays inside that cell and clear of the
  /// periodic seam. A mass still in its ball is tested against those discs only; -1 (or NaN) in
  /// clear_r2: not known.
  std::vector<double> clear_x, clear_y, clear_r2;
  std::vector<std::int32_t> clear_count;
  std::vector<GrainGrid::Disc> clear_discs;
  /// The first disc each mass was last found inside (x, y, r, grain), written with `discs`: a
  /// record of one disc is this alone, and for a mass whose anchor holds one disc it is that disc,
  /// so that the contact limit loads eight masses' at once (src/sim/contact_limit_wide.hpp). Otherwise
  /// it holds anything.
  std::vector<double> disc_x, disc_y, disc_r;
  std::vector<std::int32_t> disc_grain;
  /// For a record of count lanes::kOneDiscWithForce (written eight masses at a time, while their
  /// arrays are in cache) the collision's force against that disc, as the collisions compute it,
  /// and its grain in `touch`; -0, -0 and `no_grain` for the others.
  std::vector<double> fx, fy;
  std::vector<std::int32_t> touch;
  /// The masses whose collisions the recorded forces do not cover (inside other records, pushed,
  /// beyond a wall), in order, and the largest depth of those they do cover.
  std::vector<std::int32_t> todo;
  double deepest = 0;
  /// The records describe the droplet's state as it is: set by the contact limit, cleared by the
  /// collisions that use them and by every other writer of the state. Without it the collisions
  /// test every mass's record against its position.
  bool current = false;

  /// No record for any of `masses` masses, at most `capacity` discs a mass; `no_grain` is the
  /// touched set's entry for no grain. Allocates here so that a step allocates nothing.
  void reset(std::size_t masses, std::size_t disc_capacity, std::int32_t no_grain);
};

}  // namespace softdrop
