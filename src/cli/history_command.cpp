#include "cli/history_command.hpp"

#include <cmath>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "cli/common_options.hpp"
#include "cli/kept_arrangement.hpp"
#include "cli/output.hpp"
#include "softdrop/medium.hpp"
#include "softdrop/store.hpp"
#include "store/params_json.hpp"

namespace softdrop::cli {

CLI::App* add_history_command(CLI::App& app, HistoryArgs& a) {
  CLI::App* s = app.add_subcommand("history", "List the runs of a search database, or one run's generations");
  s->fallthrough();
  s->add_option("--db", a.db, "SQLite history file")->capture_default_str();
  s->add_option("--run", a.run, "List this run's generations instead of the runs")->check(id_check());
  auto* best =
      s->add_flag("--best", a.best, "With --run: only the generations that raised the best T (the best-T curve)");
  auto* candidates = s->add_flag("--candidates", a.candidates, "With --run: one row per candidate of every generation");
  auto* params =
      s->add_flag("--params", a.params,
                  "With --run: the options the run was started with (long option names) and its target generation");
  best->excludes(candidates)->excludes(params);
  candidates->excludes(params);
  s->add_option("--format", a.format, "table, csv or json")
      ->capture_default_str()
      ->check(CLI::IsMember({"table", "csv", "json"}));
  s->footer(
      "Columns (softdrop columns lists every name, with its unit). Runs: island = this run's island and "
      "archipelago = the run id of its islands' first run (optimize --islands; empty otherwise); evaluations = "
      "candidates evaluated so far (generation 0's included); droplets = droplet runs so far (evaluations x "
      "--starts, and the parents' re-runs); objective = what a candidate scores (optimize --objective); "
      "best_generation = where the best was found; held_out_tortuosity, held_out_standard_error, held_out_starts = "
      "the best's held-out value (as --best gives it). With a robust objective (mean, quantile, lower-bound) every "
      "tortuosity below is the objective's value over the evaluation's droplets, and the best is the arrangement "
      "the search stands on, its best_tortuosity the mean of its re-runs on fresh starts. Generations: kind = the "
      "move that made its candidates: all (every grain jumps), single (one touched grain), relocate (one "
      "untouched grain put next to the path), migrate (another island's best, accepted if it beat this "
      "island's), or mixed (es draws each candidate's move: see --candidates); accepted = 1 if the strategy kept "
      "a candidate; best_candidate_tortuosity = the best among the generation's passing candidates (empty if "
      "none passed); outcomes = each candidate's outcome, in order; best_tortuosity = the best after it; touched "
      "= grains the best arrangement's droplet touched; seconds = wall time; state = the strategy's state (JSON); "
      "parent_tortuosity = the value of the arrangement the candidates were made from, re-run on their starts "
      "(robust objectives). Candidates: kind = its move (as above; empty where an older file "
      "cannot tell single from relocate); moved_grain = the grain a single or relocate move moved; "
      "moved = grains moved; tortuosity = its value if passed; steps = time steps simulated; reason = why its "
      "run ended; droplets, passed = its droplets and how many passed. --best: held_out_tortuosity, "
      "held_out_standard_error = the mean T and its standard error over held_out_starts random starts of that "
      "generation's arrangement (softdrop validate, or the end of the search; empty where none was computed); "
      "re_runs = robust objectives: the re-runs on fresh starts that its best_tortuosity is the mean of (0: the "
      "value it was kept with). --params: the options with their types in --format json.");
  return s;
}

CLI::App* add_export_command(CLI::App& app, ExportArgs& a) {
  CLI::App* s = app.add_subcommand("export", "Write a stored configuration as a grain file for `simulate`");
  s->fallthrough();
  s->add_option("--db", a.db, "SQLite history file")->capture_default_str();
  s->add_option("--run", a.run, "Run id")->required()->check(id_check());
  s->add_option("--generation", a.generation, "The arrangement kept as of this generation (default: the run's best)")
      ->check(index_check());
  s->add_option("--output,-o", a.output, "Grain file to write (.json, otherwise CSV)")->required();
  s->add_option("--simulate-config", a.simulate_config,
                "Also write a TOML config: `softdrop simulate --config FILE` reproduces the stored T");
  return s;
}

namespace {

nlohmann::json or_null(bool present, double v) { return present ? nlohmann::json(v) : nlohmann::json(); }

// A strategy's stored state as JSON (an object in --format json, its text in CSV); null where the
// generation has none (generation 0, and the strategies that keep no state).
nlohmann::json state_json(const std::string& state) {
  if (state.empty()) return nlohmann::json();
  nlohmann::json j = nlohmann::json::parse(state, nullptr, false);
  return j.is_discarded() ? nlohmann::json(state) : j;
}

}  // namespace

void check_stored_generation(std::int64_t generation, const RunRecord& run) {
  if (generation > run.generations)
    throw std::invalid_argument("generation = " + std::to_string(generation) + ": run " + std::to_string(run.id) +
                                " has stored generations 0 to " + std::to_string(run.generations));
}

int run_history(const HistoryArgs& a) {
  if (a.best && a.run == 0) throw std::invalid_argument("best: --best needs --run");
  if (a.candidates && a.run == 0) throw std::invalid_argument("candidates: --candidates needs --run");
  if (a.params && a.run == 0) throw std::invalid_argument("params: --params needs --run");
  auto history = open_history(a.db, OpenMode::read_only);
  Table t;
  if (a.run == 0) {
    t.header = {"run",
                "created",
                "status",
                "strategy",
                "island",
                "archipelago",
                "grains",
                "generations",
                "evaluations",
                "best_tortuosity",
                "best_generation",
                "held_out_tortuosity",
                "held_out_standard_error",
                "held_out_starts",
                "lambda",
                "seed",
                "version",
                "objective",
                "droplets"};
    for (const RunRecord& r : history->runs()) {
      const auto params = nlohmann::json::parse(r.params, nullptr, false);
      const std::string strategy = params.is_object() ? params.value("strategy", "paper") : "?";
      const std::string objective = params.is_object() ? params.value("objective", "single") : "?";
      const std::optional<ValidationRecord> v = held_out_of(history->validations(r.id), r.best_generation);
      t.rows.push_back(
          {r.id, r.created, r.status, strategy, r.island >= 0 ? nlohmann::json(r.island) : nlohmann::json(),
           r.island >= 0 ? nlohmann::json(r.archipelago) : nlohmann::json(), r.grains, r.generations, r.evaluations,
           r.best_t, r.best_generation, v ? finite_or_null(v->mean_t) : nlohmann::json(),
           v ? finite_or_null(v->standard_error) : nlohmann::json(), v ? nlohmann::json(v->starts) : nlohmann::json(),
           r.lambda, r.seed, r.version, objective, r.droplets});
    }
  } else if (a.params) {
    t.header = {"option", "value"};
    const auto params = nlohmann::json::parse(history->run(a.run).params, nullptr, false);
    if (!params.is_object())
      throw std::runtime_error("--db '" + a.db + "': run " + std::to_string(a.run) + " has no readable options");
    for (const auto& [key, value] : params.items())
      t.rows.push_back({key, value});  // typed in JSON; CSV and the table write it as text
  } else if (a.candidates) {
    t.header = {"generation", "candidate",   "kind",  "accepted", "outcome", "tortuosity", "steps",
                "touched",    "moved_grain", "moved", "seconds",  "reason",  "droplets",   "passed"};
    for (const GenerationRecord& g : history->generations(a.run))
      for (const CandidateRecord& c : g.candidates)
        t.rows.push_back({g.generation, c.index, c.kind.empty() ? nlohmann::json() : nlohmann::json(c.kind),
                          c.index == g.accepted ? 1 : 0, c.outcome, or_null(c.outcome == "passed", c.tortuosity),
                          c.steps, c.touched,
                          c.moved_grain >= 0 ? nlohmann::json(c.moved_grain) : nlohmann::json(nullptr), c.moved,
                          c.seconds, c.reason, c.droplets, c.passed});
  } else if (a.best) {
    // Beside the in-search best T, the held-out value of that generation's arrangement where one
    // was stored (held_out_of's choice of its validations). A robust objective's best is the arrangement
    // the search stands on: one row for each arrangement kept, with its value where its tenure
    // ended (the mean of its re-runs on fresh starts) and how many re-runs that mean holds.
    t.header = {
        "generation",      "kind",   "best_tortuosity", "touched", "held_out_tortuosity", "held_out_standard_error",
        "held_out_starts", "re_runs"};
    const BestCurve curve = best_rows(*history, a.run);
    for (const BestRow& b : curve.rows) {
      const std::optional<ValidationRecord>& v = b.held_out;
      t.rows.push_back(
          {b.point.generation, b.kind, b.point.value, b.touched, v ? finite_or_null(v->mean_t) : nlohmann::json(),
           v ? finite_or_null(v->standard_error) : nlohmann::json(), v ? nlohmann::json(v->starts) : nlohmann::json(),
           curve.robust ? nlohmann::json(b.point.re_runs) : nlohmann::json()});
    }
  } else {
    t.header = {"generation", "kind",    "accepted", "best_candidate_tortuosity", "outcomes", "best_tortuosity",
                "touched",    "seconds", "state",    "parent_tortuosity"};
    for (const GenerationRecord& g : history->generations(a.run)) {
      // The generation's best passing candidate, and every candidate's outcome.
      bool any = false;
      double top = 0;
      std::string outcomes;
      for (const CandidateRecord& c : g.candidates) {
        if (c.outcome == "passed" && (!any || c.tortuosity > top)) top = c.tortuosity, any = true;
        outcomes += (outcomes.empty() ? "" : ";") + c.outcome;
      }
      t.rows.push_back({g.generation, g.kind, g.accepted >= 0 ? 1 : 0, or_null(any, top), outcomes, g.best_t, g.touched,
                        g.seconds, state_json(g.state), finite_or_null(g.parent_t)});
    }
  }
  t.print(std::cout, a.format);
  return 0;
}

int run_export(const ExportArgs& a) {
  check_output_path("--output", a.output);
  if (!a.simulate_config.empty()) check_output_path("--simulate-config", a.simulate_config);
  auto history = open_history(a.db, OpenMode::read_only);
  const RunRecord run = history->run(a.run);
  check_stored_generation(a.generation, run);
  const Configuration c = history->configuration(a.run, a.generation < 0 ? run.best_generation : a.generation);
  const ArrangementValues values = arrangement_values(*history, a.run, c);
  // Both files are made in memory first, so a stored run the config cannot be made of leaves
  // neither behind.
  std::string config, replays;
  if (!a.simulate_config.empty()) {
    // The droplet and exit options of the run, so that simulate pushes the same droplet: numbers in
    // JSON notation, which TOML reads back to the same doubles. The single objective's value is one
    // droplet's from x0 = W/2, and the config replays it. A robust objective's value belongs to
    // the medium, not to a start: the config pushes the droplets of its held-out value (the
    // default starts of softdrop validate if none is stored), whose <T> simulate then gives.
    try {
      search_params_from_json(run.params);  // names a required key the stored run lacks
    } catch (const std::exception& e) {
      throw std::runtime_error("--db '" + a.db + "': run " + std::to_string(a.run) + ": " + e.what());
    }
    const nlohmann::json params = nlohmann::json::parse(run.params);
    std::ostringstream toml;
    toml << "# softdrop simulate --config " << a.simulate_config << "  (run " << a.run << ", generation "
         << c.generation << ", T = " << fmt(values.in_search) << " in the search: " << in_search_basis(values) << ")\n";
    toml << "medium = " << nlohmann::json(a.output).dump() << "\n";
    if (values.robust()) {
      const HeldOutOptions defaults;
      const int starts = values.held_out ? values.held_out->starts : defaults.starts;
      const std::uint64_t seed = values.held_out ? values.held_out->seed : defaults.seed;
      replays = "the " + std::to_string(starts) + " random starts (seed " + std::to_string(seed) + ") of " +
                (values.held_out ? "its held-out value" : std::string("softdrop validate's held-out value"));
      toml << "# " << replays << " (simulate gives their <T>"
           << (values.held_out ? "; stored: " + held_out_text(*values.held_out) : std::string()) << ")\n";
      toml << "droplets = " << starts << "\nseed = " << seed << "\n";
    } else {
      replays = "its droplet from x0 = W/2";
      toml << "x0 = " << nlohmann::json(0.5 * c.medium.width).dump() << "\n";
    }
    for (const std::string& key : simulation_param_keys())
      if (params.contains(key)) toml << key << " = " << params.at(key).dump() << "\n";  // older runs lack newer keys
    config = toml.str();
  }
  save_medium(a.output, c.medium);
  if (!config.empty()) write_file_atomically(a.simulate_config, config);
  std::cerr << "export: run " << a.run << ", configuration of generation " << c.generation << " ("
            << c.medium.grains.size() << " grains) written to " << a.output << "\n";
  std::cerr << "export: in the search T = " << fmt(values.in_search, 6) << " (" << in_search_basis(values) << ")\n";
  if (values.held_out) std::cerr << "export: held out, " << held_out_text(*values.held_out) << " (softdrop validate)\n";
  if (!config.empty()) std::cerr << "export: " << a.simulate_config << " replays " << replays << "\n";
  return 0;
}

}  // namespace softdrop::cli
