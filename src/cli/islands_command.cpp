// `softdrop optimize --islands K`: K searches of one archipelago, each a run of the history
// (runs.island, runs.archipelago = the first run's id); `--resume` of any of them continues all.
#include "cli/islands_command.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <iostream>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "cli/mpi_islands.hpp"
#include "cli/output.hpp"
#include "service/search_start.hpp"
#include "softdrop/medium.hpp"
#include "softdrop/version.hpp"
#include "store/params_json.hpp"
#include "util/random.hpp"

namespace softdrop::cli {
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

// The island with the highest best T (the lowest-numbered among equals).
std::size_t best_island(const std::vector<Configuration>& bests) {
  std::size_t top = 0;
  for (std::size_t i = 1; i < bests.size(); ++i)
    if (bests[i].eval.tortuosity > bests[top].eval.tortuosity) top = i;
  return top;
}

// Progress on stderr: at most once a second on a terminal, every 10 s otherwise.
class IslandsProgress {
 public:
  IslandsProgress(std::int64_t target, bool quiet) : target_(target), quiet_(quiet), tty_(::isatty(2) != 0) {}
  void update(const std::vector<std::int64_t>& last, const std::vector<Configuration>& bests, std::int64_t evaluations,
              bool force) {
    if (quiet_) return;
    const auto now = clock::now();
    if (!force && now - last_ < (tty_ ? std::chrono::seconds(1) : std::chrono::seconds(10))) return;
    last_ = now;
    const std::int64_t lowest = *std::min_element(last.begin(), last.end());
    const std::size_t top = best_island(bests);
    const double s = std::chrono::duration<double>(now - t0_).count();
    std::ostringstream line;
    line << "optimize: " << last.size() << " islands at generation " << lowest << "/" << target_ << "  best T "
         << fmt(bests[top].eval.tortuosity, 8) << " (island " << top << ")  "
         << fmt(s > 0 ? static_cast<double>(evaluations) / s : 0.0, 3) << " eval/s";
    std::cerr << (tty_ ? "\r" : "") << line.str() << (tty_ && !force ? "\033[K" : "\n") << std::flush;
  }

 private:
  using clock = std::chrono::steady_clock;
  std::int64_t target_;
  bool quiet_, tty_;
  clock::time_point t0_ = clock::now(), last_ = t0_;
};

}  // namespace

bool resumes_islands(const OptimizeArgs& a) {
  if (a.resume <= 0 || !std::filesystem::exists(a.db)) return false;
  auto history = open_history(a.db, OpenMode::read_only);
  for (const RunRecord& r : history->runs())
    if (r.id == a.resume) return r.archipelago != 0;
  return false;  // the single-run path says the run is missing
}

int run_islands(OptimizeArgs& a, const CLI::App& cmd, Host* host) {
  nlohmann::json given = params_of(a);
  given["islands"] = a.islands.islands;  // (given or not: only those given are compared on resume)
  given["migrate-every"] = a.islands.migrate_every;
  given["migration"] = to_string(a.islands.migration);
  given["island-starts"] = island_starts_name(a.own_island_starts);
  std::unique_ptr<History> history;
  std::vector<std::int64_t> runs;
  std::vector<Search> islands;
  std::int64_t initial_evaluations = 0;
  if (a.resume > 0) {
    history = open_history(a.db, OpenMode::create);
    const std::vector<RunRecord> members = archipelago_of(*history, history->run(a.resume), a.db);
    nlohmann::json stored = nlohmann::json::parse(members.front().params);
    try {
      a.search = search_params_from_json(members.front().params);
      a.islands.islands = stored.at("islands").get<int>();
      a.islands.migrate_every = stored.at("migrate-every").get<int>();
      a.islands.migration = parse_migration(stored.at("migration").get<std::string>());
      if (!stored.contains("island-starts")) stored["island-starts"] = island_starts_name(false);  // made before it
      a.own_island_starts = stored.at("island-starts").get<std::string>() == island_starts_name(true);
    } catch (const std::exception& e) {
      throw std::runtime_error("--db '" + a.db + "': run " + std::to_string(members.front().id) + ": " + e.what());
    }
    const nlohmann::json read_back = nlohmann::json::parse(search_params_to_json(a.search));
    for (const auto& [key, value] : read_back.items())
      if (!stored.contains(key)) stored[key] = value;
    stored.erase("island");
    if (const std::string bad = contradictions(given, stored, given_keys(given, a, &cmd)); !bad.empty())
      throw std::invalid_argument("resume " + std::to_string(a.resume) +
                                  ": the command line contradicts the stored run: " + bad);
    const bool target_given = cmd.get_option("--generations")->count() > 0;
    if (!target_given && stored.contains("target-generations"))
      a.generations = stored["target-generations"].get<std::int64_t>();
    for (const RunRecord& r : members) {
      history->check_run(r.id);
      runs.push_back(r.id);
      islands.push_back(resumed_search(*history, r, island_search_options(a.search, r.island)));
    }
    // Only once every island has been read back: a refused resume writes nothing.
    if (target_given)
      for (const RunRecord& r : members) history->set_param(r.id, "target-generations", std::to_string(a.generations));
    if (!a.quiet)
      std::cerr << "optimize: resuming the " << runs.size() << " islands of run " << runs.front() << " in " << a.db
                << "\n";
  } else {
    check_database(a.db);  // (a new file: its folder must exist and be writable)
    // Every island starts from one medium, or each from its own, all made before the history is
    // touched. The single objective's evaluation takes no seed, so one evaluation serves every
    // island; a robust objective's starts come from the island's seed, so each evaluates its own.
    const bool each = a.own_island_starts || a.search.objective.robust();
    const std::size_t starts = each ? static_cast<std::size_t>(a.islands.islands) : 1;
    std::vector<Generation> g0(starts);
    std::vector<Configuration> first_of(starts);
    for (std::size_t s = 0; s < starts; ++s) {
      OptimizeArgs from = a;
      if (a.own_island_starts) from.medium.options.seed = derive_seed(a.medium.options.seed, s);
      from.search = island_search_options(a.search, static_cast<int>(s));
      g0[s] = starting_generation(start_of(from), from.search, &first_of[s], [&](int attempt, const std::string& why) {
        if (!a.quiet) std::cerr << "optimize: starting medium " << attempt << ": " << why << "; trying another\n";
      });
      initial_evaluations += static_cast<std::int64_t>(g0[s].candidates.size());
    }
    history = open_history(a.db, OpenMode::create);
    nlohmann::json params = given;
    params["target-generations"] = a.generations;
    for (int i = 0; i < a.islands.islands; ++i) {
      const std::size_t s = each ? static_cast<std::size_t>(i) : 0;
      params["island"] = i;
      const SearchOptions options = island_search_options(a.search, i);
      const std::int64_t id = history->create_run(params.dump(), options, g0[s], first_of[s]);
      history->set_island(id, i, runs.empty() ? id : runs.front());
      runs.push_back(id);
      islands.emplace_back(options, first_of[s], 0);
    }
    if (!a.quiet)
      for (std::size_t s = 0; s < first_of.size(); ++s)
        std::cerr << "optimize: " << (each ? "island " + std::to_string(s) + " of " : std::string()) << runs.size()
                  << " islands, runs " << runs.front() << " to " << runs.back() << " in " << a.db << ": "
                  << first_of[s].medium.grains.size() << " grains, porosity "
                  << fmt(exact_porosity(first_of[s].medium), 6) << ", T0 = " << fmt(first_of[s].eval.tortuosity, 8)
                  << "\n";
  }

  std::optional<StopOnSignal> stop;  // a host handles the signals itself
  if (!host) stop.emplace("\nsoftdrop: stopping after the generations in flight (Ctrl-C again to drop them)\n");
  IslandsProgress progress(a.generations, a.quiet);
  std::int64_t evaluations = 0;
  const DriveOptions drive = drive_options_of(a, stop ? stop->flag() : nullptr);
  auto tell_host = [&](int island, const Generation& g, const Configuration& best) {
    if (!host || !host->on_progress) return true;
    nlohmann::json event = generation_event(runs[static_cast<std::size_t>(island)], g, best, a.generations);
    event["island"] = island;
    return host->on_progress(event);
  };
  // Each island's last generation and best, as it reports them (the callbacks are called one at
  // a time; the islands themselves may be running on other threads, or other ranks).
  std::vector<std::int64_t> last;
  std::vector<Configuration> best_of;
  for (const Search& s : islands) last.push_back(s.last_generation()), best_of.push_back(s.best());
  IslandCallbacks callbacks;
  callbacks.generation = [&](int island, const Generation& g, const Configuration& best) {
    const auto i = static_cast<std::size_t>(island);
    history->append(runs[i], g, best);
    last[i] = g.number;
    if (best.generation != best_of[i].generation) best_of[i] = best;
    evaluations += static_cast<std::int64_t>(g.candidates.size());
    progress.update(last, best_of, evaluations, false);
    return tell_host(island, g, best);
  };
  callbacks.migration = [&](const std::vector<Generation>& gs, const std::vector<Configuration>& bests) {
    history->append_together(runs, gs, bests);
    for (std::size_t i = 0; i < gs.size(); ++i) last[i] = gs[i].number, best_of[i] = bests[i];
    bool go_on = true;
    for (std::size_t i = 0; i < gs.size(); ++i) go_on = tell_host(static_cast<int>(i), gs[i], bests[i]) && go_on;
    return go_on;
  };
  const Job* job = current_job();
  const SearchSummary summary = job && job->size() > 1
                                    ? drive_islands_on_ranks(*job, islands, a.islands, drive, callbacks)
                                    : drive_islands(islands, a.islands, drive, callbacks);
  progress.update(last, best_of, evaluations, true);
  nlohmann::json per_island = nlohmann::json::array();
  const std::size_t top = best_island(best_of);
  for (std::size_t i = 0; i < runs.size(); ++i) {
    history->set_status(runs[i], last[i] >= a.generations ? "finished" : "interrupted");
    per_island.push_back({{"island", i},
                          {"run", runs[i]},
                          {"last_generation", last[i]},
                          {"best_tortuosity", best_of[i].eval.tortuosity},
                          {"best_generation", best_of[i].generation}});
  }
  // The best island's best gets its held-out value, stored with that island's run, when every
  // island reached the target (a stopped search leaves it to `softdrop validate`).
  const nlohmann::json held_out = summary.termination == Termination::generations
                                      ? validate_best(a, *history, runs[top], best_of[top])
                                      : nlohmann::json();
  nlohmann::json j{{"version", kVersion},
                   {"db", a.db},
                   {"run", runs.front()},
                   {"strategy", to_string(a.search.strategy.kind)},
                   {"islands", per_island},
                   {"migrate_every", a.islands.migrate_every},
                   {"migration", to_string(a.islands.migration)},
                   {"termination", to_string(summary.termination)},
                   {"message", summary.message},
                   {"last_generation", summary.last_generation},
                   {"generations_run", summary.generations_run},
                   {"evaluations", summary.evaluations + initial_evaluations},
                   {"accepted", summary.accepted},
                   {"best_tortuosity", summary.best_t},
                   {"best_island", top},
                   {"best_run", runs[top]},
                   {"held_out", held_out},
                   {"wall_seconds", summary.seconds},
                   {"evaluations_per_second", summary.evaluations_per_second()}};
  if (!deliver_summary(a, j, host)) {
    std::cout << "runs         " << runs.front() << " to " << runs.back() << " in " << a.db << " (" << runs.size()
              << " islands, "
              << (a.islands.migrate_every > 0 ? std::string(to_string(a.islands.migration)) + " migration every " +
                                                    std::to_string(a.islands.migrate_every) + " generations"
                                              : std::string("no migration"))
              << ")\n"
              << "stopped      " << summary.message << "\n"
              << "best T       " << fmt(summary.best_t, 10) << " (island " << top << ", run " << runs[top]
              << ", generation " << best_of[top].generation << ")\n"
              << "this session " << summary.generations_run << " generations, " << summary.accepted << " accepted, "
              << summary.evaluations + initial_evaluations << " evaluations, "
              << fmt(summary.evaluations_per_second(), 3) << " eval/s\n";
    print_held_out(std::cout, held_out);
  }
  return summary.termination == Termination::interrupted && stop ? stop->exit_code() : 0;
}

}  // namespace softdrop::cli
