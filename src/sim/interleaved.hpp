#pragma once
// Several droplets' runs stepped together on one thread (run_interleaved), the drivers under
// run_batch, sweeps and the search. Private to the library.
#include <cstdint>
#include <functional>
#include <memory>

#include "softdrop/simulation.hpp"

namespace softdrop {

/// A droplet for run_interleaved: the simulation to run it in (placed above the medium at x0 by the
/// driver, as Simulation::run does), its options, and the caller's id, handed back with the result.
struct DropletJob {
  Simulation* sim = nullptr;
  double x0 = 0;
  const RunOptions* options = nullptr;
  std::int64_t id = 0;
};

/// Lets the run_interleaved calls of several threads hand running droplets to each other. A thread
/// whose `next` has nothing more for it takes droplets over from a thread that steps at least two
/// more than it does, so the last droplets of a batch or a sweep spread over the threads instead of
/// running on one while the others idle. A droplet's summary does not depend on the thread or the
/// lane that steps it, so the results keep their bits. With an exchange, `done` and `cancelled` may
/// be called on another thread than the `next` that handed the droplet out, and a droplet's
/// simulation and options must stay valid until its `done` or `cancelled`, on whichever thread.
class LaneExchange {
 public:
  LaneExchange();
  ~LaneExchange();
  LaneExchange(const LaneExchange&) = delete;
  LaneExchange& operator=(const LaneExchange&) = delete;
  /// Droplets handed from one thread to another so far.
  std::int64_t handovers() const;
  /// The threads' shared state, defined and used by lane_exchange.hpp alone.
  struct Impl;
  Impl* impl() const { return impl_.get(); }

 private:
  std::unique_ptr<Impl> impl_;
};

/// Runs droplets on this thread `lanes` at a time, stepped together. With AVX-512 or AVX, enough
/// droplets of one set of parameters (fewest_block_droplets(), lane_policy.hpp) go as one block
/// laid out lane by lane, eight to a group (one AVX-512 register, two AVX ones): every stage but
/// the contacts (forces, viscosity, integration, either constraint order) is vector code across
/// droplets, so the chains of dependent sums, square roots and divisions that bound one ring serve
/// eight. The others step ring by ring, and their sequential constraints go as lanes of the
/// block's where there are enough (apply_length_constraint_interleaved). Every
/// droplet gets exactly the operations of Simulation::run, so its summary has the same bits (its
/// state().fx, fy, scratch of a step, are not kept in a block).
/// `next(job, may_wait)` fills in the next droplet and returns true, or returns false: when
/// may_wait is false, there is none at the moment (it is asked again after the next step); when
/// may_wait is true (every lane is idle), there are none left and the driver returns (with an
/// exchange, once no other thread has droplets to hand over). A lane's simulation must not be
/// handed out again before its `done(id, summary)`. A run whose options cancel it
/// (RunOptions::cancelled) goes to `cancelled(id)` instead, and its lane takes the next droplet;
/// without that callback RunCancelled leaves the driver, as other exceptions do.
void run_interleaved(int lanes, const std::function<bool(DropletJob*, bool may_wait)>& next,
                     const std::function<void(std::int64_t id, RunSummary&&)>& done,
                     const std::function<void(std::int64_t id)>& cancelled = nullptr, LaneExchange* exchange = nullptr);

}  // namespace softdrop
