#pragma once
/// \file area_trace.hpp
/// The paper's area figure as data: the droplet's area S(t) relative to S0, its area when it
/// reaches the medium, while it crosses the medium.

#include <cstdint>
#include <vector>

#include "softdrop/droplet.hpp"
#include "softdrop/medium.hpp"
#include "softdrop/simulation.hpp"

namespace softdrop {

/// One droplet's area trace. Times are in time units; NaN where a moment never came.
struct AreaTrace {
  RunSummary run;               ///< the run itself (outcome, T, steps)
  std::vector<double> t, area;  ///< S(t) every `interval` steps, and at the exit
  double enter = 0;             ///< time the lowest mass first reached y = H (NaN: never)
  double leave = 0;             ///< time the highest mass went below y = 0 (NaN: never)
  double s0 = 0;                ///< S0: the area at `enter` (NaN if it never entered)
  /// Smallest and largest S / S0 inside the medium (from `enter` to `leave`, or to the run's end),
  /// over every step, not only the samples. NaN if the droplet never entered.
  double min_ratio = 0, max_ratio = 0;
};

/// Runs the droplet from above the medium at x = x0 under `run` (its path is recorded as `run`
/// asks, into the summary; its area samples and snapshots are not), then replays the same run recording the area every
/// `interval` steps (>= 1). A droplet that passed is followed until its last mass has left the medium (at most 20 000
/// steps more). Deterministic: the trace belongs to exactly the run summarised in `run`.
AreaTrace trace_area(const DropletParams& params, const Medium& medium, double x0, const RunOptions& run, int interval);

}  // namespace softdrop
