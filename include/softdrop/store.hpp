#pragma once
/// \file store.hpp
/// The stores of a softdrop database. One SQLite file holds search histories (History; README.md,
/// "The history database", has the schema) and sweep records (SweepStore: tables sweeps,
/// sweep_media, sweep_droplets), each behind one storage interface. Every generation, and every
/// medium with its droplets, is one transaction, so a process killed at any instant loses at most
/// the generation or the medium in flight, and a run or a sweep continues where it stopped.
/// OpenMode says how a file is opened; DatabaseError, why it cannot be.

#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "softdrop/batch.hpp"
#include "softdrop/search.hpp"
#include "softdrop/sweep.hpp"

namespace softdrop {

/// How to open a database file.
enum class OpenMode {
  read_only,  ///< must exist and be a softdrop database
  create      ///< created if missing; an existing file must be a softdrop database
};

/// A file that is not a usable softdrop database (missing, not SQLite, foreign, newer, truncated,
/// corrupted, unwritable): one line naming the file. The Python module raises it as StoreError.
struct DatabaseError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// The schema version this build writes (PRAGMA user_version). Files with a higher version are
/// refused; files with a lower one are read as they are and migrated when opened for writing
/// (1 -> 2 adds the sweeps, 2 -> 3 the strategies' state of each generation, 3 -> 4 relocation
/// moves, 4 -> 5 islands, 5 -> 6 the held-out values of arrangements, 6 -> 7 the robust
/// objectives' droplet counts and re-runs, 7 -> 8 each candidate's move, the generation kind
/// 'mixed' and the *_view views under the names of `softdrop columns`, 8 -> 9 each sweep droplet's
/// shaken_at and route_tortuosity, 9 -> 10 the second droplets of sweeps of pairs).
constexpr int kHistorySchemaVersion = 10;
/// PRAGMA application_id of a softdrop database: "SDRP".
constexpr std::int32_t kHistoryApplicationId = 0x53445250;

/// A run's row.
struct RunRecord {
  std::int64_t id = 0;
  std::string created, updated;  ///< UTC, ISO 8601
  std::string version;           ///< softdrop version that created the run
  std::string status;            ///< running, finished or interrupted
  std::string params;            ///< JSON object: every option that defines the run
  std::uint64_t seed = 0;
  int lambda = 1;
  std::int64_t grains = 0;
  double width = 0, height = 0;
  bool periodic = true;
  std::int64_t generations = 0;  ///< last stored generation number
  std::int64_t evaluations = 0;  ///< candidates evaluated so far
  std::int64_t droplets = 0;     ///< droplet runs so far (evaluations x starts, and the parents' re-runs)
  double best_t = 0;
  std::int64_t best_generation = 0;
  int island = -1;               ///< the run's island (docs/search.md); -1: not one of islands
  std::int64_t archipelago = 0;  ///< id of its archipelago's first run (island 0); 0: none
};

/// A held-out value of a run's arrangement (held_out_value, batch.hpp), as stored: at dt, and at dt / 2 where
/// it was asked. NaN where nothing (or one droplet, for an error) passed.
struct ValidationRecord {
  std::int64_t generation = 0;  ///< the arrangement kept as of this generation
  std::string created;          ///< UTC, ISO 8601
  std::string version;          ///< softdrop version that computed it
  std::uint64_t seed = 1;       ///< of the starts
  int starts = 0;
  double dt = 0;
  int passed = 0;
  double mean_t = 0, standard_error = 0, q1 = 0, median = 0, q3 = 0;
  bool half_dt = false;  ///< the starts were run again at dt / 2
  int half_dt_passed = 0;
  double half_dt_mean_t = 0, half_dt_standard_error = 0;
  int paired = 0;  ///< starts that passed at both time steps
  double dt_shift = 0, dt_shift_error = 0;
};

/// The record of a held-out value of the arrangement kept as of `generation`.
ValidationRecord validation_record(std::int64_t generation, const HeldOutOptions& options, const HeldOutValue& value);

/// A candidate's row.
struct CandidateRecord {
  int index = 0;
  std::string kind;  ///< its move (MoveKind's name); empty where an older file does not tell it
  int moved_grain = -1;
  int moved = 0;
  std::string outcome;
  std::string reason;
  double tortuosity = 0;  ///< the objective's value (Evaluation::tortuosity); 0 unless passed
  int droplets = 1;       ///< droplets pushed
  int passed = 0;         ///< droplets that passed
  std::int64_t steps = 0;
  int touched = 0;
  double seconds = 0;
};

/// A generation's row with its candidates.
struct GenerationRecord {
  std::int64_t generation = 0;
  std::string kind;
  int accepted = -1;
  double best_t = 0;
  int touched = 0;
  double seconds = 0;
  std::string finished;  ///< UTC time it was written
  std::string state;     ///< the strategy's state after it (JSON; empty: none)
  /// Robust objectives: the value of the arrangement the candidates were made from, re-run on this
  /// generation's starts, and how many of its droplets passed (NaN and 0: not re-run).
  double parent_t = std::numeric_limits<double>::quiet_NaN();
  int parent_passed = 0;
  std::vector<CandidateRecord> candidates;
};

/// A robust objective's in-search value of the arrangement kept in generation `kept` (see
/// Configuration): the best_t of the last generation before another arrangement was kept, the
/// mean of its re-runs on fresh starts, and how many re-runs that is (0: the value it was kept
/// with). Throws std::invalid_argument if `generations` does not hold `kept`.
struct KeptValue {
  double value = 0;
  std::int64_t re_runs = 0;
};
KeptValue kept_value(const std::vector<GenerationRecord>& generations, std::int64_t kept);

/// One point of a run's best-T curve as `history --best` gives it: a generation, the value of the
/// arrangement kept there, and for a robust objective the re-runs that value is the mean of.
struct BestPoint {
  std::int64_t generation = 0;
  double value = 0;
  std::int64_t re_runs = 0;
};
/// The best-T curve of `generations` (numbered 0, 1, 2, ...): for the single objective generation 0
/// and each generation that raised best_t, at its best_t; for a robust one generation 0 and each
/// generation that kept a candidate, at kept_value's value.
std::vector<BestPoint> best_curve(const std::vector<GenerationRecord>& generations, bool robust);

/// The held-out value stored for the arrangement kept as of `generation`: of several (other seeds
/// or start counts, or validated again) the one of most starts, and of those the one made last.
/// Empty: none stored.
std::optional<ValidationRecord> held_out_of(const std::vector<ValidationRecord>& validations, std::int64_t generation);

/// Storage of search runs. Implementations must make each call atomic.
class History {
 public:
  virtual ~History() = default;

  /// Creates a run together with its generation 0; returns its id.
  virtual std::int64_t create_run(const std::string& params_json, const SearchOptions& options,
                                  const Generation& initial, const Configuration& best) = 0;
  /// Appends generation g of `run` with its strategy state; the arrangement it kept (its accepted
  /// candidate: grains, touched set, path) is stored. `best` is the best after it.
  /// Throws if the generation is not the next one (e.g. another process writes the same run).
  virtual void append(std::int64_t run, const Generation& g, const Configuration& best) = 0;
  /// Appends generation gs[i] of runs[i] for every i in one transaction: the islands' migration,
  /// which a kill leaves made by all of them or by none.
  virtual void append_together(const std::vector<std::int64_t>& runs, const std::vector<Generation>& gs,
                               const std::vector<Configuration>& bests) = 0;
  /// Sets a run's status (running, finished, interrupted).
  virtual void set_status(std::int64_t run, const std::string& status) = 0;
  /// Makes a run island `island` of the archipelago whose first run is `archipelago`.
  virtual void set_island(std::int64_t run, int island, std::int64_t archipelago) = 0;
  /// Sets one key of a run's stored parameters (a JSON value, e.g. "target-generations" = "500").
  virtual void set_param(std::int64_t run, const std::string& key, const std::string& json_value) = 0;

  virtual std::vector<RunRecord> runs() = 0;
  /// Throws std::runtime_error naming the id if there is no such run.
  virtual RunRecord run(std::int64_t id) = 0;
  /// Throws if the generations are not numbered 0, 1, 2, ... (a damaged or edited file).
  virtual std::vector<GenerationRecord> generations(std::int64_t run) = 0;
  /// Throws std::runtime_error naming the file unless the run can be continued: its parameters
  /// are a JSON object, and its generations are exactly 0 to its last one, each with candidates
  /// and none without its generation. Cheaper than generations() on a long run.
  virtual void check_run(std::int64_t run) = 0;
  /// The arrangement kept as of `generation` (the last accepted one at or before it), with its
  /// tortuosity, touched grains and path; generation -1 means the latest. Throws
  /// std::invalid_argument for a generation outside -1 and 0 to the run's last. For the paper's
  /// strategy this is the best as of then; for others the best is at the run's best_generation.
  virtual Configuration configuration(std::int64_t run, std::int64_t generation) = 0;
  /// The strategy state stored with `generation` ("" if none).
  virtual std::string strategy_state(std::int64_t run, std::int64_t generation) = 0;
  /// The strategy states stored with generations 1 to `last`, in order, as a JSON array of the
  /// non-empty ones: what make_strategy takes for a strategy that resumes_by_replay().
  virtual std::string strategy_states(std::int64_t run, std::int64_t last) = 0;
  /// Stores a held-out value of the run's arrangement as of v.generation, replacing one of the
  /// same generation, seed and starts (the numbers are deterministic: the same).
  virtual void add_validation(std::int64_t run, const ValidationRecord& v) = 0;
  /// The run's held-out values, by generation, seed and starts.
  virtual std::vector<ValidationRecord> validations(std::int64_t run) = 0;
};

/// What a search says of one arrangement it kept: the value it stands on in the search, as
/// `history --best` gives it, and the held-out value stored for it. Every command and reader that
/// quotes a kept arrangement's value quotes these.
struct ArrangementValues {
  std::string objective;  ///< single, mean, quantile or lower-bound
  int starts = 1;         ///< droplets an evaluation pushes (1 for single)
  /// single: the droplet's T from x0 = W/2. Robust objectives: kept_value's (the mean of the
  /// re-runs on fresh starts, or with none the value it was kept with).
  double in_search = 0;
  std::int64_t re_runs = 0;  ///< robust objectives: the re-runs in_search is the mean of
  std::optional<ValidationRecord> held_out;
  bool robust() const { return objective != "single"; }
};
/// Throws as History::generations does, and std::runtime_error naming the run if its stored
/// parameters are not a JSON object.
ArrangementValues arrangement_values(History& history, std::int64_t run, const Configuration& kept);
/// The same from what a caller has read already: the run's row, its generations (read only for a
/// robust objective: may be empty for the single one) and its validations.
ArrangementValues arrangement_values(const RunRecord& run, const std::vector<GenerationRecord>& generations,
                                     const std::vector<ValidationRecord>& validations, const Configuration& kept);

/// A run's best-T curve as `history --best` gives it: best_curve's points, each with the move
/// (GenerationRecord::kind) and touched grains of its generation and the held-out value stored for
/// that generation's arrangement (held_out_of). robust: the run's objective is not single, and each
/// point's value is kept_value's.
struct BestRow {
  BestPoint point;
  std::string kind;
  int touched = 0;
  std::optional<ValidationRecord> held_out;
};
struct BestCurve {
  bool robust = false;
  std::vector<BestRow> rows;
};
/// Throws as arrangement_values.
BestCurve best_rows(History& history, std::int64_t run);
/// The same from what a caller has read already: the run's row, its generations and validations.
BestCurve best_rows(const RunRecord& run, const std::vector<GenerationRecord>& generations,
                    const std::vector<ValidationRecord>& validations);

/// Opens an SQLite history. A missing file (read_only), a file that is not SQLite, a foreign SQLite
/// database, one from a newer schema or a truncated or corrupted one gives std::runtime_error with
/// one line naming the file, and the file is not modified.
std::unique_ptr<History> open_history(const std::string& path, OpenMode mode);

/// The checks open_history(path, OpenMode::create) makes, without creating or writing anything
/// (for a new file: that its folder exists and is writable): lets a command refuse a bad file
/// before long work, and create a new one only afterwards.
void check_database(const std::string& path);

/// A sweep's row.
struct SweepRecord {
  std::int64_t id = 0;
  std::string created, updated, version, status;
  std::string params;      ///< JSON of the options (the sweep's identity)
  std::int64_t units = 0;  ///< porosities x media
  std::int64_t done = 0;   ///< media stored
};

class SweepStore {
 public:
  virtual ~SweepStore() = default;
  /// The id of the sweep with exactly these parameters, 0 if there is none. Writes nothing.
  virtual std::int64_t find(const std::string& params_json) = 0;
  /// The id of the sweep with exactly these parameters, created if there is none.
  virtual std::int64_t find_or_create(const std::string& params_json, const SweepOptions& options) = 0;
  /// Units already stored for a sweep.
  virtual std::vector<SweepUnit> done_units(std::int64_t sweep) = 0;
  /// Stores one medium with its droplets in one transaction. Returns false, storing nothing, if
  /// the unit is already stored: another process running the same sweep computed it (records are
  /// deterministic, so they are the same).
  virtual bool add(std::int64_t sweep, const SweepMedium& medium) = 0;
  /// Whether the unit is stored (by this process or another one).
  virtual bool has_unit(std::int64_t sweep, const SweepUnit& unit) = 0;
  /// running, complete or interrupted.
  virtual void set_status(std::int64_t sweep, const std::string& status) = 0;
  virtual std::vector<SweepRecord> sweeps() = 0;
  /// Throws std::runtime_error naming the id if there is no such sweep.
  virtual SweepRecord sweep(std::int64_t id) = 0;
  /// Every stored medium of a sweep with its droplets, ordered by (porosity, medium).
  virtual std::vector<SweepMedium> media(std::int64_t sweep) = 0;
  /// The stored medium of one unit with its droplets (empty: not stored), read alone: a sweep of
  /// the paper's size holds 400 000 droplets.
  virtual std::optional<SweepMedium> medium(std::int64_t sweep, const SweepUnit& unit) = 0;
};

/// Opens the sweep store of a softdrop database (the same checks as open_history).
std::unique_ptr<SweepStore> open_sweep_store(const std::string& path, OpenMode mode);

}  // namespace softdrop
