// The lane-by-lane step of a block of droplets (lane_block_step.hpp), on AVX-512 or AVX.
#include "lane_block_step.hpp"

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "lane_layout.hpp"
#include "ring_contact.hpp"
#include "ring_stages.hpp"
#include "simd_dispatch.hpp"
#include "step_driver.hpp"

namespace softdrop {

#if defined(SOFTDROP_AVX_DISPATCH)
namespace {
// A thread's block: the lanes' x, y, px, py, fx, fy, and what the last step left in it. After a
// step the first four are each droplet's state (the copy out wrote x, y, and px, py are the
// positions the step began with in both), so a droplet still in the same lane whose state nothing
// has changed since (BlockSlot::id) need not be copied in again.
struct LaneBlock {
  std::vector<double> data;
  std::uint64_t last_id = 0;  // 0: the data is not a finished step's
  int lanes = 0, count = 0, masses = 0;
};
// Block ids are unique over threads (a droplet can change thread). Each thread takes them from
// the shared counter a chunk at a time, so that threads stepping blocks do not write one cache line
// at every step; only an id's equality with another matters, never its order or value.
std::atomic<std::uint64_t> next_block_chunk{1};
constexpr std::uint64_t kBlockIdChunk = std::uint64_t{1} << 16;
std::uint64_t new_block_id() {
  thread_local std::uint64_t next = 0, end = 0;
  if (next == end) {
    next = next_block_chunk.fetch_add(kBlockIdChunk, std::memory_order_relaxed);
    end = next + kBlockIdChunk;
  }
  return next++;
}
// n doubles of -0, a force that changes no double it is added to (the thread's own array).
const double* minus_zeros(int n) {
  thread_local std::vector<double> zeros;
  if (zeros.size() < static_cast<std::size_t>(n)) zeros.assign(static_cast<std::size_t>(n), -0.0);
  return zeros.data();
}
}  // namespace

// The block as a layout of the step (step_driver.hpp): droplets sims[0..count) of one set of
// parameters on a thread's copy of their positions laid out lane by lane, `registers` groups of
// eight lanes, L = 8 registers. The forces and integration are forces_k, viscosity_k and
// verlet_lanes of stage_kernels.inc, and the constraint lane_kernels.inc's, at eight lanes: the
// one-ring stages' kernels, and in their order. Gravity, the springs and the pressure are one pass
// over the block (forces_k), the gravity stage's; the collisions and the contact limit are each
// droplet's own (on the block's forces, then on its own arrays after the copy out).
struct LaneBlockStep::Layout {
  Simulation* const* sims;
  int count, n, registers, L;
  const StepContext& k;
  const DropletParams& p;
  double* block[6];                   // x, y, px, py, fx, fy
  double area[lanes::kMaxLanes];      // written by the gravity stage's pass, read by the collisions
  int corrections[lanes::kMaxLanes];  // the constraint's counts (unread)
  std::uint64_t id = 0;               // the block id the step gave its droplets (at the contact limit)
  RingPair* pairs = nullptr;          // the two-droplet pairs among the lanes
  int pair_count = 0;

  // Not an aggregate: the scratch arrays are left as they are, not zeroed at every step.
  Layout(Simulation* const* s, int c, int masses, int regs, const StepContext& constants, const DropletParams& params)
      : sims(s), count(c), n(masses), registers(regs), L(8 * regs), k(constants), p(params) {}

  // The ring-ring stages run between the rings of each pair (a block of single droplets has none).
  static constexpr bool kRingPairs = true;

  bool damped() const { return k.damped; }
  bool shaken() const {
    for (int t = 0; t < count; ++t)
      if (sims[t]->runtime().shake.on) return true;
    return false;
  }
  template <StepStage S>
  void stage();

  // A droplet's force on each of its masses, x and y; null: none.
  struct LaneForce {
    const double *fx = nullptr, *fy = nullptr;
  };
  // Adds force_of(runtime) to each lane's masses in the block's forces (padding lanes take the
  // last droplet's); a lane without one gets -0, which changes no double.
  template <class ForceOf>
  void add_lane_forces(ForceOf&& force_of) {
    const double* no_force = minus_zeros(n);
    const double* f[2][lanes::kMaxLanes];
    for (int t = 0; t < L; ++t) {
      const LaneForce lane = force_of(sims[std::min(t, count - 1)]->runtime());
      f[0][t] = lane.fx ? lane.fx : no_force;
      f[1][t] = lane.fy ? lane.fy : no_force;
    }
    lanes::add_in(f[0], block[4], n, registers);
    lanes::add_in(f[1], block[5], n, registers);
  }
};

template <>
void LaneBlockStep::Layout::stage<StepStage::gravity>() {
  // With the springs and the pressure: one pass over the block.
  lanes::forces_before_contacts(k, block[0], block[1], block[2], block[3], block[4], block[5], area, n, registers);
}
template <>
void LaneBlockStep::Layout::stage<StepStage::springs>() {}  // in the gravity stage's pass
template <>
void LaneBlockStep::Layout::stage<StepStage::pressure>() {}  // in the gravity stage's pass

template <>
void LaneBlockStep::Layout::stage<StepStage::vibration>() {
  // Each lane's force added as the one-ring stage adds it.
  add_lane_forces([](const DropletRuntime& r) {
    return r.shake.on ? LaneForce{r.shake.fx.data(), r.shake.fy.data()} : LaneForce{};
  });
}

template <>
void LaneBlockStep::Layout::stage<StepStage::collisions>() {
  // First the forces the contact limit recorded, for every lane whose droplet's records are
  // current, then each droplet's own.
  add_lane_forces([](const DropletRuntime& r) {
    return r.contact.current ? LaneForce{r.contact.fx.data(), r.contact.fy.data()} : LaneForce{};
  });
  for (int t = 0; t < count; ++t) {
    DropletRuntime& r = sims[t]->runtime();
    r.area = area[t];
    // Each droplet's own model: droplets of a block share the step's constants, not their medium.
    collisions_stage(sims[t]->model(), r, block[4] + t, block[5] + t, L, /*recorded_added=*/true);
  }
}

template <>
void LaneBlockStep::Layout::stage<StepStage::ring_contacts>() {
  // Each pair's, on the block's forces: the positions the stage reads are still each droplet's own.
  for (int q = 0; q < pair_count; ++q) {
    const RingPair& pair = pairs[q];
    ring_contacts_stage(sims[pair.a]->model(), sims[pair.a]->runtime(), sims[pair.b]->runtime(), pair.scratch,
                        RingForces{block[4] + pair.a, block[5] + pair.a, L},
                        RingForces{block[4] + pair.b, block[5] + pair.b, L});
  }
}

template <>
void LaneBlockStep::Layout::stage<StepStage::viscosity>() {
  lanes::viscosity(k, block[0], block[1], block[2], block[3], block[4], block[5], n, registers);
}

template <>
void LaneBlockStep::Layout::stage<StepStage::integrate>() {
  lanes::integrate(k.h2m, block[0], block[1], block[2], block[3], block[4], block[5], n, registers);
}

template <>
void LaneBlockStep::Layout::stage<StepStage::constraint>() {
  if (p.constraint_order == ConstraintOrder::sequential)
    lanes::constrain_sequential(block[0], block[1], n, registers, p.constraint_iterations, k.dmin, k.dmax, corrections);
  else
    lanes::constrain_red_black(block[0], block[1], n, registers, p.constraint_iterations, k.dmin, k.dmax, corrections);
}

template <>
void LaneBlockStep::Layout::stage<StepStage::contact_limit>() {
  // The centres of mass from the block, which Simulation::centre_of_mass gives after the step (the
  // contact limits seldom move a mass: then it sums the state again).
  double cx[lanes::kMaxLanes], cy[lanes::kMaxLanes];
  lanes::centres(block[0], block[1], n, registers, cx, cy);
  // Verlet left the positions the step began with as the previous ones, so px, py are x, y as they
  // still are in each state: moved there as the copy out overwrites them, rather than copied back
  // from the block. Padding lanes repeat the last droplet and are not copied back.
  double* out[2][lanes::kMaxLanes];
  double* previous[2][lanes::kMaxLanes];
  for (int t = 0; t < L; ++t) {
    DropletState& s = sims[std::min(t, count - 1)]->runtime().state;
    out[0][t] = t < count ? s.x.data() : nullptr;
    out[1][t] = t < count ? s.y.data() : nullptr;
    previous[0][t] = t < count ? s.px.data() : nullptr;
    previous[1][t] = t < count ? s.py.data() : nullptr;
  }
  for (int a = 0; a < 2; ++a) lanes::copy_out(out[a], block[a], n, registers, previous[a]);
  id = new_block_id();
  for (int t = 0; t < count; ++t) {
    DropletRuntime& r = sims[t]->runtime();
    r.block = BlockSlot{id, t, id, cx[t], cy[t]};
    r.contact.current = false;                 // the step moved every mass
    contact_limit_stage(sims[t]->model(), r);  // may move a mass, which clears r.block.id
  }
}

template <>
void LaneBlockStep::Layout::stage<StepStage::ring_limit>() {
  // On each droplet's own state, after its contact limit; a moved mass clears both block ids.
  for (int q = 0; q < pair_count; ++q) {
    RingPair& pair = pairs[q];
    pair.moved =
        ring_limit_stage(sims[pair.a]->model(), sims[pair.a]->runtime(), sims[pair.b]->runtime(), pair.scratch);
  }
}

void LaneBlockStep::step(Simulation* const* sims, int count, RingPair* pairs, int pair_count) {
  const DropletModel& model = sims[0]->model();
  const int n = sims[0]->state().size();
  const int registers = (count + 7) / 8, L = 8 * registers;
  const std::size_t size = static_cast<std::size_t>(n) * static_cast<std::size_t>(L);
  thread_local LaneBlock memory;
  const bool same_layout = memory.last_id != 0 && memory.lanes == L && memory.masses == n;
  const std::uint64_t previous_id = same_layout ? memory.last_id : 0;
  const bool same_padding = same_layout && memory.count == count;
  memory.last_id = 0;  // until this step has finished
  if (memory.data.size() < 6 * size) memory.data.resize(6 * size);
  double* const X = memory.data.data();
  Layout layout(sims, count, n, registers, model.context, model.params);
  for (int q = 0; q < pair_count; ++q)
    if (const RingPair& r = pairs[q]; r.a < 0 || r.b < 0 || r.a >= count || r.b >= count || r.a == r.b)
      throw std::logic_error("LaneBlockStep: a pair's lanes are not two of the block's");
  layout.pairs = pairs;
  layout.pair_count = pair_count;
  for (int a = 0; a < 6; ++a) layout.block[a] = X + static_cast<std::size_t>(a) * size;
  // The lanes whose droplet is not in the block as the last step left it (padding lanes repeat
  // the last droplet's, and are there if the last step had as many droplets).
  double* in[4][lanes::kMaxLanes];
  bool stale[lanes::kMaxLanes];
  int stale_lanes = 0;
  for (int t = 0; t < L; ++t) {
    const int d = std::min(t, count - 1);
    DropletRuntime& r = sims[d]->runtime();
    DropletState& s = r.state;
    double* const arrays[4] = {s.x.data(), s.y.data(), s.px.data(), s.py.data()};
    for (int a = 0; a < 4; ++a) in[a][t] = arrays[a];
    stale[t] = previous_id == 0 || r.block.id != previous_id || r.block.lane != d || (t >= count && !same_padding);
    stale_lanes += stale[t];
  }
  if (stale_lanes > L / 4) {
    for (int a = 0; a < 4; ++a) lanes::copy_in(in[a], layout.block[a], n, registers);
  } else if (stale_lanes > 0) {
    for (int t = 0; t < L; ++t)
      if (stale[t])
        for (int a = 0; a < 4; ++a)
          for (int i = 0; i < n; ++i) layout.block[a][static_cast<std::size_t>(i) * L + t] = in[a][t][i];
  }
  run_stages(layout);
  memory.last_id = layout.id;
  memory.lanes = L;
  memory.count = count;
  memory.masses = n;
}
#else
void LaneBlockStep::step(Simulation* const*, int, RingPair*, int) {
  throw std::logic_error("lane-by-lane step without AVX");
}
#endif

}  // namespace softdrop
