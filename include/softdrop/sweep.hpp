#pragma once
/// \file sweep.hpp
/// The tortuosity-porosity sweep (the paper's main study): for each target porosity, M media,
/// each with K droplets from random starts. The unit of work is one medium and its droplets; units
/// are numbered, can be split into shards (`unit % shards == shard`), and are independent of one
/// another, so an interrupted or sharded sweep gives exactly the records of an uninterrupted one.

#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "softdrop/droplet.hpp"
#include "softdrop/medium.hpp"
#include "softdrop/simulation.hpp"

namespace softdrop {

/// Everything that defines a sweep (stored with it; the same options resume the same sweep).
/// Where a sweep's media come from. The two streams give disjoint media for every seed (their
/// seeds are hashes of different tags), so a study can be validated on media its tuning never saw.
enum class MediaStream {
  held_out,     ///< the sweep's own media: `softdrop sweep`'s, never calibrate's
  calibration,  ///< the media `calibrate` tunes on (and every sweep stored before the streams were)
};

/// Names of the streams as the command line and stored sweeps spell them ("held-out",
/// "calibration"); the parse throws std::invalid_argument naming media-stream.
const char* to_string(MediaStream stream);
MediaStream parse_media_stream(const std::string& name);
std::vector<std::string> media_stream_names();

struct SweepOptions {
  std::vector<double> porosities{0.5, 0.6, 0.7, 0.8, 0.9};  ///< target porosities
  int media = 10;                                           ///< M media per porosity
  int droplets = 20;                                        ///< K droplets per medium, from random starts
  std::uint64_t seed = 1;                                   ///< seed of media and start positions
  MediaStream stream = MediaStream::held_out;               ///< which media the seed picks
  MediumOptions medium;                                     ///< the media (porosity and seed are set per medium)
  DropletParams droplet;
  RunOptions run;  ///< exit conditions (traces are not recorded)
  /// A second droplet pushed after each (run_two_droplets): each start is a pair's, its first
  /// droplet from the start a one-droplet sweep would use. None (the default): one droplet.
  std::optional<SecondDroplet> second;

  bool IsValid(std::string* why) const;
};

/// One unit of work: medium `medium` of porosity `porosity` (indices into the options).
struct SweepUnit {
  int porosity = 0;
  int medium = 0;
  bool operator==(const SweepUnit&) const = default;
};

/// The units of shard `shard` of `shards` (0 <= shard < shards), in order.
std::vector<SweepUnit> sweep_units(const SweepOptions& options, int shard = 0, int shards = 1);

/// Seed of a unit's medium: depends on the media stream, the sweep seed, the target porosity's
/// value and the medium index, so adding porosities or media to a sweep leaves the existing units
/// unchanged.
std::uint64_t sweep_medium_seed(const SweepOptions& options, const SweepUnit& unit);
/// The options from which the sweep generates the unit's medium (generate_medium): the sweep's
/// medium options with the unit's target porosity and sweep_medium_seed.
MediumOptions sweep_medium_options(const SweepOptions& options, const SweepUnit& unit);

/// One droplet's record.
struct SweepDroplet {
  int droplet = 0;
  double start_x = 0;
  Outcome outcome = Outcome::timeout;
  double tortuosity = 0;  ///< 0 unless passed
  std::int64_t steps = 0;
  /// When the medium began to shake (time units since the run began), NaN if it never did
  /// (RunSummary::shaken_at); NaN too in a store older than version 9, which did not record it.
  double shaken_at = std::numeric_limits<double>::quiet_NaN();
  /// RunSummary::route_tortuosity: T itself if the medium never shook; NaN unless passed, and in
  /// a store older than version 9.
  double route_tortuosity = std::numeric_limits<double>::quiet_NaN();
};

/// A pair's second droplet (a sweep with SweepOptions::second), for pairs whose second was
/// released: its run as SweepDroplet has it, and the pair's contacts.
struct SweepSecond {
  SweepDroplet run;  ///< run.droplet: the pair's number, its first droplet's
  double released_at = std::numeric_limits<double>::quiet_NaN();  ///< since the first began (time units)
  /// When each droplet was first held, found stuck while the other still moved (time units since
  /// its own start); NaN if never.
  double first_held_at = std::numeric_limits<double>::quiet_NaN();
  double held_at = std::numeric_limits<double>::quiet_NaN();
  std::int64_t contact_steps = 0;  ///< steps with the rings in contact
  int shared_touched = 0;          ///< grains both droplets touched
};

/// One medium's record: its summary and its droplets.
struct SweepMedium {
  SweepUnit unit;
  double target_porosity = 0;
  double porosity = 0;  ///< exact porosity of the generated medium
  int grains = 0;
  std::uint64_t medium_seed = 0;
  int passed = 0, stuck = 0, timeout = 0, diverged = 0;
  double mean_t = 0;          ///< <T> over passed droplets (0 if none)
  double standard_error = 0;  ///< of <T> (0 if fewer than 2 passed)
  double stuck_fraction = 0;
  double seconds = 0;  ///< wall time (not part of the deterministic record)
  /// The droplets from the medium's starts (with a second droplet: each pair's first); the counts
  /// and <T> above are theirs.
  std::vector<SweepDroplet> droplets;
  std::vector<SweepSecond> second_droplets;  ///< with a second droplet: the released seconds, by pair
};

/// Generates the unit's medium and pushes its K droplets through it with up to `threads` threads
/// (0: all cores). Deterministic whatever the thread count. `progress(done, total)` is called as
/// droplets finish.
SweepMedium run_sweep_unit(const SweepOptions& options, const SweepUnit& unit, int threads,
                           const std::function<void(int, int)>& progress = {});

/// Runs `units` keeping every thread busy across unit boundaries: droplets of the next units start
/// while the last droplets of earlier ones finish (at most threads + 1 units are open at once, plus
/// as many as it takes for their droplets to fill every thread's lanes twice over).
/// `on_done` is called on the calling thread with each unit as it completes, in completion order,
/// so that a store can commit it; each record equals run_sweep_unit's for that unit. `stop` is
/// polled before each new unit: once it returns true no unit starts, and the units already started
/// are finished and handed to on_done. `skip(unit)` is asked, on a worker thread under the
/// scheduler's lock, before each unit starts: true passes the unit over (another process has stored
/// it meanwhile). `threads` 0 means all cores.
void run_sweep_units(const SweepOptions& options, const std::vector<SweepUnit>& units, int threads,
                     const std::function<void(SweepMedium&&)>& on_done, const std::function<bool()>& stop = {},
                     const std::function<bool(const SweepUnit&)>& skip = {});

/// Per-porosity aggregate of medium records: droplets pooled over the porosity's media.
struct SweepPoint {
  double target_porosity = 0;
  double porosity = 0;  ///< mean exact porosity of its media
  int media = 0, droplets = 0, passed = 0, stuck = 0, diverged = 0;
  double mean_t = 0, standard_error = 0;  ///< over all passed droplets of the porosity
  /// Media where at least one droplet passed, and the standard error of mean_t with those media as
  /// clusters (0 if fewer than two): droplets of one medium share its throats, so this is the
  /// error to quote for the porosity; standard_error treats every droplet as independent.
  int media_passed = 0;
  double media_standard_error = 0;
  double stuck_fraction = 0;
  /// The other averaging: each medium's mean T first, then their plain mean over the media_passed
  /// media, and its standard error over them (0 if fewer than two). Every medium counts alike;
  /// mean_t counts a medium by its passed droplets.
  double per_medium_t = 0, per_medium_standard_error = 0;
};
/// Aggregates records by target porosity (ascending); points with no passed droplet are kept with
/// mean_t = 0 and passed = 0. `second_droplets`: the pairs' seconds instead of the droplets.
std::vector<SweepPoint> sweep_points(const std::vector<SweepMedium>& media, bool second_droplets = false);

}  // namespace softdrop
