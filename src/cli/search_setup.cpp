// What one search and islands share (search_setup.hpp).
#include "cli/search_setup.hpp"

#include <cmath>
#include <iostream>
#include <stdexcept>

#include "cli/output.hpp"
#include "softdrop/medium.hpp"
#include "softdrop/version.hpp"
#include "store/params_json.hpp"

namespace softdrop::cli {

OptimizeArgs::OptimizeArgs() {
  const SearchRun d = default_search_run();
  search = d.search;
  medium.options = d.start.medium;
  start_attempts = d.start.attempts;
  generations = SearchRun::kDefaultGenerations;
  validate_starts = d.validate_starts;
  islands.islands = d.islands;
  islands.migrate_every = d.migrate_every;
}

// The objective's options (search.hpp).
void add_objective_options(CLI::Option_group* g, OptimizeArgs& a) {
  g->add_option_function<std::string>(
       "--objective", [&a](const std::string& v) { a.search.objective.kind = parse_objective(v); },
       "What a candidate scores. single: T of one droplet from the middle of the top (the paper's; one path, "
       "chaotic in its start). mean: <T> of --starts droplets from fresh starts each generation, the "
       "candidates and their parent on the same starts. quantile: the --quantile of their T. lower-bound: "
       "<T> - --se-factor x its standard error. A droplet that does not pass counts as T = 1")
      ->check(CLI::IsMember(objective_names()))
      ->default_str(to_string(a.search.objective.kind));
  g->add_option("--starts", a.search.objective.starts,
                "mean, quantile, lower-bound: droplets per evaluation, in [1, 4096], stratified over the top and "
                "drawn afresh each generation")
      ->capture_default_str();
  g->add_option("--quantile", a.search.objective.quantile, "quantile: the quantile of the droplets' T, in (0, 1)")
      ->capture_default_str();
  g->add_option("--se-factor", a.search.objective.se_factor, "lower-bound: k in <T> - k x standard error")
      ->capture_default_str();
  g->add_option("--margin", a.search.objective.margin,
                "mean, quantile, lower-bound: a candidate beats its parent only by more than this many standard "
                "errors of their droplets' paired differences (0: any gain)")
      ->capture_default_str();
}

SearchStart start_of(const OptimizeArgs& a) {
  SearchStart start;
  start.file = a.medium.file;
  start.medium = a.medium.options;
  start.medium.kind = parse_medium_kind(a.medium.kind);
  start.medium.radii = parse_radius_distribution(a.medium.radii);
  start.medium.periodic = !a.medium.walls;
  start.attempts = a.start_attempts;
  return start;
}

SearchRun search_run_of(const OptimizeArgs& a, const CLI::App* cmd) {
  SearchRun run;
  run.search = a.search;
  run.search.gap = a.medium.options.gap;  // one spacing rule: the generator's and the moves' (--gap)
  run.start = start_of(a);
  run.db = a.out.db;
  run.resume = a.resume;
  // A resume without --generations goes on to the run's own target.
  if (a.resume == 0 || (cmd && cmd->get_option("--generations")->count() > 0)) run.generations = a.generations;
  run.time_limit = a.time_limit;
  run.threads = a.threads;
  run.lanes = a.lanes;
  run.speculate = !a.no_speculation;
  run.validate_starts = a.validate_starts;
  run.islands = a.islands.islands;
  run.migrate_every = a.islands.migrate_every;
  run.migration = to_string(a.islands.migration);
  run.own_island_starts = a.own_island_starts;
  run.given = a.given;
  return run;
}

ProgramSearchObserver::ProgramSearchObserver(const SearchOutput& out, Host* host, const char* interrupt)
    : out_(out), host_(host) {
  if (!host) signals_.emplace(interrupt);
}

void ProgramSearchObserver::start_refused(int attempt, const std::string& why) {
  if (!out_.quiet) std::cerr << "optimize: starting medium " << attempt << ": " << why << "; trying another\n";
}

void ProgramSearchObserver::validating(int done, int total) {
  if (out_.quiet) return;
  if (!validation_) validation_.emplace("optimize: held-out droplets");  // its clock starts here
  validation_->update(done, total);
}

nlohmann::json held_out_json(const ValidationRecord& r, double objective) {
  return {{"objective_value", finite_or_null(objective)},
          {"generation", r.generation},
          {"starts", r.starts},
          {"seed", r.seed},
          {"passed", r.passed},
          {"mean_tortuosity", finite_or_null(r.mean_t)},
          {"standard_error", finite_or_null(r.standard_error)},
          {"half_dt_mean_tortuosity", finite_or_null(r.half_dt_mean_t)},
          {"half_dt_standard_error", finite_or_null(r.half_dt_standard_error)},
          {"dt_shift", finite_or_null(r.dt_shift)},
          {"dt_shift_error", finite_or_null(r.dt_shift_error)}};
}

void print_held_out(std::ostream& out, const nlohmann::json& held_out) {
  if (!held_out.is_object()) return;
  if (!held_out["mean_tortuosity"].is_number()) {
    out << "held-out T   none of " << held_out["starts"] << " random starts passed\n";
    return;
  }
  out << "held-out T   " << fmt(held_out["mean_tortuosity"].get<double>(), 6)
      << (held_out["standard_error"].is_number() ? " +- " + fmt(held_out["standard_error"].get<double>(), 2) : "")
      << " over " << held_out["starts"] << " random starts (" << held_out["passed"] << " passed)"
      << (held_out["half_dt_mean_tortuosity"].is_number()
              ? "; at dt/2 " + fmt(held_out["half_dt_mean_tortuosity"].get<double>(), 6)
              : "")
      << " (softdrop validate)\n";
  if (held_out["objective_value"].is_number())
    out << "held-out obj " << fmt(held_out["objective_value"].get<double>(), 6)
        << " (the objective over those starts, a droplet that did not pass as T = 1; beside the best T)\n";
}

nlohmann::json generation_event(std::int64_t run, const Generation& g, const Configuration& best, std::int64_t target) {
  return {{"run", run},
          {"generation", g.number},
          {"kind", to_string(g.kind)},
          {"accepted_candidate", g.accepted >= 0 ? nlohmann::json(g.accepted) : nlohmann::json()},
          {"candidates", g.candidates.size()},
          {"seconds", g.seconds},
          {"best_tortuosity", best.eval.tortuosity},
          {"best_generation", best.generation},
          {"target_generations", target}};
}

bool deliver_summary(const SearchOutput& out, const nlohmann::json& j, Host* host) {
  if (!out.json_file.empty()) write_file_atomically(out.json_file, j.dump(2) + "\n");
  if (host) {
    host->summary = j;
    return true;
  }
  if (out.format != "json") return false;
  std::cout << j.dump(2) << '\n';
  return true;
}

}  // namespace softdrop::cli
