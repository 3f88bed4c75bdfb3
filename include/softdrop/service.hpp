#pragma once
/// \file service.hpp
/// The studies run on a database, as the program and the Python module run them: what to run (an
/// options struct with IsValid), where (a database file), an observer that hears of each step and
/// may stop the run, and a summary of how it ended (cf. Ceres' Solver::Options, IterationCallback
/// and Summary). Stopped runs continue where they stopped when run again with the same options.

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "softdrop/search.hpp"
#include "softdrop/store.hpp"
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

/// Where a new search starts: the grain file `file`, or else a medium generated from `medium`;
/// when the droplet does not pass through it, the next of `attempts` media, medium seed
/// derive_seed(medium.seed, attempt) for attempt = 1, 2, ...
struct SearchStart {
  std::string file;
  MediumOptions medium;
  int attempts = 100;
};

/// A search's run on a history file: a new run, or a stored one continued (`resume`). A resumed
/// run takes its search options from the history; the options given here are then only checked
/// against it (see `given`).
struct SearchRun {
  SearchOptions search;     ///< a new run's options
  SearchStart start;        ///< a new run's first arrangement
  std::string db;           ///< the history file; a new one is created once generation 0 exists
  std::int64_t resume = 0;  ///< the run to continue (0: start a new one)
  /// Run up to this generation number. None: a new run's kDefaultGenerations, a resumed run's
  /// own target (the last one given).
  std::optional<std::int64_t> generations;
  double time_limit = 0;  ///< wall seconds (0: none)
  int threads = 0;        ///< 0: all cores; the history does not depend on it
  int lanes = 0;          ///< DriveOptions::lanes
  bool speculate = true;  ///< DriveOptions::speculate
  /// At the end of a run that reached its target, the best arrangement's held-out value over this
  /// many random starts, at dt and dt/2, stored in the history (0: none).
  int validate_starts = 200;
  /// On resume: the stored parameters' keys (the program's option names: "lambda", "seed",
  /// "r-min", ...) that the caller set. Each must have the stored value, or the resume is refused
  /// naming it; the others are taken from the run.
  std::vector<std::string> given;
  /// The island model (docs/search.md): `islands` > 1 searches side by side, each a run of the
  /// history with a seed of its own, every `migrate_every` generations each taking another
  /// island's best (`migration`: ring or broadcast; 0: never, independent lineages), all from one
  /// start or, with `own_island_starts`, each from a generated medium of its own. Resuming any
  /// island's run resumes them all, with their stored options.
  int islands = 1;
  int migrate_every = 50;
  std::string migration = "ring";
  bool own_island_starts = false;

  static constexpr std::int64_t kDefaultGenerations = 200;
  /// generations in [0, 1e9], time_limit >= 0, threads, lanes, validate_starts in [0, 1e6],
  /// start.attempts >= 1, db not empty; for a new run, the search's and the medium's options and
  /// grains >= 1 for a generated medium.
  bool IsValid(std::string* why) const;
};

/// The program's default search (`softdrop optimize` with no options): the evolution strategy with
/// a relocation every third generation, lambda = 8, the mean objective over 16 fresh starts a
/// generation, from 20 non-overlapping grains in the default 500 x 500 periodic box.
/// SearchOptions{} itself is the paper's algorithm.
SearchRun default_search_run();

/// How islands are driven (private to the library: its threads, or the program's MPI ranks).
struct IslandsDrive;

/// What a search's run tells as it goes, on the thread that called run_search.
class SearchObserver {
 public:
  virtual ~SearchObserver() = default;
  /// A random starting medium (attempt 1, 2, ...) the droplet did not pass through, and why.
  virtual void start_refused(int /*attempt*/, const std::string& /*why*/) {}
  /// Before the session's first generation: the run's id, its best so far, the generation it goes
  /// on from (0 for a new run) and its target.
  virtual void started(std::int64_t /*run*/, const Configuration& /*best*/, std::int64_t /*from*/,
                       std::int64_t /*target*/, bool /*resumed*/) {}
  /// Islands, instead of started(): before the session's first generation, the islands' runs, the
  /// generation each goes on from, their starting arrangements (a new search: one shared by all,
  /// or one an island) or, resumed, each island's best so far, and the target.
  virtual void islands_started(const std::vector<std::int64_t>& /*runs*/, const std::vector<std::int64_t>& /*from*/,
                               const std::vector<Configuration>& /*starts*/, std::int64_t /*target*/,
                               bool /*resumed*/) {}
  /// After each generation is stored (island: its index, or -1 for a run of one search). false
  /// stops the run there (Termination::callback); islands stop after the generations in flight.
  virtual bool generation(std::int64_t /*run*/, int /*island*/, const Generation& /*g*/, const Configuration& /*best*/,
                          std::int64_t /*target*/) {
    return true;
  }
  /// The held-out droplets of the end's validation, as they finish.
  virtual void validating(int /*done*/, int /*total*/) {}
  /// A flag raised asynchronously (a signal's) to stop after the generation in flight; nullptr:
  /// none. Read once, before the first generation.
  virtual const std::atomic<bool>* stop_flag() { return nullptr; }
};

/// How a search's run ended.
struct SearchRunSummary {
  std::int64_t run = 0;
  bool resumed = false;
  /// A resumed run already at or past the target: nothing ran; `best` then holds only the stored
  /// best's generation and T, and drive.last_generation the run's last generation.
  bool nothing_to_do = false;
  std::int64_t target = 0;  ///< the generation the session ran up to
  SearchOptions search;     ///< the run's options (a resumed run's, as stored)
  SearchSummary drive;      ///< the session's generations: why they ended, counts, speculation
  Configuration best;       ///< the run's best after the session
  /// Generation 0's candidates and droplets when this session made it (a new run), else 0.
  std::int64_t initial_evaluations = 0, initial_droplets = 0;
  /// The held-out value stored at the end (validate_starts > 0 and the target reached).
  std::optional<ValidationRecord> held_out;
  /// Robust objectives: the objective over the held-out starts at dt, a droplet that did not
  /// pass counted as T = 1 (NaN otherwise).
  double held_out_objective = std::numeric_limits<double>::quiet_NaN();
  /// Islands: each island's run, last generation and best, in island order; `run` is island 0's,
  /// `best` and the held-out value the best island's (the lowest-numbered among equals).
  struct Island {
    std::int64_t run = 0;
    std::int64_t last_generation = 0;
    Configuration best;
  };
  std::vector<Island> islands;
  int best_island = -1;
  int migrate_every = 0;
  std::string migration;
};

/// Runs a search on a history file: generation 0 of a new run (stored with its options once it
/// exists, so a start that fails creates no file), or a stored run read back and checked against
/// this build; then generations, each stored as it ends, until the target, the time limit, the
/// stop flag or the observer stops it; the run marked finished or interrupted; and the best's
/// held-out value stored when the target was reached. A refused run changes no file. Throws
/// std::invalid_argument for invalid or contradicting options, std::runtime_error for a start
/// through which no droplet passes or a stored run this build does not reproduce, and
/// DatabaseError for a file that is not a usable history, naming it.
SearchRunSummary run_search(const SearchRun& run, SearchObserver& observer);
/// The same, with the islands driven by `drive` (the program's MPI ranks; nullptr: this process's
/// threads).
SearchRunSummary run_search(const SearchRun& run, SearchObserver& observer, const IslandsDrive* drive);

}  // namespace softdrop
