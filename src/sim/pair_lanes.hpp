#pragma once
// Several pairs of droplets (run_two_droplets) stepped together on one thread
// (run_pairs_interleaved), the driver under run_two_droplet_batch. Private to the library.
#include <cstdint>
#include <functional>

#include "softdrop/simulation.hpp"

namespace softdrop {

/// The most pairs run_pairs_interleaved steps together: their rings fill two lane-by-lane blocks.
inline constexpr int kMostInterleavedPairs = 24;

/// A pair for run_pairs_interleaved: its first droplet's start x, and the caller's id, handed back
/// with the summary.
struct PairJob {
  double x0 = 0;
  std::int64_t id = 0;
};

/// Runs pairs of droplets of `droplet` through `medium` (each as run_two_droplets runs it, with
/// `options` and `second`) on this thread, up to `pairs` (in [1, kMostInterleavedPairs]) of them stepped together. With
/// AVX-512 or AVX, the rings of every running pair go as one lane-by-lane block (LaneBlockStep) when there are at least
/// fewest_block_droplets(); otherwise as a ring group (RingGroup). Either layout runs the ring-ring stages between each
/// pair's two rings. Every pair's summary has the bits run_two_droplets gives it. `next(job)` fills in the next pair
/// and returns true, or returns false: there are no more, and the driver returns once the running pairs have ended.
/// `done(id, summary)` takes each pair's summary as it ends. An exception of a pair's run leaves the driver.
void run_pairs_interleaved(int pairs, const DropletParams& droplet, const Medium& medium, const RunOptions& options,
                           const SecondDroplet& second, const std::function<bool(PairJob*)>& next,
                           const std::function<void(std::int64_t id, TwoDropletSummary&&)>& done);

}  // namespace softdrop
