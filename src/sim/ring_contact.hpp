#pragma once
// Contacts between the rings of two droplets: the ring_contacts and ring_limit stages of a step
// with two droplets (the pairs of a RingGroup or of a lane-by-lane block). Private to the library.
//
// Each ring is the other's obstacle, thickened by the contact limit's depth: a mass of one ring
// within max_depth of the other's boundary, or inside it, is in contact with the nearest edge.
// The contact is the grains' (docs/model.md): the penalty k_c (depth) with damping c_c of the
// normal velocity, relative to the edge's point here, never pulling; and the limit, which moves a
// mass no deeper than max_depth, i.e. never inside the other ring, and stops its approach. Every
// force and every correction acts on the mass and, opposite, on the edge's two ends in the
// proportions of the contact point (1 - t, t): the pair's momentum is unchanged by both stages.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "droplet_model.hpp"
#include "droplet_runtime.hpp"

namespace softdrop {

// An axis-aligned box, [x0, x1] x [y0, y1] (length units).
struct RingBox {
  double x0 = 0, x1 = 0, y0 = 0, y1 = 0;
  /// The box of the point (x, y) alone.
  static RingBox at(double x, double y) { return {x, x, y, y}; }
  /// Widens the box to hold (x, y).
  void add(double x, double y) {
    x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
  }
  /// Whether (x, y) lies within `margin` of the box.
  bool near(double x, double y, double margin) const {
    return !(x < x0 - margin || x > x1 + margin || y < y0 - margin || y > y1 + margin);
  }
};

// A uniform grid of one ring's edges, rebuilt for each use (O(N)): edge j, from mass j to mass
// j + 1, is listed in every cell that its bounding box, widened by `reach`, overlaps, so a point
// finds every edge within reach of it in its own cell. The cells are hashed into a table of a
// power-of-two size of at least 2 N entries; a cell shares its list with the cells hashed alike
// (an edge may then be listed twice), which costs a few distance tests more and changes no
// result. Each list ascends.
class EdgeGrid {
 public:
  /// Lists the edges of `ring`, its x shifted by shift_x (a periodic copy), within `reach`; with
  /// `only`, just the edges whose box widened by `reach` meets it (in the shifted frame), for
  /// queries from points inside `only` alone.
  void build(const DropletState& ring, double shift_x, double reach, const RingBox* only = nullptr);
  /// The edges listed in the cell of (x, y) (in the shifted frame): [*begin, *end).
  void cell(double x, double y, const std::int32_t** begin, const std::int32_t** end) const;
  double shift() const { return shift_; }

 private:
  std::uint64_t bucket(std::int64_t ix, std::int64_t iy) const;
  double cell_ = 1, shift_ = 0;
  std::uint64_t mask_ = 0;
  std::vector<std::int32_t> start_, entries_;  // each bucket's first entry; the edges, bucket by bucket
  // The build's scratch, kept so that a step allocates nothing once the sizes are reached: each
  // listing's bucket and edge, and each bucket's next free entry.
  std::vector<std::uint64_t> cells_;
  std::vector<std::int32_t> listed_, next_;
};

// The two rings' scratch: each ring's edge grid.
struct RingContactScratch {
  EdgeGrid edges[2];
  std::int64_t contacts = 0;  ///< masses in contact with the other ring in the last ring_contacts
};

// Where the ring_contacts stage adds one ring's forces: mass i's at fx[i * stride], fy[i * stride]
// (a ring's own arrays, or its lane of a lane-by-lane block's forces).
struct RingForces {
  double* fx = nullptr;
  double* fy = nullptr;
  std::ptrdiff_t stride = 1;
  /// The ring's own force arrays.
  static RingForces of(DropletRuntime& r) { return {r.state.fx.data(), r.state.fy.data(), 1}; }
};

// Two droplets of a layout (ring_group_step.hpp, lane_block_step.hpp) that run in one medium: the
// layout's droplets a and b, between which the ring-ring stages run, with the pair's scratch;
// `moved` is what the step's ring limit moved.
struct RingPair {
  int a = 0, b = 0;
  RingContactScratch* scratch = nullptr;
  int moved = 0;
};

/// The ring_contacts stage: the penalty forces between the masses of each ring and the edges of
/// the other, added to both rings' forces, fa and fb (a's masses first, then b's). It reads the
/// positions of the rings' own states.
void ring_contacts_stage(const DropletModel& m, const DropletRuntime& a, const DropletRuntime& b,
                         RingContactScratch* scratch, RingForces fa, RingForces fb);
/// The ring_limit stage: no mass of either ring inside the other (a's masses first, then b's).
/// Returns the number of masses moved. A ring whose masses moved is changed(): the contact limit's
/// records of it no longer hold.
int ring_limit_stage(const DropletModel& m, DropletRuntime& a, DropletRuntime& b, RingContactScratch* scratch);

/// The x shift that brings ring b next to ring a in a periodic medium of width W (a multiple of
/// W; 0 for walls): the rings' coordinates are unwrapped, each on its own.
double periodic_shift(const DropletState& a, const DropletState& b, const Medium& medium);

/// Whether the rings' bounding boxes, each widened by `reach`, overlap (in a periodic medium, b's
/// nearest copy): the conservative test that a second droplet starts clear of the first.
bool rings_within(const DropletState& a, const DropletState& b, const Medium& medium, double reach);

}  // namespace softdrop
