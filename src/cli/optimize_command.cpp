#include "cli/optimize_command.hpp"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstring>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "cli/islands_command.hpp"
#include "cli/mpi_islands.hpp"
#include "cli/output.hpp"
#include "service/run_values.hpp"
#include "service/search_start.hpp"
#include "softdrop/medium.hpp"
#include "softdrop/store.hpp"
#include "softdrop/version.hpp"
#include "store/params_json.hpp"

namespace softdrop::cli {

CLI::App* add_optimize_command(CLI::App& app, OptimizeArgs& a) {
  CLI::App* s = app.add_subcommand(
      "optimize", "Search grain arrangements of maximum tortuosity, logging every generation to SQLite");
  s->fallthrough();

  auto* h = s->add_option_group("History");
  h->add_option("--db", a.out.db, "SQLite history file (created if missing; holds many runs)")->capture_default_str();
  h->add_option("--resume", a.resume, "Continue this run of the database instead of starting a new one")
      ->check(id_check());

  auto* g = s->add_option_group("Search", "stored with the run; a resume must not contradict them");
  g->add_option("--generations", a.generations,
                "Run up to this generation number (a resume without it goes on to the run's own target)")
      ->capture_default_str();
  g->add_option("--time-limit", a.time_limit, "Stop after this many wall seconds (0: no limit)")->capture_default_str();
  g->add_option("--lambda", a.search.lambda,
                "Candidates per generation, evaluated in parallel (1 with --strategy paper: the paper)")
      ->capture_default_str();
  g->add_option("--preset", a.preset,
                "paper: the paper's algorithm (--strategy paper --lambda 1 --relocate-every 0, its two moves at "
                "their default steps) for every search option not given")
      ->check(CLI::IsMember({"paper"}));
  g->add_option("--seed", a.search.seed, "Seed of the moves")->capture_default_str()->check(seed_check());
  g->add_option("--single-every", a.search.single_every,
                "Every this-th generation moves one grain the droplet touched (0: never)")
      ->capture_default_str();
  g->add_option("--relocate-every", a.search.relocate_every,
                "Every this-th generation puts one grain the droplet did not touch next to its path (0: never)")
      ->capture_default_str();
  g->add_option("--step", a.search.step, "All-grain move: jump radius of each grain (length units)")
      ->capture_default_str();
  g->add_option("--single-step", a.search.single_step, "Single move: jump radius of the grain (length units)")
      ->capture_default_str();
  g->add_option_function<std::string>(
       "--strategy", [&a](const std::string& v) { a.search.strategy.kind = parse_strategy(v); },
       "paper (the paper's hill climb), es (its moves with step sizes that adapt), lahc (late acceptance: "
       "also keeps candidates no worse than history-length generations ago), anneal (simulated annealing) or cmaes "
       "(CMA-ES on every grain centre, a population of --lambda >= 5)")
      ->check(CLI::IsMember(strategy_names()))
      ->default_str(to_string(a.search.strategy.kind));
  g->add_option("--target-success", a.search.strategy.target_success,
                "es: share of candidates that should improve; steps grow above it, shrink below")
      ->capture_default_str();
  g->add_option("--history-length", a.search.strategy.history_length,
                "lahc: generations back that a candidate is compared with")
      ->capture_default_str();
  g->add_option("--temperature", a.search.strategy.temperature,
                "anneal: temperature at generation 0 (units of T): a candidate dT worse is kept with probability "
                "exp(dT / temperature)")
      ->capture_default_str();
  g->add_option("--half-life", a.search.strategy.half_life, "anneal: generations in which the temperature halves")
      ->capture_default_str();
  g->add_option("--sigma", a.search.strategy.sigma,
                "cmaes: the Gaussian's first standard deviation of each grain coordinate (length units); it adapts")
      ->capture_default_str();
  add_objective_options(g, a);
  g->add_option("--islands", a.islands.islands,
                "Island model: this many searches with seeds of their own, run side by side, each a run of the "
                "history; every --migrate-every generations each takes another's best (1: one search)")
      ->capture_default_str();
  g->add_option("--migrate-every", a.islands.migrate_every,
                "Islands: generations between migrations (0: never: independent lineages from the same start, the best "
                "of them kept)")
      ->capture_default_str();
  g->add_option_function<std::string>(
       "--migration", [&a](const std::string& v) { a.islands.migration = parse_migration(v); },
       "Islands: ring (island i takes island i-1's best) or broadcast (every island takes the best of all)")
      ->check(CLI::IsMember(migration_names()))
      ->default_str(to_string(a.islands.migration));
  g->add_option_function<std::string>(
       "--island-starts", [&a](const std::string& v) { a.own_island_starts = v == island_starts_name(true); },
       "Islands: shared (every island starts from one medium) or own (each from a generated medium of its "
       "own: with --migrate-every 0, restarts that sample starting media)")
      ->check(CLI::IsMember({island_starts_name(false), island_starts_name(true)}))
      ->default_str(island_starts_name(false));
  g->add_option("--max-redraws", a.search.max_redraws,
                "Redraws of a jump refused by the spacing rule before the grain stays put")
      ->capture_default_str();
  g->add_option("--path-interval", a.search.run.path_interval, "Steps between stored path points")
      ->capture_default_str();
  g->add_option("--threads", a.threads, "Worker threads (0 = all cores); results do not depend on it")
      ->capture_default_str();
  g->add_flag("--no-speculation", a.no_speculation,
              "Evaluate one generation at a time (by default, with --strategy paper or es, idle threads "
              "evaluate the next generations ahead, assuming no improvement; the history is the same "
              "either way)");
  g->add_option("--lanes", a.lanes,
                "Candidates each thread steps together, in [0, 64] (0: chosen for this processor, see "
                "docs/search.md); a matter of speed only: results do not depend on it")
      ->capture_default_str();
  g->add_option("--validate-starts", a.validate_starts,
                "At the end, the best arrangement's held-out <T> over this many random starts, at dt and dt/2, "
                "stored in the history (as softdrop validate; 0: none)")
      ->capture_default_str();
  g->add_option("--start-attempts", a.start_attempts,
                "Random starting media to try until the droplet passes (generated media only)")
      ->capture_default_str();
  add_exit_options(g, a.search.run);

  add_medium_options(s, a.medium, true);
  add_droplet_options(s, a.search.droplet);

  // Once the command line and config are read: which stored keys were given, and the preset filling
  // in the search options not given, so that --check, the run and the stored parameters all see
  // the search that runs.
  s->parse_complete_callback([&a, s] {
    a.given.clear();
    const nlohmann::json keys = search_run_values(default_search_run());
    for (const auto& [key, value] : keys.items())
      if (const CLI::Option* o = s->get_option_no_throw("--" + key); o && o->count() > 0) a.given.push_back(key);
    for (std::string& key : apply_search_preset(a.preset, a.given, &a.search)) a.given.push_back(std::move(key));
  });

  auto* o = add_summary_options(s, a.out.format, a.out.json_file, a.out.quiet);
  o->add_flag("--verbose", a.out.verbose,
              "Also print how the speculation went: threads, lanes, evaluations dropped (JSON always has it)");
  return s;
}

namespace {

// Progress on stderr: at most once a second on a terminal, every 10 s otherwise.
class SearchProgress {
 public:
  /// `from`: the generation the session starts after (0 for a new run, the stored one on resume).
  SearchProgress(std::int64_t run, std::int64_t from, std::int64_t target, bool quiet)
      : run_(run), from_(from), target_(target), quiet_(quiet), tty_(::isatty(2) != 0), t0_(clock::now()), last_(t0_) {}
  void update(const Generation& g, const Configuration& best, bool force) {
    ++generations_;
    evaluations_ += static_cast<std::int64_t>(g.candidates.size());
    if (g.accepted >= 0) ++accepted_;
    if (quiet_) return;
    const auto now = clock::now();
    if (!force && now - last_ < (tty_ ? std::chrono::seconds(1) : std::chrono::seconds(10))) return;
    last_ = now;
    const double s = std::chrono::duration<double>(now - t0_).count();
    // A robust objective re-runs the best every generation (g.parent), so its value moves: say what
    // it is the mean of, as history --best does.
    const std::int64_t re_runs = g.number - best.generation;
    const std::string basis = g.parent.droplets == 0 ? ""
                              : re_runs > 0
                                  ? ", the mean of " + std::to_string(re_runs) + (re_runs > 1 ? " re-runs" : " re-run")
                                  : ", as kept";
    std::ostringstream line;
    line << "optimize: run " << run_ << " generation " << g.number << "/" << target_ << "  best T "
         << fmt(best.eval.tortuosity, 8) << " (gen " << best.generation << basis << ")  accepted " << accepted_ << "/"
         << generations_ << "  " << fmt(s > 0 ? static_cast<double>(evaluations_) / s : 0.0, 3) << " eval/s  "
         << percent_and_eta(s, static_cast<double>(g.number - from_), static_cast<double>(target_ - from_));
    std::cerr << (tty_ ? "\r" : "") << line.str() << (tty_ && !force ? "\033[K" : "\n") << std::flush;
  }

 private:
  using clock = std::chrono::steady_clock;
  std::int64_t run_, from_, target_;
  bool quiet_, tty_;
  clock::time_point t0_, last_;
  std::int64_t generations_ = 0, evaluations_ = 0, accepted_ = 0;
};

// The program's observer of a search's run: its lines and progress on stderr, the host's callback
// (the Python module's), and Ctrl-C when no host handles the signals itself.
class OptimizeObserver : public ProgramSearchObserver {
 public:
  OptimizeObserver(const SearchOutput& out, Host* host)
      : ProgramSearchObserver(out, host,
                              "\nsoftdrop: stopping after the generation in flight (Ctrl-C again to drop it)\n") {}
  void started(std::int64_t run, const Configuration& best, std::int64_t from, std::int64_t target,
               bool resumed) override {
    if (!out_.quiet) {
      if (resumed)
        std::cerr << "optimize: resuming run " << run << " of " << out_.db << " at generation " << from << " (best T "
                  << fmt(best.eval.tortuosity, 8) << ")\n";
      else
        std::cerr << "optimize: run " << run << " in " << out_.db << ": " << best.medium.grains.size()
                  << " grains, porosity " << fmt(exact_porosity(best.medium), 6)
                  << ", T0 = " << fmt(best.eval.tortuosity, 8) << "\n";
    }
    progress_.emplace(run, from, target, out_.quiet);
  }
  bool generation(std::int64_t run, int /*island*/, const Generation& g, const Configuration& best,
                  std::int64_t target) override {
    progress_->update(g, best, g.number == target);
    if (!host_ || !host_->on_progress) return true;
    return host_->on_progress(generation_event(run, g, best, target));
  }

 private:
  std::optional<SearchProgress> progress_;
};

}  // namespace

void check_optimize(const OptimizeArgs& a, const CLI::App& cmd) {
  if (!a.out.json_file.empty()) check_output_path("--json", a.out.json_file);
  if (std::string why; !search_run_of(a, &cmd).IsValid(&why)) throw std::invalid_argument(why);
}

int run_search_run(const SearchRun& run, const SearchOutput& out, Host* host, const IslandsDrive* ranks) {
  if (run.resume > 0 ? resumes_islands(run) : run.islands > 1) return run_islands(out, run, host, ranks);
  OptimizeObserver observer(out, host);
  const SearchRunSummary summary = run_search(run, observer);
  report_optimize(out, summary, host);
  return summary.drive.termination == Termination::interrupted ? observer.exit_code() : 0;
}

int run_optimize(OptimizeArgs& a, const CLI::App& cmd, Host* host) {
  check_optimize(a, cmd);
  const Job* job = current_job();
  const bool on_ranks = job && job->size() > 1;  // under mpirun: islands only
  if (on_ranks && job->rank() != 0) {            // rank 0 has the history and gives this rank its islands
    work_on_islands(*job, a.threads, a.lanes, !a.no_speculation);
    return 0;
  }
  // (a plain run resumed with --islands is refused by the service, as any contradicting option is)
  const SearchRun run = search_run_of(a, &cmd);
  const bool islands = run.resume > 0 ? resumes_islands(run) : run.islands > 1;
  if (on_ranks && !islands)
    throw std::runtime_error("optimize runs across MPI ranks only with --islands K (K > 1), or resuming islands");
  IslandsDrive ranks;  // rank 0's part of a job: the islands on every rank
  if (on_ranks)
    ranks.drive = [job](std::vector<Search>& searches, const IslandOptions& options, const DriveOptions& drive,
                        const IslandCallbacks& callbacks) {
      return drive_islands_on_ranks(*job, searches, options, drive, callbacks);
    };
  return run_search_run(run, a.out, host, on_ranks ? &ranks : nullptr);
}

}  // namespace softdrop::cli
