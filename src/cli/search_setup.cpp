// What one search and islands share (search_setup.hpp).
#include "cli/search_setup.hpp"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <stdexcept>

#include "cli/output.hpp"
#include "optimizer/strategy.hpp"
#include "softdrop/medium.hpp"
#include "softdrop/version.hpp"
#include "store/params_json.hpp"
#include "util/random.hpp"

namespace softdrop::cli {

OptimizeArgs::OptimizeArgs() {
  // The default search scene: the default 500 x 500 periodic box with 20 non-overlapping grains of
  // the default radii (phi ~ 0.72).
  medium.options.kind = MediumKind::non_overlapping;
  medium.options.grains = 20;
  // The measured best of the strategies (results/search/README.md): the evolution strategy with a
  // relocation every third generation and a generation of 8, enough candidates for every thread
  // and lane. The library's SearchOptions{} stays the paper's algorithm, and a stored run without
  // these keys reads as that.
  search.strategy.kind = StrategyKind::es;
  search.relocate_every = 3;
  search.lambda = 8;
  // The paper's objective, one droplet from the middle of the top, tunes that one chaotic path
  // (results/search/README.md): the default scores a medium by the mean T of droplets from fresh
  // starts, compared on common starts.
  search.objective.kind = ObjectiveKind::mean;
}

// The objective's options (search.hpp), each noted with the objectives that use it.
void add_objective_options(CLI::Option_group* g, OptimizeArgs& a) {
  g->add_option_function<std::string>(
       "--objective", [&a](const std::string& v) { a.search.objective.kind = parse_objective(v); },
       "What a candidate scores. single: T of one droplet from the middle of the top (the paper's; one path, "
       "chaotic in its start). mean: <T> of --starts droplets from fresh starts each generation, the "
       "candidates and their parent on the same starts. quantile: the --quantile of their T. lower-bound: "
       "<T> - --se-factor x its standard error. A droplet that does not pass counts as T = 1")
      ->check(CLI::IsMember(objective_names()))
      ->default_str(to_string(a.search.objective.kind));
  const auto of_objectives = [&a](const char* option, std::vector<ObjectiveKind> kinds) {
    return [&a, option, kinds](const std::string&) { a.objective_options.emplace_back(option, kinds); };
  };
  g->add_option("--starts", a.search.objective.starts,
                "mean, quantile, lower-bound: droplets per evaluation, in [1, 4096], stratified over the top and "
                "drawn afresh each generation")
      ->capture_default_str()
      ->each(of_objectives("--starts", {ObjectiveKind::mean, ObjectiveKind::quantile, ObjectiveKind::lower_bound}));
  g->add_option("--quantile", a.search.objective.quantile, "quantile: the quantile of the droplets' T, in (0, 1)")
      ->capture_default_str()
      ->each(of_objectives("--quantile", {ObjectiveKind::quantile}));
  g->add_option("--se-factor", a.search.objective.se_factor, "lower-bound: k in <T> - k x standard error")
      ->capture_default_str()
      ->each(of_objectives("--se-factor", {ObjectiveKind::lower_bound}));
  g->add_option("--margin", a.search.objective.margin,
                "mean, quantile, lower-bound: a candidate beats its parent only by more than this many standard "
                "errors of their droplets' paired differences (0: any gain)")
      ->capture_default_str()
      ->each(of_objectives("--margin", {ObjectiveKind::mean, ObjectiveKind::quantile, ObjectiveKind::lower_bound}));
}

void check_objective_options(const OptimizeArgs& a) {
  for (const auto& [option, kinds] : a.objective_options)
    if (std::find(kinds.begin(), kinds.end(), a.search.objective.kind) == kinds.end())
      throw std::invalid_argument(option.substr(2) + ": not an option of --objective " +
                                  to_string(a.search.objective.kind));
}

// The command line's view of the run: search options plus how the starting medium was made.
const char* island_starts_name(bool own) { return own ? "own" : "shared"; }

nlohmann::json params_of(const OptimizeArgs& a) {
  nlohmann::json j = nlohmann::json::parse(search_params_to_json(a.search));
  const MediumOptions& m = a.medium.options;
  j["medium"] = a.medium.file;
  j["grains"] = m.grains;
  j["width"] = m.width;
  j["height"] = m.height;
  j["r-min"] = m.r_min;
  j["r-max"] = m.r_max;
  j["radius-distribution"] = a.medium.radii;
  j["r-median"] = m.r_median;
  j["r-sigma"] = m.r_sigma;
  j["walls"] = a.medium.walls;
  j["medium-seed"] = m.seed;
  if (a.islands.islands > 1) {  // (plain runs keep the parameters they always had)
    j["islands"] = a.islands.islands;
    j["migrate-every"] = a.islands.migrate_every;
    j["migration"] = to_string(a.islands.migration);
    j["island-starts"] = island_starts_name(a.own_island_starts);
  } else if (a.own_island_starts) {
    j["island-starts"] =
        island_starts_name(true);  // (refused: for a new run here, on a resumed plain run as a contradiction)
  }
  return j;
}

// Options given on the command line (or in a config file) that differ from the stored run.
std::string contradictions(const nlohmann::json& given, const nlohmann::json& stored, const CLI::App& cmd,
                           const std::vector<std::string>& preset_keys) {
  std::string out;
  for (const auto& [key, value] : given.items()) {
    const CLI::Option* opt = cmd.get_option_no_throw("--" + key);
    const bool preset = std::find(preset_keys.begin(), preset_keys.end(), key) != preset_keys.end();
    if (!preset && (!opt || opt->count() == 0)) continue;
    const bool differs = !stored.contains(key) || stored.at(key) != value;
    if (differs)
      out += (out.empty() ? "" : ", ") + std::string("--") + key + " " + value.dump() + " (stored " +
             (stored.contains(key) ? stored.at(key).dump() : std::string("nothing")) + ")";
  }
  return out;
}

nlohmann::json validate_best(const OptimizeArgs& a, History& history, std::int64_t run, const Configuration& best) {
  if (a.validate_starts <= 0) return nullptr;
  HeldOutOptions o;
  o.starts = a.validate_starts;
  o.threads = a.threads;
  Progress progress("optimize: held-out droplets");
  RunOptions runs = a.search.run;
  runs.path_interval = 0;
  const HeldOutValue v = held_out_value(a.search.droplet, best.medium, runs, o, [&](int done, int total) {
    if (!a.quiet) progress.update(done, total);
  });
  const ValidationRecord r = validation_record(best.generation, o, v);
  history.add_validation(run, r);
  // A robust objective over the held-out starts: the counterpart of the best's in-search value.
  const nlohmann::json objective = a.search.objective.robust()
                                       ? nlohmann::json(objective_value(a.search.objective, v.at_dt.runs))
                                       : nlohmann::json();
  return {{"objective_value", objective},
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

// Generation 0 of a new run: the loaded medium, or random media until the droplet passes. A medium
// that cannot be generated at all (e.g. too many grains for the box) is an error, not a retry.
Generation start(const OptimizeArgs& a, Configuration* best) {
  if (!a.medium.file.empty()) {
    if (is_image_file(a.medium.file))
      throw std::invalid_argument("medium: " + a.medium.file +
                                  " is an image; a search moves grains, so it starts from a grain file (.json, .csv)");
    return initial_generation(load_medium(a.medium.file), a.search, best);
  }
  std::string last_reason;
  for (int attempt = 0; attempt < a.start_attempts; ++attempt) {
    MediumOptions m = a.medium.options;
    if (attempt > 0) m.seed = derive_seed(a.medium.options.seed, static_cast<std::uint64_t>(attempt));
    const Medium medium = generate_medium(m);
    try {
      return initial_generation(medium, a.search, best);
    } catch (const std::runtime_error& e) {  // the droplet did not pass: try another medium
      last_reason = e.what();
      if (!a.quiet)
        std::cerr << "optimize: starting medium " << attempt + 1 << ": " << last_reason << "; trying another\n";
    }
  }
  throw std::runtime_error("start-attempts = " + std::to_string(a.start_attempts) +
                           ": no starting medium let the droplet pass (" + last_reason + ")");
}

DriveOptions drive_options_of(const OptimizeArgs& a, const std::atomic<bool>* stop) {
  DriveOptions d;
  d.generations = a.generations;
  d.time_limit = a.time_limit;
  d.stop = stop;
  d.threads = a.threads;
  d.speculate = !a.no_speculation;
  d.lanes = a.lanes;
  return d;
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

bool deliver_summary(const OptimizeArgs& a, const nlohmann::json& j, Host* host) {
  if (!a.json_file.empty()) write_file_atomically(a.json_file, j.dump(2) + "\n");
  if (host) {
    host->summary = j;
    return true;
  }
  if (a.format != "json") return false;
  std::cout << j.dump(2) << '\n';
  return true;
}

Search resumed_search(History& history, const RunRecord& rec, const SearchOptions& options) {
  // The strategy moves on from the last kept arrangement; the best may be an earlier one (with a
  // robust objective it is that arrangement, with the mean of its re-runs stored as the run's best).
  Configuration current = history.configuration(rec.id, -1);
  const bool robust = options.objective.robust();
  // Both must come out the same with this build (on the starts they were kept on), or the history
  // would fork. The best is checked apart only when it is another arrangement.
  const auto check = [&](Configuration& c) {
    const Evaluation again = evaluate(c.medium, options, c.generation);
    if (again.outcome != Outcome::passed || again.tortuosity != c.eval.tortuosity || again.touched != c.eval.touched)
      throw std::runtime_error("resume " + std::to_string(rec.id) + ": this build gives T = " + fmt(again.tortuosity) +
                               " for the stored arrangement of generation " + std::to_string(c.generation) +
                               ", the run stored " + fmt(c.eval.tortuosity) +
                               " (built with other numerics? resuming would not continue the same history)");
    c.eval = again;
  };
  check(current);
  Configuration best = current;
  if (!robust && rec.best_generation != current.generation) {
    best = history.configuration(rec.id, rec.best_generation);
    check(best);
  }
  if (robust) {
    if (rec.best_generation != current.generation)
      throw std::runtime_error("resume " + std::to_string(rec.id) + ": the stored best (generation " +
                               std::to_string(rec.best_generation) + ") is not the last kept arrangement (generation " +
                               std::to_string(current.generation) + "), as the " + to_string(options.objective.kind) +
                               " objective keeps it");
    best.eval.tortuosity = rec.best_t;
  }
  return Search(options, std::move(best), std::move(current),
                resumes_by_replay(options.strategy.kind) ? history.strategy_states(rec.id, rec.generations)
                                                         : history.strategy_state(rec.id, rec.generations),
                rec.generations);
}

}  // namespace softdrop::cli
