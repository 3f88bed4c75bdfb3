#pragma once
/// \file batch.hpp
/// Many droplets through one medium, in parallel, with results independent of the thread count.
///
/// The held-out tortuosity of a medium: droplets from many random starts across the top of the
/// box, at the droplet's time step and at half of it. One droplet from one start is a chaotic
/// trajectory (moving the start by 0.01 can change its T by 0.3); the mean over starts, and
/// whether it holds when the time step is halved, is a property of the medium.

#include <atomic>
#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "softdrop/droplet.hpp"
#include "softdrop/medium.hpp"
#include "softdrop/simulation.hpp"

namespace softdrop {

struct BatchOptions {
  int droplets = 1;        ///< K droplets
  std::uint64_t seed = 1;  ///< droplet i starts at x drawn from stream derive_seed(seed, i)
  int threads = 0;         ///< worker threads, 0 = all cores
  /// Droplets each thread steps together, in [1, 64]; 0: chosen for the processor (24 with AVX-512
  /// or AVX, stepped as lane-by-lane blocks of three groups of eight, 1 otherwise). Results do not
  /// depend on it.
  int lanes = 0;
  /// Start x of every droplet; NaN draws it uniformly in [0, W) (walls: [R, W - R]).
  double start_x = std::numeric_limits<double>::quiet_NaN();
  /// If set, once it reads true no droplet starts, the droplets in flight run to their end, and
  /// run_batch returns those that ran: droplets 0 to n - 1, since droplets start in index order.
  const std::atomic<bool>* stop = nullptr;
  /// If set, called with each droplet's index and summary as it finishes, before the summary is
  /// kept (serialised, from the worker threads): it may thin what the summary recorded, so that a
  /// long batch keeps only what its caller needs (render paths keeps a few points a pixel).
  std::function<void(int, RunSummary&)> on_finished;
};

/// Aggregate over a batch: tortuosity statistics over passed droplets.
struct BatchStats {
  int droplets = 0, passed = 0, stuck = 0, timeout = 0, diverged = 0;
  double mean_tortuosity = 0;  ///< <T> over passed droplets (0 if none)
  double standard_error = 0;   ///< sample standard deviation / sqrt(passed) (0 if < 2)
  double stuck_fraction = 0;   ///< stuck / droplets
  double mean_steps = 0;       ///< mean steps per droplet
};

/// Start x of droplet i of a batch (deterministic in seed and i).
double batch_start_x(const BatchOptions& options, const Medium& medium, const DropletParams& params, int i);

/// Runs options.droplets droplets, each in its own Simulation; `progress(done, total)` is called
/// from worker threads (serialised) as droplets finish. Results are ordered by droplet index; there
/// are fewer than options.droplets only if options.stop was raised.
std::vector<RunSummary> run_batch(const DropletParams& params, const Medium& medium, const RunOptions& run_options,
                                  const BatchOptions& options, const std::function<void(int, int)>& progress = {});

BatchStats summarize(const std::vector<RunSummary>& runs);

/// options.droplets pairs, pair i's first droplet from batch_start_x(options, medium, droplet, i),
/// on options.threads worker threads, each stepping as many pairs together as fill options.lanes
/// droplets (at least one pair); the results are in pair order and do not depend on the thread or
/// lane count (on_finished is not read). `progress(done, total)` is called
/// from the workers (serialised) as pairs end. Once options.stop reads true no pair starts, and
/// the pairs that ran, 0 to n - 1, are returned.
std::vector<TwoDropletSummary> run_two_droplet_batch(const DropletParams& droplet, const Medium& medium,
                                                     const RunOptions& run, const BatchOptions& options,
                                                     const SecondDroplet& second,
                                                     const std::function<void(int, int)>& progress = {});

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
