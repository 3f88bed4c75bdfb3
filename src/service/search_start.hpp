#pragma once
// What a search's run on a history needs for one search and for islands alike (service.hpp): the
// parameters stored with a run, its first arrangement, a stored run read back, the check of given
// options against a stored run, and the held-out value stored at the end.

#include <cstdint>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "optimizer/islands.hpp"
#include "softdrop/search.hpp"
#include "softdrop/service.hpp"
#include "softdrop/store.hpp"

namespace softdrop {

/// How islands are driven: drive_islands on this process's threads by default, the program's MPI
/// ranks otherwise (drive_islands' contract).
struct IslandsDrive {
  std::function<SearchSummary(std::vector<Search>& islands, const IslandOptions& options, const DriveOptions& drive,
                              const IslandCallbacks& callbacks)>
      drive;
};

/// The island options of a run (SearchRun's islands, migrate_every and migration). Throws
/// std::invalid_argument naming an unknown migration.
IslandOptions island_options(const SearchRun& run);

/// Whether `run` resumes one of islands (reads its history; false if it has no such run).
bool resumes_islands(const SearchRun& run);

/// The parameters of `run` as stored with a new run and compared on resume: the search's, the
/// start's (search_run_params) and, for islands, theirs (islands, migrate-every, migration,
/// island-starts).
nlohmann::json wanted_params(const SearchRun& run);

/// A search of islands (SearchRun::islands > 1, or a resume of one of islands): run_search's
/// contract for each island's run.
SearchRunSummary run_islands(const SearchRun& run, SearchObserver& observer, const IslandsDrive* drive);

/// The drive's options of a run: its target, time limit, threads, lanes and speculation, and the
/// observer's stop flag.
DriveOptions drive_options(const SearchRun& run, std::int64_t target, SearchObserver& observer);

/// The island with the highest best T (the lowest-numbered among equals).
std::size_t best_island(const std::vector<Configuration>& bests);

/// Generation 0 of a new run: the grain file's medium, or random media until the droplet passes
/// (`refused(attempt, why)` hears of each that it does not). A medium that cannot be generated at
/// all (too many grains for the box, say) is an error, not a retry; so is an image file.
Generation starting_generation(const SearchStart& start, const SearchOptions& search, Configuration* best,
                               const std::function<void(int, const std::string&)>& refused = {});

/// A stored run as a search that continues it, after checking that this build evaluates its
/// current and best arrangements as stored (throws std::runtime_error naming the run if not).
Search resumed_search(History& history, const RunRecord& run, const SearchOptions& options);

/// The stored parameters of a run, with the keys a run stored before they existed read as what it
/// did (search_params_to_json of `options`, the run's options read back).
nlohmann::json stored_params(const RunRecord& run, const SearchOptions& options);

/// The target a resume without one goes on to, as stored with the run (`stored`: its parameters;
/// none if it has no target stored). Throws std::runtime_error naming the db and run if the stored
/// target is not a whole number in [0, 1e9].
std::optional<std::int64_t> stored_target(const nlohmann::json& stored, const std::string& db, std::int64_t run);

/// The `given` keys whose value in `wanted` is not the stored one, as "--key value (stored value)"
/// items; "" when none differs.
std::string contradictions(const nlohmann::json& wanted, const nlohmann::json& stored,
                           const std::vector<std::string>& given);

/// The held-out value of the arrangement `best` (kept as of best.generation) over `starts` random
/// starts at dt and dt/2, stored with run `run`; `objective`, for a robust objective, is set to its
/// value over those starts at dt.
ValidationRecord validate_kept(History& history, std::int64_t run, const SearchOptions& search,
                               const Configuration& best, int starts, int threads,
                               const std::function<void(int, int)>& progress, double* objective);

}  // namespace softdrop
