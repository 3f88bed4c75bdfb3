#include "cli/validate_command.hpp"

#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "cli/kept_arrangement.hpp"
#include "cli/output.hpp"
#include "cli/simulate_output.hpp"
#include "softdrop/medium.hpp"
#include "softdrop/store.hpp"
#include "softdrop/version.hpp"
#include "store/params_json.hpp"

namespace softdrop::cli {

CLI::App* add_validate_command(CLI::App& app, ValidateArgs& a) {
  CLI::App* s = app.add_subcommand(
      "validate", "The held-out tortuosity of a medium: <T> over droplets from many random starts, at dt and at dt/2");
  s->fallthrough();
  auto* what = s->add_option_group("Source", "a grain file, or a search's stored arrangement");
  what->add_option("--medium", a.medium, "Grain file to validate (.json or .csv), with the droplet options below");
  what->add_option("--db", a.db,
                   "Or a search history: the run's arrangement with the run's own droplet (the value is stored "
                   "in the history)");
  what->add_option("--run", a.run, "With --db: the run")->check(id_check());
  what->add_option("--generation", a.generation,
                   "With --db: the arrangement kept as of this generation (default: the best)")
      ->check(index_check());
  auto* g = s->add_option_group("Held out");
  g->add_option("--starts", a.held_out.starts, "Droplets, each from a random start across the top")
      ->capture_default_str();
  g->add_option("--seed", a.held_out.seed, "Seed of the starts (the same starts at both time steps)")
      ->capture_default_str()
      ->check(seed_check());
  g->add_flag("--same-dt-only", a.same_dt_only, "Do not run the starts again at dt/2");
  g->add_option("--threads", a.held_out.threads, "Worker threads (0 = all cores); results do not depend on it")
      ->capture_default_str();
  auto* d = add_droplet_options(s, a.droplet);
  add_exit_options(d, a.run_options);
  auto* o = add_summary_options(s, a.format, a.json_file, a.quiet);
  o->add_option("--runs", a.runs_csv,
                "CSV, one row a droplet and time step: start, start_x, dt, outcome, tortuosity, steps");
  return s;
}

void check_validate(ValidateArgs& a, const CLI::App& cmd) {
  if (a.medium.empty() == a.db.empty())
    throw std::invalid_argument("validate: give --medium FILE or --db FILE --run N");
  if (!a.db.empty() && a.run == 0) throw std::invalid_argument("run: --db needs --run");
  if (a.db.empty() && (a.run != 0 || a.generation >= 0))
    throw std::invalid_argument(std::string(a.run != 0 ? "run" : "generation") + ": an option of --db");
  if (!a.db.empty())  // the run's droplet is stored with it
    for (const CLI::App* group : cmd.get_subcommands([](const CLI::App* s) { return s->get_group() == "Droplet"; }))
      for (const CLI::Option* o : group->get_options())
        if (o->count() > 0)
          throw std::invalid_argument(o->get_name().substr(2) + ": the run's droplet is stored with it; leave " +
                                      o->get_name() + " out with --db");
  a.held_out.half_dt = !a.same_dt_only;
  std::string why;
  if (!a.held_out.IsValid(&why)) throw std::invalid_argument(why);
  if (!a.droplet.IsValid(&why)) throw std::invalid_argument(why);
  if (!a.run_options.IsValid(&why)) throw std::invalid_argument(why);
  for (const auto& [option, path] : {std::pair{"--json", a.json_file}, {"--runs", a.runs_csv}})
    if (!path.empty()) check_output_path(option, path);
}

namespace {

nlohmann::json runs_json(const HeldOutRuns& r) {
  return {{"dt", r.dt},
          {"starts", r.starts},
          {"passed", r.passed},
          {"stuck", r.stuck},
          {"timeout", r.timeout},
          {"diverged", r.diverged},
          {"pass_fraction", r.pass_fraction},
          {"mean_tortuosity", finite_or_null(r.mean_t)},
          {"standard_error", finite_or_null(r.standard_error)},
          {"q1", finite_or_null(r.q1)},
          {"median", finite_or_null(r.median)},
          {"q3", finite_or_null(r.q3)}};
}

std::string runs_line(const char* label, const HeldOutRuns& r) {
  std::ostringstream line;
  line << label << fmt(r.dt, 6) << ": ";
  if (r.passed == 0) {
    line << "no droplet passed";
  } else {
    line << "<T> = " << fmt(r.mean_t, 6);
    if (r.passed > 1) line << " +- " << fmt(r.standard_error, 2);
    line << ", quartiles " << fmt(r.q1, 4) << " / " << fmt(r.median, 4) << " / " << fmt(r.q3, 4);
  }
  line << "; " << r.passed << " of " << r.starts << " passed (" << fmt(100 * r.pass_fraction, 3) << " %)";
  if (r.timeout + r.diverged > 0) line << ", " << r.timeout << " timeout, " << r.diverged << " diverged";
  return line.str();
}

}  // namespace

int run_validate(ValidateArgs& a, const CLI::App& cmd) {
  check_validate(a, cmd);
  Medium medium;
  nlohmann::json source;
  std::string in_search;       // the run's own value, beside the held-out one
  ObjectiveOptions objective;  // the run's (with --db): its value over the held-out starts too
  if (!a.db.empty()) {
    auto history = open_history(a.db, OpenMode::read_only);
    const RunRecord run = history->run(a.run);
    const Configuration c = history->configuration(a.run, a.generation < 0 ? run.best_generation : a.generation);
    SearchOptions stored;
    try {
      stored = search_params_from_json(run.params);
    } catch (const std::exception& e) {
      throw std::runtime_error("--db '" + a.db + "': run " + std::to_string(a.run) + ": " + e.what());
    }
    a.droplet = stored.droplet;
    a.run_options = stored.run;
    a.run_options.path_interval = 0;
    medium = c.medium;
    objective = stored.objective;
    source = {{"db", a.db}, {"run", a.run}, {"generation", c.generation}, {"objective", to_string(objective.kind)}};
    // Its value in the search (for a robust objective the mean of its re-runs on fresh starts).
    const ArrangementValues values = arrangement_values(*history, a.run, c);
    source["in_search_tortuosity"] = values.in_search;
    if (values.robust()) source["re_runs"] = values.re_runs;
    in_search = std::string(values.robust() ? "in-search    " : "in-search T  ") + fmt(values.in_search, 6) + " (" +
                in_search_basis(values) + ", generation " + std::to_string(c.generation) + ")\n";
  } else {
    medium = load_medium(a.medium);
    source = {{"medium", a.medium}};
  }
  Progress progress("validate: droplets");
  const HeldOutValue v = held_out_value(a.droplet, medium, a.run_options, a.held_out, [&](int done, int total) {
    if (!a.quiet) progress.update(done, total);
  });

  nlohmann::json j{{"version", kVersion},
                   {"source", source},
                   {"seed", a.held_out.seed},
                   {"grains", medium.grains.size()},
                   {"porosity", exact_porosity(medium)},
                   {"at_dt", runs_json(v.at_dt)}};
  // The run's robust objective over the held-out starts: the in-search value's counterpart.
  const double held_out_objective = objective.robust() ? objective_value(objective, v.at_dt.runs) : 0.0;
  if (objective.robust()) j["at_dt"]["objective_value"] = held_out_objective;
  if (a.held_out.half_dt)
    j["at_half_dt"] = runs_json(v.at_half_dt), j["dt_shift"] = {{"paired", v.paired},
                                                                {"mean", finite_or_null(v.dt_shift)},
                                                                {"standard_error", finite_or_null(v.dt_shift_error)}};
  if (!a.db.empty()) {  // stored beside the run, for history --best, export and read_history
    auto history = open_history(a.db, OpenMode::create);
    history->add_validation(a.run, validation_record(source["generation"].get<std::int64_t>(), a.held_out, v));
  }
  if (!a.json_file.empty()) write_file_atomically(a.json_file, j.dump(2) + "\n");
  if (!a.runs_csv.empty()) {
    std::ostringstream out;
    out << "start,start_x,dt,outcome,tortuosity,steps\n";
    for (const HeldOutRuns* r : {&v.at_dt, &v.at_half_dt})
      for (std::size_t i = 0; i < r->runs.size(); ++i) {
        const RunSummary& s = r->runs[i];
        out << i << ',' << fmt(s.start_x) << ',' << fmt(r->dt) << ',' << to_string(s.outcome) << ','
            << (s.outcome == Outcome::passed ? fmt(s.tortuosity) : "") << ',' << s.steps << '\n';
      }
    write_file_atomically(a.runs_csv, out.str());
  }
  if (a.format == "json") {
    std::cout << j.dump(2) << '\n';
    return 0;
  }
  std::cout << medium_line(medium, exact_porosity(medium)) << in_search << "starts       " << a.held_out.starts
            << " across the top (seed " << a.held_out.seed << ")\n"
            << runs_line("at dt        ", v.at_dt) << "\n";
  if (objective.robust())
    std::cout << "objective    " << fmt(held_out_objective, 6) << " over these starts (" << to_string(objective.kind)
              << ", a droplet that did not pass counted as T = 1): the in-search value's counterpart\n";
  if (a.held_out.half_dt) {
    std::cout << runs_line("at dt/2      ", v.at_half_dt) << "\n";
    std::cout << "dt/2 - dt     ";
    if (v.paired == 0)
      std::cout << "no start passed at both\n";
    else
      std::cout << (v.dt_shift >= 0 ? "+" : "") << fmt(v.dt_shift, 3)
                << (v.paired > 1 ? " +- " + fmt(v.dt_shift_error, 2) : std::string()) << " in T over the " << v.paired
                << " starts that passed at both\n";
  }
  return 0;
}

}  // namespace softdrop::cli
