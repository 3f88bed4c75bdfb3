// A search of islands on a history file (service.hpp, search_start.hpp): K runs made or resumed
// together, driven between migrations on threads or ranks, each generation stored as it ends.
#include <algorithm>
#include <memory>
#include <stdexcept>

#include "service/run_values.hpp"
#include "service/search_start.hpp"
#include "softdrop/medium.hpp"
#include "store/params_json.hpp"
#include "util/random.hpp"

namespace softdrop {
namespace {

// The islands' runs of the archipelago that `run` belongs to, by island; checks they are whole.
std::vector<RunRecord> archipelago_of(History& history, const RunRecord& run, const std::string& db) {
  std::vector<RunRecord> members;
  for (const RunRecord& r : history.runs())
    if (r.archipelago == run.archipelago) members.push_back(r);
  std::sort(members.begin(), members.end(), [](const RunRecord& x, const RunRecord& y) { return x.island < y.island; });
  const nlohmann::json params = nlohmann::json::parse(members.front().params);
  const int islands = params.value("islands", 0);
  bool whole = static_cast<int>(members.size()) == islands;
  for (std::size_t i = 0; whole && i < members.size(); ++i) whole = members[i].island == static_cast<int>(i);
  if (!whole)
    throw std::runtime_error("--db '" + db + "': the islands of run " + std::to_string(run.archipelago) + " are " +
                             std::to_string(members.size()) + " runs, not its " + std::to_string(islands) +
                             " islands (cut short while it was being made?): start it again");
  return members;
}

// What run_islands makes or reads back before the drive.
struct Archipelago {
  SearchOptions search;
  IslandOptions islands;
  std::vector<std::int64_t> runs;
  std::vector<Search> searches;
  std::vector<Configuration> starts;  // what the observer hears of
  std::int64_t target = 0;
};

// The islands of a stored run, read back and checked against what the caller gave; nothing is
// written unless they all are.
Archipelago resumed(History& history, const SearchRun& run, const nlohmann::json& wanted) {
  Archipelago a;
  const std::vector<RunRecord> members = archipelago_of(history, history.run(run.resume), run.db);
  nlohmann::json stored;
  try {
    a.search = search_params_from_json(members.front().params);
    stored = stored_params(members.front(), a.search);
    a.islands.islands = stored.at("islands").get<int>();
    a.islands.migrate_every = stored.at("migrate-every").get<int>();
    a.islands.migration = parse_migration(stored.at("migration").get<std::string>());
  } catch (const std::exception& e) {
    throw std::runtime_error("--db '" + run.db + "': run " + std::to_string(members.front().id) + ": " + e.what());
  }
  if (!stored.contains("island-starts")) stored["island-starts"] = island_starts_name(false);  // made before it
  stored.erase("island");
  if (const std::string bad = contradictions(wanted, stored, run.given); !bad.empty())
    throw std::invalid_argument("resume " + std::to_string(run.resume) +
                                ": the command line contradicts the stored run: " + bad);
  a.target = run.generations.value_or(
      stored_target(stored, run.db, members.front().id).value_or(SearchRun::kDefaultGenerations));
  for (const RunRecord& r : members) {
    history.check_run(r.id);
    a.runs.push_back(r.id);
    a.searches.push_back(resumed_search(history, r, island_search_options(a.search, r.island)));
    a.starts.push_back(a.searches.back().best());
  }
  // Only once every island has been read back: a refused resume writes nothing.
  if (run.generations)
    for (const RunRecord& r : members) history.set_param(r.id, "target-generations", std::to_string(a.target));
  return a;
}

}  // namespace

std::size_t best_island(const std::vector<Configuration>& bests) {
  std::size_t top = 0;
  for (std::size_t i = 1; i < bests.size(); ++i)
    if (bests[i].eval.tortuosity > bests[top].eval.tortuosity) top = i;
  return top;
}

SearchRunSummary run_islands(const SearchRun& run, SearchObserver& observer, const IslandsDrive* driver) {
  SearchRunSummary summary;
  summary.resumed = run.resume > 0;
  // Given or not, the islands' keys take part in the check of a resume (only those given count).
  nlohmann::json wanted = wanted_params(run);
  set_island_params(run, &wanted);
  std::unique_ptr<History> history;
  Archipelago a;
  if (summary.resumed) {
    history = open_history(run.db, OpenMode::create);
    a = resumed(*history, run, wanted);
  } else {
    a.search = run.search;
    a.islands = island_options(run);
    a.target = run.generations.value_or(SearchRun::kDefaultGenerations);
    check_database(run.db);  // (a new file: its folder must exist and be writable)
    // Every island starts from one medium, or each from its own, all made before the history is
    // touched. The single objective's evaluation takes no seed, so one evaluation serves every
    // island; a robust objective's starts come from the island's seed, so each evaluates its own.
    const bool each = run.own_island_starts || a.search.objective.robust();
    const std::size_t starts = each ? static_cast<std::size_t>(a.islands.islands) : 1;
    std::vector<Generation> g0(starts);
    a.starts.resize(starts);
    for (std::size_t s = 0; s < starts; ++s) {
      SearchStart start = run.start;
      if (run.own_island_starts) start.medium.seed = derive_seed(run.start.medium.seed, s);
      g0[s] = starting_generation(start, island_search_options(a.search, static_cast<int>(s)), &a.starts[s],
                                  [&](int attempt, const std::string& why) { observer.start_refused(attempt, why); });
      summary.initial_evaluations += static_cast<std::int64_t>(g0[s].candidates.size());
      summary.initial_droplets += g0[s].candidates.front().eval.droplets;
    }
    history = open_history(run.db, OpenMode::create);
    nlohmann::json params = wanted;
    params["target-generations"] = a.target;
    for (int i = 0; i < a.islands.islands; ++i) {
      const std::size_t s = each ? static_cast<std::size_t>(i) : 0;
      params["island"] = i;
      const SearchOptions options = island_search_options(a.search, i);
      const std::int64_t id = history->create_run(params.dump(), options, g0[s], a.starts[s]);
      history->set_island(id, i, a.runs.empty() ? id : a.runs.front());
      a.runs.push_back(id);
      a.searches.emplace_back(options, a.starts[s], 0);
    }
  }
  // Each island's last generation and best, as it reports them (the callbacks are called one at
  // a time; the islands themselves may be running on other threads, or other ranks).
  std::vector<std::int64_t> last;
  std::vector<Configuration> best_of;
  for (const Search& s : a.searches) last.push_back(s.last_generation()), best_of.push_back(s.best());
  observer.islands_started(a.runs, last, a.starts, a.target, summary.resumed);
  IslandCallbacks callbacks;
  callbacks.generation = [&](int island, const Generation& g, const Configuration& best) {
    const auto i = static_cast<std::size_t>(island);
    history->append(a.runs[i], g, best);
    last[i] = g.number;
    if (best.generation != best_of[i].generation) best_of[i] = best;
    return observer.generation(a.runs[i], island, g, best, a.target);
  };
  callbacks.migration = [&](const std::vector<Generation>& gs, const std::vector<Configuration>& bests) {
    history->append_together(a.runs, gs, bests);
    for (std::size_t i = 0; i < gs.size(); ++i) last[i] = gs[i].number, best_of[i] = bests[i];
    bool go_on = true;
    for (std::size_t i = 0; i < gs.size(); ++i)
      go_on = observer.generation(a.runs[i], static_cast<int>(i), gs[i], bests[i], a.target) && go_on;
    return go_on;
  };
  const DriveOptions options = drive_options(run, a.target, observer);
  summary.drive = driver && driver->drive ? driver->drive(a.searches, a.islands, options, callbacks)
                                          : drive_islands(a.searches, a.islands, options, callbacks);
  for (std::size_t i = 0; i < a.runs.size(); ++i) {
    history->set_status(a.runs[i], last[i] >= a.target ? "finished" : "interrupted");
    summary.islands.push_back({a.runs[i], last[i], best_of[i]});
  }
  const std::size_t top = best_island(best_of);
  summary.best_island = static_cast<int>(top);
  summary.run = a.runs.front();
  summary.best = best_of[top];
  summary.search = a.search;
  summary.target = a.target;
  summary.migrate_every = a.islands.migrate_every;
  summary.migration = to_string(a.islands.migration);
  // The best island's best gets its held-out value, stored with that island's run, when every
  // island reached the target (a stopped search leaves it to `softdrop validate`).
  if (summary.drive.termination == Termination::generations && run.validate_starts > 0)
    summary.held_out = validate_kept(
        *history, a.runs[top], a.search, summary.best, run.validate_starts, run.threads,
        [&](int done, int total) { observer.validating(done, total); }, &summary.held_out_objective);
  return summary;
}

}  // namespace softdrop
