// run_pairs_interleaved: pairs of droplets stepped together on one thread, their rings as a
// lane-by-lane block (lane_block_step.hpp) or a ring group (ring_group_step.hpp), with the
// ring-ring stages between each pair's two rings.
#include "pair_lanes.hpp"

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

static_assert(2 * kMostInterleavedPairs <= lanes::kMaxLanes, "the rings of the pairs make one block");

void run_pairs_interleaved(int pairs, const DropletParams& droplet, const Medium& medium, const RunOptions& options,
                           const SecondDroplet& second, const std::function<bool(PairJob*)>& next,
                           const std::function<void(std::int64_t id, TwoDropletSummary&&)>& done) {
  if (pairs < 1 || pairs > kMostInterleavedPairs)
    throw std::invalid_argument("pairs = " + std::to_string(pairs) + ": must be in [1, " +
                                std::to_string(kMostInterleavedPairs) + "]");
  struct Slot {
    std::unique_ptr<TwoDropletRun> run;
    std::int64_t id = 0;
    int first_lane = 0, lanes = 0;  // its rings' places among this step's rings
  };
  std::vector<Slot> slots(static_cast<std::size_t>(pairs));
  const bool lane_wise = constraint_vector_width() >= VectorWidth::avx;
  // At most 2 kMostInterleavedPairs rings: one block.
  std::vector<Simulation*> rings;
  std::vector<RingPair> ring_pairs;
  std::vector<DropletState*> group_rings;  // a ring group's scratch
  std::vector<int> corrections;
  bool more = true;
  for (;;) {
    for (Slot& slot : slots) {
      PairJob job;
      if (slot.run || !more || !(more = next(&job))) continue;
      slot.run = std::make_unique<TwoDropletRun>(droplet, medium, job.x0, options, second);
      slot.id = job.id;
    }
    rings.clear();
    ring_pairs.clear();
    for (Slot& slot : slots) {
      if (!slot.run) continue;
      Simulation *a = nullptr, *b = nullptr;
      slot.run->begin_step(&a, &b);
      slot.first_lane = static_cast<int>(rings.size());
      for (Simulation* sim : {a, b})
        if (sim) rings.push_back(sim);
      slot.lanes = static_cast<int>(rings.size()) - slot.first_lane;
      if (slot.lanes == 2) ring_pairs.push_back({slot.first_lane, slot.first_lane + 1, slot.run->scratch(), 0});
    }
    if (rings.empty()) return;  // a pair still running steps a ring; every slot is empty, and next() said no
    if (lane_wise && rings.size() >= fewest_block_droplets()) {
      LaneBlockStep::step(rings.data(), static_cast<int>(rings.size()), ring_pairs.data(),
                          static_cast<int>(ring_pairs.size()));
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
