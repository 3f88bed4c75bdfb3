// The lane-by-lane step of a block of droplets (lane_block_step.hpp), on AVX-512 or AVX.
#include "lane_block_step.hpp"

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "lane_layout.hpp"
#include "simd_dispatch.hpp"
#include "step_test_seam.hpp"

namespace softdrop {

#if defined(SOFTDROP_TEST_HOOKS)
std::atomic<test_seam::StepMutation>& test_seam::step_mutation() {
  static std::atomic<StepMutation> mutation{StepMutation::none};
  return mutation;
}
#endif

#if defined(SOFTDROP_AVX_DISPATCH)
namespace {
// A thread's block: the lanes' x, y, px, py, fx, fy, and what the last step left in it. After a
// step the first four are each droplet's state (the copy out wrote x, y, and px, py are the
// positions the step began with in both), so a droplet still in the same lane whose state nothing
// has changed since (Simulation::block_id_) need not be copied in again.
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
}  // namespace

void LaneBlockStep::step(Simulation* const* sims, int count) {
  const Simulation& first = *sims[0];
  const DropletParams& p = first.params_;
  const int n = first.state_.size();
  const int registers = (count + 7) / 8, L = 8 * registers;
  const std::size_t size = static_cast<std::size_t>(n) * static_cast<std::size_t>(L);
  thread_local LaneBlock memory;
  const bool same_layout = memory.last_id != 0 && memory.lanes == L && memory.masses == n;
  const std::uint64_t previous_id = same_layout ? memory.last_id : 0;
  const bool same_padding = same_layout && memory.count == count;
  memory.last_id = 0;  // until this step has finished
  if (memory.data.size() < 6 * size) memory.data.resize(6 * size);
  double* const X = memory.data.data();
  double* const block[6] = {X, X + size, X + 2 * size, X + 3 * size, X + 4 * size, X + 5 * size};
  double *FX = block[4], *FY = block[5];
  // Padding lanes repeat the last droplet and are not copied back.
  double* in[4][lanes::kMaxLanes];
  double* out[2][lanes::kMaxLanes];
  double* previous[2][lanes::kMaxLanes];
  for (int t = 0; t < L; ++t) {
    DropletState& s = sims[std::min(t, count - 1)]->state_;
    double* const arrays[4] = {s.x.data(), s.y.data(), s.px.data(), s.py.data()};
    for (int a = 0; a < 4; ++a) in[a][t] = arrays[a];
    for (int a = 0; a < 2; ++a) out[a][t] = t < count ? arrays[a] : nullptr;
    for (int a = 0; a < 2; ++a) previous[a][t] = t < count ? arrays[a + 2] : nullptr;
  }
  // The lanes whose droplet is not in the block as the last step left it (padding lanes repeat
  // the last droplet's, and are there if the last step had as many droplets).
  bool stale[lanes::kMaxLanes];
  int stale_lanes = 0;
  for (int t = 0; t < L; ++t) {
    const int d = std::min(t, count - 1);
    const Simulation& sim = *sims[d];
    stale[t] =
        previous_id == 0 || sim.block_id_ != previous_id || sim.block_lane_ != d || (t >= count && !same_padding);
    stale_lanes += stale[t];
  }
  if (stale_lanes > L / 4) {
    for (int a = 0; a < 4; ++a) lanes::copy_in(in[a], block[a], n, registers);
  } else if (stale_lanes > 0) {
    for (int t = 0; t < L; ++t)
      if (stale[t])
        for (int a = 0; a < 4; ++a)
          for (int i = 0; i < n; ++i) block[a][static_cast<std::size_t>(i) * L + t] = in[a][t][i];
  }
  const StepContext& k = *first.context_;
  double area[lanes::kMaxLanes];
  thread_local std::vector<double> no_force;
  const double dmax = k.dmax, dmin = k.dmin;
  int corrections[lanes::kMaxLanes];
  // The stages of kStepStages up to the constraint; the contact limit is each droplet's own
  // (run_interleaved runs it after this).
  auto run = [&](StepStage stage) {
    switch (stage) {
      case StepStage::gravity:  // with the springs and the pressure: one pass over the block
        lanes::forces_before_contacts(k, block[0], block[1], block[2], block[3], FX, FY, area, n, registers);
        return;
      case StepStage::springs:
      case StepStage::pressure:
        return;  // in the gravity stage's pass
      case StepStage::collisions: {
        // First the forces the contact limit recorded, for every lane whose droplet's records
        // are current (-0, which changes no double, for the others), then each droplet's own.
        if (no_force.size() < static_cast<std::size_t>(n)) no_force.assign(static_cast<std::size_t>(n), -0.0);
        const double* recorded[2][lanes::kMaxLanes];
        for (int t = 0; t < L; ++t) {
          const Simulation& sim = *sims[std::min(t, count - 1)];
          recorded[0][t] = sim.contact_.current ? sim.contact_.fx.data() : no_force.data();
          recorded[1][t] = sim.contact_.current ? sim.contact_.fy.data() : no_force.data();
        }
        lanes::add_in(recorded[0], FX, n, registers);
        lanes::add_in(recorded[1], FY, n, registers);
        for (int t = 0; t < count; ++t) {
          sims[t]->area_ = area[t];
          sims[t]->accumulate_collisions(FX + t, FY + t, L, /*recorded_added=*/true);
        }
        return;
      }
      case StepStage::viscosity:
        if (p.viscosity > 0) lanes::viscosity(k, block[0], block[1], block[2], block[3], FX, FY, n, registers);
        return;
      case StepStage::integrate:
        lanes::integrate(k.h2m, block[0], block[1], block[2], block[3], FX, FY, n, registers);
        return;
      case StepStage::constraint:
        if (p.constraint_order == ConstraintOrder::sequential)
          lanes::constrain_sequential(block[0], block[1], n, registers, p.constraint_iterations, dmin, dmax,
                                      corrections);
        else
          lanes::constrain_red_black(block[0], block[1], n, registers, p.constraint_iterations, dmin, dmax,
                                     corrections);
        return;
      case StepStage::contact_limit:
        throw std::logic_error("LaneBlockStep: the contact limit is each droplet's own");
    }
  };
  bool mutated = false;
#if defined(SOFTDROP_TEST_HOOKS)
  mutated = test_seam::step_mutation() == test_seam::StepMutation::block_damps_before_collisions;
#endif
  if (mutated)
    for (StepStage s :
         {StepStage::gravity, StepStage::viscosity, StepStage::collisions, StepStage::integrate, StepStage::constraint})
      run(s);
  else
    run_step_stages(run, StepStage::gravity, StepStage::constraint);
  // The centres of mass from the block (run_interleaved needs them after the contact limits, which
  // seldom move a mass: then they are computed again from the state).
  double cx[lanes::kMaxLanes], cy[lanes::kMaxLanes];
  lanes::centres(block[0], block[1], n, registers, cx, cy);
  // Verlet left the positions the step began with as the previous ones, so px, py are x, y as they
  // still are in each state: moved there as the copy out overwrites them, rather than copied back
  // from the block.
  for (int a = 0; a < 2; ++a) lanes::copy_out(out[a], block[a], n, registers, previous[a]);
  const std::uint64_t id = new_block_id();
  for (int t = 0; t < count; ++t) {
    sims[t]->block_id_ = id;
    sims[t]->block_lane_ = t;
    sims[t]->block_centre_id_ = id;
    sims[t]->block_cx_ = cx[t];
    sims[t]->block_cy_ = cy[t];
    sims[t]->contact_.current = false;  // the step moved every mass
  }
  memory.last_id = id;
  memory.lanes = L;
  memory.count = count;
  memory.masses = n;
}
#else
void LaneBlockStep::step(Simulation* const*, int) { throw std::logic_error("lane-by-lane step without AVX"); }
#endif

}  // namespace softdrop
