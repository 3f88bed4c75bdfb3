#pragma once
// Several pairs of droplets (run_two_droplets) stepped together on one thread
// (run_pairs_interleaved), the driver under run_two_droplet_batch. Private to the library.
#include <cstdint>
#include <functional>

#include "softdrop/simulation.hpp"

namespace softdrop {

/// A pair for run_pairs_interleaved: its first droplet's start x, and the caller's id, handed back
/// with the summary.
struct PairJob {
  double x0 = 0;
  std::int64_t id = 0;
};

/// Runs pairs of droplets of `droplet` through `medium` (each as run_two_droplets runs it, with
/// `options` and `second`) on this thread, stepped together in `lanes` (in [2, 64]) lanes: a pair
/// holds a lane for each of its droplets that runs or is yet to be released, and a new pair starts
/// whenever two lanes are free. So the rings stepped never outnumber the lanes, and a pair whose
/// first droplet has ended gives its lane to the next. With AVX-512 or AVX, the rings go as
/// lane-by-lane blocks (LaneBlockStep) of at most 24, each filled before the next begins, when
/// there are at least fewest_block_droplets(); otherwise as a ring group (RingGroup). Either layout
/// runs the ring-ring stages between each pair's two rings. Every pair's summary has the bits
/// run_two_droplets gives it. `next(job)` fills in the next pair and returns true, or returns
/// false: there are no more, and the driver returns once the running pairs have ended. `done(id,
/// summary)` takes each pair's summary as it ends. An exception of a pair's run leaves the driver.
void run_pairs_interleaved(int lanes, const DropletParams& droplet, const Medium& medium, const RunOptions& options,
                           const SecondDroplet& second, const std::function<bool(PairJob*)>& next,
                           const std::function<void(std::int64_t id, TwoDropletSummary&&)>& done);

}  // namespace softdrop
