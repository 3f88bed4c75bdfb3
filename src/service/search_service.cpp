// A search's run on a history file (softdrop/service.hpp): a new run from its first arrangement,
// or a stored one read back and checked; its generations stored as they end; the end's held-out
// value.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <optional>
#include <stdexcept>

#include "service/run_values.hpp"
#include "service/search_start.hpp"
#include "softdrop/service.hpp"
#include "store/params_json.hpp"
#include "util/validation.hpp"
#include "util/worker_threads.hpp"

namespace softdrop {

bool SearchRun::IsValid(std::string* why) const {
  using detail::fail;
  using detail::num;
  if (generations && (*generations < 0 || *generations > 1'000'000'000))
    return fail(why, "generations = " + std::to_string(*generations) + ": must be in [0, 1e9]");
  if (!(time_limit >= 0) || !std::isfinite(time_limit))
    return fail(why, "time-limit = " + num(time_limit) + ": must be >= 0");
  if (!detail::valid_threads(threads, why)) return false;
  DriveOptions drive;
  drive.lanes = lanes;
  if (!drive.IsValid(why)) return false;
  if (validate_starts < 0 || validate_starts > kMaxHeldOutStarts)
    return fail(why, "validate-starts = " + std::to_string(validate_starts) + ": must be in [0, 1e6]");
  if (start.attempts < 1) return fail(why, "start-attempts = " + std::to_string(start.attempts) + ": must be >= 1");
  if (resume < 0) return fail(why, "resume = " + std::to_string(resume) + ": not a run id");
  if (db.empty()) return fail(why, "db: an empty file name");
  try {
    if (!island_options(*this).IsValid(why)) return false;
  } catch (const std::invalid_argument& e) {
    return fail(why, e.what());
  }
  if (own_island_starts && !start.file.empty())
    return fail(why, "island-starts = own: needs generated media, not --medium " + start.file);
  if (resume > 0) return true;  // a resumed run takes its options from the history
  if (own_island_starts && islands < 2) return fail(why, "island-starts = own: an option of --islands K (K > 1)");
  if (!given_options_used(search, given, why)) return false;
  // (0 grains would mean "fill to a porosity" to the medium generator, which a search does not offer)
  if (start.file.empty()) {
    if (start.medium.grains < 1) return fail(why, "grains = " + std::to_string(start.medium.grains) + ": must be >= 1");
    if (!start.medium.IsValid(why)) return false;
  }
  return search.IsValid(why);
}

IslandOptions island_options(const SearchRun& run) {
  IslandOptions o;
  o.islands = run.islands;
  o.migrate_every = run.migrate_every;
  o.migration = parse_migration(run.migration);
  return o;
}

nlohmann::json wanted_params(const SearchRun& run) {
  nlohmann::json j = search_run_params(run.search, run.start);
  if (run.islands > 1)  // (runs of one search keep the parameters they always had)
    set_island_params(run, &j);
  else if (run.own_island_starts)
    j["island-starts"] = island_starts_name(true);  // (on a resumed run of one search: a contradiction)
  return j;
}

DriveOptions drive_options(const SearchRun& run, std::int64_t target, SearchObserver& observer) {
  DriveOptions d;
  d.generations = target;
  d.time_limit = run.time_limit;
  d.stop = observer.stop_flag();
  d.threads = run.threads;
  d.speculate = run.speculate;
  d.lanes = run.lanes;
  return d;
}

bool resumes_islands(const SearchRun& run) {
  if (run.resume <= 0 || !std::filesystem::exists(run.db)) return false;
  auto history = open_history(run.db, OpenMode::read_only);
  for (const RunRecord& r : history->runs())
    if (r.id == run.resume) return r.archipelago != 0;
  return false;  // the one search's path says the run is missing
}

namespace {

// A stored run read back: its record, and the target stored with it (none for a run stored before
// targets were).
struct ReadBack {
  RunRecord record;
  std::optional<std::int64_t> stored_target;
};

// The stored run `run.resume`, read back and checked against what the caller gave; its options
// are returned in `options`. Nothing is written.
ReadBack read_back(History& history, const SearchRun& run, SearchOptions* options) {
  const std::vector<RunRecord> runs = history.runs();
  if (std::none_of(runs.begin(), runs.end(), [&](const RunRecord& r) { return r.id == run.resume; }))
    throw std::invalid_argument(
        "resume = " + std::to_string(run.resume) + ": '" + run.db + "' has no run " + std::to_string(run.resume) +
        (runs.empty() ? " (it has no runs)" : " (its last run is " + std::to_string(runs.back().id) + ")"));
  history.check_run(run.resume);
  ReadBack r{history.run(run.resume), std::nullopt};
  try {
    *options = search_params_from_json(r.record.params);
  } catch (const std::exception& e) {
    throw std::runtime_error("--db '" + run.db + "': run " + std::to_string(run.resume) + ": " + e.what());
  }
  const nlohmann::json stored = stored_params(r.record, *options);
  if (const std::string bad = contradictions(wanted_params(run), stored, run.given); !bad.empty())
    throw std::invalid_argument("resume " + std::to_string(run.resume) +
                                ": the command line contradicts the stored run: " + bad);
  r.stored_target = stored_target(stored, run.db, run.resume);
  return r;
}

}  // namespace

SearchRunSummary run_search(const SearchRun& run, SearchObserver& observer) {
  return run_search(run, observer, nullptr);
}

SearchRunSummary run_search(const SearchRun& run, SearchObserver& observer, const IslandsDrive* islands) {
  std::string why;
  if (!run.IsValid(&why)) throw std::invalid_argument(why);
  // (a run of one search resumed with islands > 1 is refused below, as any contradicting option is)
  if (run.resume > 0 ? resumes_islands(run) : run.islands > 1) return run_islands(run, observer, islands);
  SearchRunSummary summary;
  summary.resumed = run.resume > 0;
  std::unique_ptr<History> history;
  std::unique_ptr<Search> search;
  SearchOptions options = run.search;
  if (summary.resumed) {
    history = open_history(run.db, OpenMode::read_only);  // checks the file before any write
    history.reset();
    history = open_history(run.db, OpenMode::create);
    const ReadBack back = read_back(*history, run, &options);
    const RunRecord& rec = back.record;
    // Without a target a resume goes on to the run's own (runs stored before targets were: the
    // default); a target at or below the last generation leaves the run as it is.
    summary.target = run.generations.value_or(back.stored_target.value_or(SearchRun::kDefaultGenerations));
    summary.run = rec.id;
    summary.search = options;
    if (summary.target <= rec.generations) {
      summary.nothing_to_do = true;
      summary.drive.last_generation = rec.generations;
      summary.drive.best_t = rec.best_t;
      summary.best.generation = rec.best_generation;
      summary.best.eval.tortuosity = rec.best_t;
      // A run killed after its last generation but before it was marked finished is finished.
      if (back.stored_target && rec.generations >= *back.stored_target && rec.status != "finished")
        history->set_status(rec.id, "finished");
      return summary;
    }
    search = std::make_unique<Search>(resumed_search(*history, rec, options));
    // Only once the run has been read back and checked: a refused resume writes nothing.
    if (run.generations && back.stored_target != run.generations)
      history->set_param(rec.id, "target-generations", std::to_string(summary.target));
  } else {
    summary.target = run.generations.value_or(SearchRun::kDefaultGenerations);
    // An existing file is checked first; a new one is created only once generation 0 exists, so
    // a start that fails leaves no file behind.
    check_database(run.db);  // (a new file: its folder must exist and be writable)
    Configuration best;
    const Generation g0 = starting_generation(run.start, options, &best, [&](int attempt, const std::string& reason) {
      observer.start_refused(attempt, reason);
    });
    summary.initial_evaluations = static_cast<std::int64_t>(g0.candidates.size());
    summary.initial_droplets = g0.candidates.front().eval.droplets;
    history = open_history(run.db, OpenMode::create);
    nlohmann::json params = wanted_params(run);
    params["target-generations"] = summary.target;  // where a resume without a target goes on to
    summary.run = history->create_run(params.dump(), options, g0, best);
    search = std::make_unique<Search>(options, std::move(best), 0);
  }
  summary.search = options;

  observer.started(summary.run, search->best(), search->last_generation(), summary.target, summary.resumed);
  summary.drive =
      drive(*search, drive_options(run, summary.target, observer), [&](const Generation& g, const Configuration& best) {
        history->append(summary.run, g, best);
        return observer.generation(summary.run, -1, g, best, summary.target);
      });
  const bool reached = summary.drive.termination == Termination::generations;
  history->set_status(summary.run, reached ? "finished" : "interrupted");
  summary.best = search->best();
  // A run that reached its target gets its best's held-out value; a stopped one is left to
  // `softdrop validate`, so that a stop takes effect at once.
  if (reached && run.validate_starts > 0)
    summary.held_out = validate_kept(
        *history, summary.run, options, summary.best, run.validate_starts, run.threads,
        [&](int done, int total) { observer.validating(done, total); }, &summary.held_out_objective);
  return summary;
}

}  // namespace softdrop
