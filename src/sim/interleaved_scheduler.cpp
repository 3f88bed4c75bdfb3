// run_interleaved: several droplets' runs stepped together on one thread, as lane-by-lane blocks
// (lane_block_step.hpp) or ring by ring, with droplets handed between threads (lane_exchange.hpp).
#include <algorithm>
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "droplet_runtime.hpp"
#include "interleaved.hpp"
#include "lane_block_step.hpp"
#include "lane_exchange.hpp"
#include "lane_layout.hpp"
#include "lane_policy.hpp"
#include "ring_group_step.hpp"
#include "run_stepper.hpp"
#include "softdrop/simulation.hpp"

namespace softdrop {

LaneExchange::LaneExchange() : impl_(std::make_unique<Impl>()) {}
LaneExchange::~LaneExchange() = default;
std::int64_t LaneExchange::handovers() const { return impl_->handovers.load(); }

void run_interleaved(int lanes, const std::function<bool(DropletJob*, bool may_wait)>& next,
                     const std::function<void(std::int64_t id, RunSummary&&)>& done,
                     const std::function<void(std::int64_t id)>& cancelled, LaneExchange* exchange) {
  if (lanes < 1 || lanes > 64) throw std::invalid_argument("lanes = " + std::to_string(lanes) + ": must be in [1, 64]");
  std::vector<Lane> slots(static_cast<std::size_t>(lanes));
  std::vector<DropletState*> rings;
  std::vector<int> corrections;
  std::vector<Simulation*> block, alone;
  const bool lane_wise = constraint_vector_width() >= VectorWidth::avx;
  LaneExchangeSeat seat(exchange, lanes);
  int busy = 0;
  // The lanes' split into the block and the droplets stepped alone is made again only after a
  // droplet joins or leaves a lane, since a droplet's parameters are fixed while it runs.
  bool lanes_changed = true;
  auto joined = [&] {
    ++busy;
    lanes_changed = true;
  };
  auto left = [&] {
    --busy;
    lanes_changed = true;
  };
  auto idle_lane = [&]() -> Lane& {
    for (Lane& l : slots)
      if (!l.run) return l;
    throw std::logic_error("run_interleaved: no idle lane");
  };
  // Fills idle lanes; may wait only while every lane is idle, and then a refusal means "no more".
  auto fill = [&](bool may_wait) {
    for (Lane& l : slots) {
      if (l.run) continue;
      if (!next(&l.job, may_wait && busy == 0)) return;
      l.job.sim->place_above(l.job.x0);
      l.run.emplace(l.job.sim, *l.job.options, &l.job.x0);
      joined();
    }
  };
  for (;;) {
    fill(false);
    if (busy < lanes && seat.offer_waiting() && seat.take(idle_lane(), busy)) joined();
    if (busy == 0) {
      if (seat.take_or_withdraw(idle_lane())) {
        joined();
      } else {
        fill(true);
        if (busy == 0) {
          if (!seat.wait_for_offer(idle_lane())) return;
          joined();
        }
      }
    }
    seat.publish(busy);
    if (seat.should_give(busy)) {
      for (auto l = slots.rbegin(); l != slots.rend(); ++l)
        if (l->run) {
          if (seat.give(*l, busy)) left();
          break;
        }
    }
    // One step of every busy lane. With AVX-512 or AVX, the droplets with the first one's
    // parameters go lane by lane (LaneBlockStep) if there are at least fewest_block_droplets();
    // the others, and all with SSE2 alone, ring by ring (RingGroup), whose constraint takes enough
    // rings of one size as lanes of the block's.
    if (lanes_changed) {
      lanes_changed = false;
      block.clear();
      alone.clear();
      for (Lane& l : slots) {
        if (!l.run) continue;
        Simulation* sim = l.run->simulation();
        if (lane_wise && (block.empty() || LaneBlockStep::compatible(block.front()->params(), sim->params())))
          block.push_back(sim);
        else
          alone.push_back(sim);
      }
      if (block.size() < fewest_block_droplets()) {
        alone.insert(alone.end(), block.begin(), block.end());
        block.clear();
      }
    }
    // Blocks of nearly equal size: 25 droplets go as 13 and 12, not 24 and 1.
    const std::size_t blocks = (block.size() + lanes::kMaxLanes - 1) / lanes::kMaxLanes;
    for (std::size_t b = 0, begin = 0; b < blocks; ++b) {
      const std::size_t end = block.size() * (b + 1) / blocks;
      LaneBlockStep::step(block.data() + begin, static_cast<int>(end - begin));
      begin = end;
    }
    RingGroup group{alone.data(), static_cast<int>(alone.size()), &rings, &corrections};
    run_stages(group);
    // Each run's book-keeping (its centre of mass: the block's sum, where the block stepped it).
    for (Lane& l : slots) {
      if (!l.run) continue;
      const bool ok = l.run->simulation()->runtime().valid();
      if (cancelled) {
        try {
          l.run->after_step(ok);
        } catch (const RunCancelled&) {
          l.run.reset();
          left();
          cancelled(l.job.id);
          continue;
        }
      } else {
        l.run->after_step(ok);
      }
      if (l.run->finished()) {
        RunSummary summary = l.run->take();
        l.run.reset();
        left();
        done(l.job.id, std::move(summary));
      }
    }
  }
}

}  // namespace softdrop
