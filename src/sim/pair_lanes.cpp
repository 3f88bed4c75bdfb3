// run_pairs_interleaved: pairs of droplets stepped together on one thread, their rings as a
// lane-by-lane block (lane_block_step.hpp) or a ring group (ring_group_step.hpp), with the
// ring-ring stages between each pair's two rings.
#include "pair_lanes.hpp"

#include <cstddef>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "lane_block_step.hpp"
#include "lane_layout.hpp"
#include "lane_policy.hpp"
#include "ring_contact.hpp"
#include "ring_group_step.hpp"
#include "two_droplet_run.hpp"

namespace softdrop {

namespace {

struct Slot {
  std::unique_ptr<TwoDropletRun> run;
  std::int64_t id = 0;
  int lanes = 0;  // its rings stepped this step (0, 1 or 2)
};

// The rings as lane-by-lane blocks of at most kMaxLanes, each filled as far as it goes before the
// next begins (the fewest groups of eight lanes), a pair's two rings in the same block. ring_pairs'
// lanes are counted from the first ring; each block's are made its own.
void step_blocks(const std::vector<Slot>& slots, std::vector<Simulation*>& rings, std::vector<RingPair>& ring_pairs) {
  const int total = static_cast<int>(rings.size());
  std::size_t s = 0, q = 0;
  for (int begin = 0; begin < total;) {
    int end = begin;
    const std::size_t first_pair = q;
    for (; s < slots.size(); ++s) {
      const Slot& slot = slots[s];
      if (!slot.run) continue;
      if (end + slot.lanes - begin > lanes::kMaxLanes) break;
      end += slot.lanes;
      if (slot.lanes == 2) ring_pairs[q].a -= begin, ring_pairs[q].b -= begin, ++q;
    }
    LaneBlockStep::step(rings.data() + begin, end - begin, ring_pairs.data() + first_pair,
                        static_cast<int>(q - first_pair));
    begin = end;
  }
}

}  // namespace

void run_pairs_interleaved(int lanes, const DropletParams& droplet, const Medium& medium, const RunOptions& options,
                           const SecondDroplet& second, const std::function<bool(PairJob*)>& next,
                           const std::function<void(std::int64_t id, TwoDropletSummary&&)>& done) {
  if (lanes < 2 || lanes > 64) throw std::invalid_argument("lanes = " + std::to_string(lanes) + ": must be in [2, 64]");
  std::vector<Slot> slots(static_cast<std::size_t>(lanes - 1));  // at most a lane each, and a pair starts in two
  const bool lane_wise = constraint_vector_width() >= VectorWidth::avx;
  std::vector<Simulation*> rings;
  std::vector<RingPair> ring_pairs;
  std::vector<DropletState*> group_rings;  // a ring group's scratch
  std::vector<int> corrections;
  bool more = true;
  for (;;) {
    int held = 0;
    for (const Slot& slot : slots)
      if (slot.run) held += slot.run->lanes_held();
    for (Slot& slot : slots) {
      PairJob job;
      if (slot.run || held + 2 > lanes || !more || !(more = next(&job))) continue;
      slot.run = std::make_unique<TwoDropletRun>(droplet, medium, job.x0, options, second);
      slot.id = job.id;
      held += 2;
    }
    rings.clear();
    ring_pairs.clear();
    for (Slot& slot : slots) {
      if (!slot.run) continue;
      Simulation *a = nullptr, *b = nullptr;
      slot.run->begin_step(&a, &b);
      const int first = static_cast<int>(rings.size());
      for (Simulation* sim : {a, b})
        if (sim) rings.push_back(sim);
      slot.lanes = static_cast<int>(rings.size()) - first;
      if (slot.lanes == 2) ring_pairs.push_back({first, first + 1, slot.run->scratch(), 0});
    }
    if (rings.empty()) return;  // a pair still running steps a ring; every slot is empty, and next() said no
    if (lane_wise && rings.size() >= fewest_block_droplets()) {
      step_blocks(slots, rings, ring_pairs);
    } else {
      RingGroup group{rings.data(),      static_cast<int>(rings.size()),     &group_rings, &corrections,
                      ring_pairs.data(), static_cast<int>(ring_pairs.size())};
      run_stages(group);
    }
    for (std::size_t q = 0; Slot & slot : slots)
      if (slot.run) slot.run->end_step(slot.lanes == 2 ? ring_pairs[q++].moved : 0);
    for (Slot& slot : slots) {
      if (!slot.run || !slot.run->finished()) continue;
      done(slot.id, slot.run->take());
      slot.run.reset();
    }
  }
}

}  // namespace softdrop
