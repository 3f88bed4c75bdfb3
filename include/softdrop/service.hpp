#pragma once
/// \file service.hpp
/// The studies run on a database, as the program and the Python module run them: what to run (an
/// options struct with IsValid), where (a database file), an observer that hears of each step and
/// may stop the run, and a summary of how it ended (cf. Ceres' Solver::Options, IterationCallback
/// and Summary). Stopped runs continue where they stopped when run again with the same options.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "softdrop/sweep.hpp"

namespace softdrop {

/// A sweep's run on a database: the sweep (its identity in the file), the worker threads, and the
/// shard of its media this process runs (shard k of n: the units i with i % n == k).
struct SweepRun {
  SweepOptions sweep;
  std::string db;   ///< the database file; created at the first medium stored
  int threads = 0;  ///< 0: all cores; the numbers do not depend on it
  int shard = 0, shards = 1;

  /// The sweep's options, threads in [0, 4096], 0 <= shard < shards; db not empty.
  bool IsValid(std::string* why) const;
};

/// Where a sweep's run stands after a medium is stored.
struct SweepProgress {
  std::int64_t sweep = 0;     ///< its id in the file
  std::size_t done = 0;       ///< media of this run's list finished (here or by another process)
  std::size_t to_do = 0;      ///< media on this run's list (the shard's, less those stored before)
  std::int64_t droplets = 0;  ///< droplets run by this process so far
  double seconds = 0;         ///< wall time since the run began
};

/// What a sweep's run tells as it goes. started() and stored() come on the thread that called
/// run_sweep; stop_requested() may come on a worker thread.
class SweepObserver {
 public:
  virtual ~SweepObserver() = default;
  /// Before any medium: the sweep's id (0: a new sweep, recorded with its first medium), and the
  /// media of the shard already stored and still to run.
  virtual void started(std::int64_t /*sweep*/, std::size_t /*stored*/, std::size_t /*to_do*/) {}
  /// After each medium is stored. false stops the run after the media in flight, which are stored.
  virtual bool stored(const SweepMedium& /*medium*/, const SweepProgress& /*progress*/) { return true; }
  /// Asked before each new medium starts, on a worker thread: true stops the run as stored()
  /// returning false does. It must be safe to call from any thread (a signal's atomic flag, say).
  virtual bool stop_requested() { return false; }
};

/// How a sweep's run ended.
struct SweepSummary {
  std::int64_t sweep = 0;
  std::string status;                  ///< complete, interrupted (stopped) or running (another shard's media remain)
  std::int64_t media = 0, done = 0;    ///< the sweep's media, and those stored (by any process)
  std::size_t media_this_session = 0;  ///< media this run stored
  std::size_t media_by_another_process = 0;  ///< media on this run's list that another process stored meanwhile
  std::int64_t droplets_this_session = 0;
  double wall_seconds = 0;
  double commit_seconds = 0;  ///< of which storing media
  std::vector<int> by_rank;   ///< media each rank of a job ran (empty: one process)
  double serve_seconds = 0;   ///< rank 0's time serving the other ranks
};

/// How the media of a sweep's run are run: by default on this process's threads
/// (run_sweep_units); the program's MPI job hands them to its ranks. Its arguments are those of
/// run_sweep_units; `stored(unit)` is true for a unit another process has stored meanwhile, which
/// is then passed over. Returns what by_rank and serve_seconds report.
struct SweepUnitsRun {
  std::vector<int> by_rank;
  double serve_seconds = 0;
};
using SweepUnitsRunner =
    std::function<SweepUnitsRun(const SweepOptions& options, const std::vector<SweepUnit>& units, int threads,
                                const std::function<void(SweepMedium&&)>& on_done, const std::function<bool()>& stop,
                                const std::function<bool(const SweepUnit&)>& stored)>;

/// Runs the sweep's media of `run` that its database does not hold yet, and stores each as it
/// ends, in one transaction: a run stopped at any instant loses at most the media in flight, and
/// run again goes on with the rest. Nothing is written before the first medium is stored, so a
/// run refused at its start leaves every file as it was and creates none. Throws
/// std::invalid_argument for invalid options and DatabaseError for a file that is not a usable
/// database, naming it.
SweepSummary run_sweep(const SweepRun& run, SweepObserver& observer, const SweepUnitsRunner& runner = {});

}  // namespace softdrop
