#pragma once
/// \file batch.hpp
/// Many droplets through one medium, in parallel, with results independent of the thread count.

#include <atomic>
#include <cstdint>
#include <functional>
#include <limits>
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
  /// or AVX, stepped as lane-by-lane blocks of three groups of eight, 6 with SSE2). Results do not
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

}  // namespace softdrop
