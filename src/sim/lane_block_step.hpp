#pragma once
// LaneBlockStep: droplets of one set of parameters stepped together, a droplet per vector lane.
#include <cstddef>

#include "droplet_runtime.hpp"
#include "softdrop/droplet.hpp"
#include "softdrop/simulation.hpp"

namespace softdrop {

struct RingPair;

// Droplets of one set of parameters, stepped together on a copy of their positions laid out lane
// by lane (lane_layout.hpp), eight to a group (an AVX-512 register or two AVX ones): forces,
// integration and constraint (either order) as vector code across droplets, where the one-ring
// forms are chains of dependent sums and square roots; the collisions (a grid look-up per mass)
// droplet by droplet on that copy, the contact limit on each droplet's own state afterwards. Each lane does the
// one-ring stages' operations in their order, so every droplet gets the bits step() gives it. Its forces stay in the
// copy: state().fx, fy are not updated.
struct LaneBlockStep {
  // Whether droplets of parameters a and b can share a block: the same constants for every stage
  // that runs across lanes (the collisions and the contact limit run droplet by droplet).
  static bool compatible(const DropletParams& a, const DropletParams& b) { return same_fields(a, b, FieldUse::forces); }
  // step() of sims[0..count), count <= lanes::kMaxLanes, all compatible with sims[0]: the stages of
  // kStepStages over the block's layout (step_driver.hpp), the contact limit on each droplet's own
  // state after the copy out. Each droplet's validity test is then sims[t]->valid().
  // pairs[0..pair_count): the lanes of two droplets in one medium (ring_contact.hpp), each lane in
  // one pair at most, with the ring-ring stages between them.
  static void step(Simulation* const* sims, int count, RingPair* pairs = nullptr, int pair_count = 0);

 private:
  struct Layout;  // the block as a layout of the step driver (lane_block_step.cpp)
};

}  // namespace softdrop
