#pragma once
/// \file held_out.hpp
/// The held-out tortuosity of a medium: droplets from many random starts across the top of the
/// box, at the droplet's time step and at half of it. One droplet from one start is a chaotic
/// trajectory (moving the start by 0.01 can change its T by 0.3); the mean over starts, and
/// whether it holds when the time step is halved, is a property of the medium.

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "softdrop/droplet.hpp"
#include "softdrop/medium.hpp"
#include "softdrop/simulation.hpp"

namespace softdrop {

struct HeldOutOptions {
  /// Droplets, each from its own start, drawn uniformly across the top as a batch draws them
  /// (batch_start_x: stream derive_seed(seed, i)); the same starts at both time steps.
  int starts = 200;
  std::uint64_t seed = 1;
  bool half_dt = true;  ///< also run every start at dt / 2 (with twice the step budget)
  int threads = 0;      ///< 0: all cores; the numbers do not depend on it

  /// starts in [1, kMaxHeldOutStarts]; threads in [0, 4096].
  bool IsValid(std::string* why) const;
};

/// The most starts one held-out value may take.
inline constexpr int kMaxHeldOutStarts = 1'000'000;

/// The droplets of one time step.
struct HeldOutRuns {
  double dt = 0;  ///< time units
  int starts = 0, passed = 0, stuck = 0, timeout = 0, diverged = 0;
  double pass_fraction = 0;  ///< passed / starts
  /// Over the passed droplets: mean T, its standard error (sample standard deviation / sqrt(n);
  /// NaN below 2), and the quartiles of T (linear interpolation between order statistics, as
  /// numpy.quantile's default). NaN where none passed.
  double mean_t = 0, standard_error = 0, q1 = 0, median = 0, q3 = 0;
  std::vector<RunSummary> runs;  ///< one per start, in start order
};

/// The held-out value: the runs at dt and, if asked, at dt / 2 from the same starts.
struct HeldOutValue {
  HeldOutRuns at_dt;
  HeldOutRuns at_half_dt;  ///< starts = 0 when not asked
  /// Over the starts that passed at both time steps: the mean of T(dt/2) - T(dt), and its standard
  /// error (NaN below 2 such starts); how much the medium's value depends on the time step.
  int paired = 0;
  double dt_shift = 0, dt_shift_error = 0;
};

/// Runs the held-out droplets through `medium`. `progress(done, total)` is called as droplets end,
/// from worker threads (serialised); an exception it throws stops the work after the droplets in
/// flight and is rethrown. Throws std::invalid_argument for invalid options, droplet or medium.
HeldOutValue held_out_value(const DropletParams& droplet, const Medium& medium, const RunOptions& run,
                            const HeldOutOptions& options, const std::function<void(int, int)>& progress = {});

}  // namespace softdrop
