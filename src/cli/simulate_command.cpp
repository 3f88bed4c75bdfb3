#include "cli/simulate_command.hpp"

#include <chrono>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "cli/columns.hpp"
#include "cli/output.hpp"
#include "cli/simulate_output.hpp"
#include "softdrop/medium.hpp"
#include "softdrop/version.hpp"
#include "studies/area_trace.hpp"

namespace softdrop::cli {

CLI::App* add_simulate_command(CLI::App& app, SimulateArgs& a) {
  CLI::App* s =
      app.add_subcommand("simulate", "Push one droplet (or --droplets K) through a generated or loaded medium");
  s->fallthrough();  // lets `simulate --config FILE` reach the program-level --config

  auto* g = add_medium_options(s, a.medium, false);
  g->add_option("--save-medium", a.save_medium_file, "Write the medium used to this grain file");
  add_droplet_options(s, a.droplet);

  auto* r = s->add_option_group("Run", "exit conditions and droplets");
  add_exit_options(r, a.run);
  r->add_option("--droplets", a.batch.droplets, "K droplets from random starts, run in parallel")
      ->capture_default_str();
  r->add_option("--x0", a.x0, "Start x of the droplet centre (default: random from --seed)")->check(finite_check());
  r->add_option("--seed", a.batch.seed, "Seed of the random start positions")
      ->capture_default_str()
      ->check(seed_check());
  r->add_option("--threads", a.batch.threads, "Worker threads (0 = all cores)")->capture_default_str();

  add_second_droplet_options(s, a.second);

  auto* w = s->add_option_group("Sweep droplet", "one droplet of a stored sweep, run again as the sweep ran it");
  w->add_option("--from-sweep", a.from_sweep,
                "A sweep's SQLite store: run one of its droplets again (--sweep-droplet), in the sweep's medium "
                "with its droplet and exit options, from the droplet's start; outputs as for any run");
  w->add_option("--sweep-droplet", a.sweep_droplet,
                "P:M:D, the droplet's porosity_index, medium_index and droplet (the store's sweep_droplets_view)");
  w->add_option("--sweep-id", a.sweep_id, "The sweep (default: the only one in the file)")->check(id_check());

  auto* o = add_summary_options(s, a.format, a.json_file, a.quiet);
  o->add_option("--runs", a.runs_csv, "CSV, one row per droplet: start, outcome, T, steps, touched");
  o->add_option("--paths", a.paths_csv, "CSV of centre-of-mass paths (droplet,time,x,y)");
  o->add_option("--path-interval", a.run.path_interval, "Steps between path samples (default 100 with --paths)");
  o->add_option("--trace", a.trace_csv,
                "CSV of the ring area S(t), each droplet replayed to its exit (droplet,time,area,area_ratio,phase; "
                "as render trace --csv)");
  o->add_option("--trace-interval", a.run.area_interval, "Steps between area samples (default 100 with --trace)")
      ->check(positive_check());
  o->add_option("--snapshots", a.snapshots_csv, "CSV of ring boundaries at --snapshot-times (droplet,time,mass,x,y)");
  o->add_option("--snapshot-times", a.run.snapshot_times, "Times (time units) of boundary snapshots")->delimiter(',');
  return s;
}

void check_simulate(SimulateArgs& a) {
  std::string why;
  if (!a.droplet.IsValid(&why)) throw std::invalid_argument(why);
  if (a.batch.droplets < 1 || a.batch.droplets > 10'000'000)
    throw std::invalid_argument("droplets = " + std::to_string(a.batch.droplets) + ": must be in [1, 1e7]");
  check_threads(a.batch.threads);
  if (!a.paths_csv.empty() && a.run.path_interval == 0) a.run.path_interval = 100;
  if (!a.trace_csv.empty() && a.run.area_interval == 0) a.run.area_interval = 100;
  if (!a.snapshots_csv.empty() && a.run.snapshot_times.empty())
    throw std::invalid_argument("snapshots: --snapshot-times is required with --snapshots");
  if (a.snapshots_csv.empty() && !a.run.snapshot_times.empty())
    throw std::invalid_argument("snapshot-times: has no effect without --snapshots FILE");
  if (a.trace_csv.empty() && a.run.area_interval > 0)
    throw std::invalid_argument("trace-interval: has no effect without --trace FILE");
  check_snapshot_times(a.run.snapshot_times, a.run, a.droplet, "snapshot-times");
  if (!a.run.IsValid(&why)) throw std::invalid_argument(why);
  check_recording(a.run, a.batch.droplets, a.droplet.masses);
  resolve_medium(a.medium);
  check_second_droplet(a.second, a.droplet);
  if (!std::isnan(a.x0) && !std::isfinite(a.x0)) throw std::invalid_argument("x0 = " + fmt(a.x0) + ": must be finite");
  for (const auto& [option, path] : {std::pair{"--save-medium", a.save_medium_file},
                                     {"--runs", a.runs_csv},
                                     {"--paths", a.paths_csv},
                                     {"--trace", a.trace_csv},
                                     {"--snapshots", a.snapshots_csv},
                                     {"--json", a.json_file}})
    if (!path.empty()) check_output_path(option, path);
}

int run_simulate(SimulateArgs& a) {
  check_simulate(a);
  const Medium medium = a.medium.file.empty() ? generate_medium(a.medium.options) : load_medium_file(a.medium);
  check_start_x(a.x0, medium, a.droplet);
  if (!a.save_medium_file.empty()) save_medium(a.save_medium_file, medium);
  const double porosity = exact_porosity(medium);
  a.batch.start_x = a.x0;
  if (a.second.on()) return run_simulate_two(a, medium);

  Progress progress("simulate: droplets done");
  // The first SIGINT or SIGTERM starts no more droplets; the ones in flight finish, and the
  // outputs hold the droplets that ran (0 to n - 1, as an uninterrupted run has them).
  const StopOnSignal stop("\nsoftdrop: finishing the droplets in flight (Ctrl-C again to leave now)\n");
  a.batch.stop = stop.flag();
  const auto t0 = std::chrono::steady_clock::now();
  RunOptions batch_run = a.run;
  batch_run.area_interval = 0;  // --trace replays each droplet with trace_area, which records the area
  const std::vector<RunSummary> runs =
      run_batch(a.droplet, medium, batch_run, a.batch,
                a.batch.droplets > 1 && !a.quiet
                    ? std::function<void(int, int)>([&](int done, int total) { progress.update(done, total); })
                    : std::function<void(int, int)>());
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const BatchStats stats = summarize(runs);
  double total_steps = 0;
  for (const auto& r : runs) total_steps += static_cast<double>(r.steps);

  nlohmann::json j;
  j["version"] = kVersion;
  j["medium"] = medium_record(medium, porosity);
  j["droplets"] = stats.droplets;
  j["passed"] = stats.passed;
  j["stuck"] = stats.stuck;
  j["timeout"] = stats.timeout;
  j["diverged"] = stats.diverged;
  j["mean_tortuosity"] = stats.passed ? nlohmann::json(stats.mean_tortuosity) : nlohmann::json();
  j["standard_error"] = stats.passed > 1 ? nlohmann::json(stats.standard_error) : nlohmann::json();
  j["stuck_fraction"] = stats.stuck_fraction;
  j["wall_seconds"] = seconds;
  j["steps_per_second"] = seconds > 0 ? total_steps / seconds : 0.0;
  j["runs"] = nlohmann::json::array();  // the --runs CSV's records, with the reason
  for (std::size_t i = 0; i < runs.size(); ++i) {
    nlohmann::json record = run_record(runs[i]);
    record["droplet"] = i;
    j["runs"].push_back(std::move(record));
  }
  if (runs.size() == 1) j["run"] = j["runs"][0];

  std::ostringstream table;
  table << std::setprecision(6);
  table << medium_line(medium, porosity);
  if (runs.size() == 1) {
    const RunSummary& r = runs[0];
    table << "outcome      " << to_string(r.outcome) << " (" << r.reason << ")\n";
    if (r.outcome == Outcome::passed) table << "tortuosity   " << fmt(r.tortuosity, 10) << '\n';
    table << "start x      " << r.start_x << "\nsteps        " << r.steps
          << " (t = " << static_cast<double>(r.steps) * a.droplet.dt << ")\ntouched      " << r.touched.size()
          << (medium.image ? " solid parts (connected pieces of the image's solid)" : " grains") << "\nmin area     "
          << r.min_area_ratio << " S0\nmax depth    " << r.max_penetration << " length units\n";
  } else {
    table << "droplets     " << stats.droplets << ": " << stats.passed << " passed, " << stats.stuck << " stuck, "
          << stats.timeout << " timeout, " << stats.diverged << " diverged\n";
    // One passed droplet has no spread to measure: say so rather than print an error of 0.
    if (stats.passed > 1)
      table << "mean T       " << fmt(stats.mean_tortuosity, 8) << " +- " << stats.standard_error
            << " (standard error)\n";
    else if (stats.passed == 1)
      table << "mean T       " << fmt(stats.mean_tortuosity, 8) << " (one droplet passed: no standard error)\n";
    table << "stuck        " << stats.stuck_fraction << " of droplets\n";
  }
  table << "speed        " << total_steps / seconds << " steps/s (" << seconds << " s wall)\n";

  if (!a.json_file.empty()) write_file_atomically(a.json_file, j.dump(2) + "\n");
  auto csv = [&](const std::string& path, const std::string& header, auto&& rows) {
    write_csv(path, header, [&](std::ostream& out) {
      for (std::size_t i = 0; i < runs.size(); ++i) rows(out, static_cast<int>(i), runs[i]);
    });
  };
  csv(a.runs_csv, std::string("droplet,") + kRunColumns, [](std::ostream& o, int i, const RunSummary& r) {
    o << i << ',';
    write_run_columns(o, r);
    o << '\n';
  });
  csv(a.paths_csv, "droplet,time,x,y",
      [](std::ostream& o, int i, const RunSummary& r) { write_path_rows(o, std::to_string(i) + ",", r); });
  if (!a.trace_csv.empty()) {  // each droplet replayed by trace_area, as render trace does
    std::vector<AreaTrace> traces;
    for (const RunSummary& r : runs)
      traces.push_back(trace_area(a.droplet, medium, r.start_x, a.run, a.run.area_interval));
    write_area_traces(a.trace_csv, traces);
  }
  csv(a.snapshots_csv, "droplet,time,mass,x,y",
      [](std::ostream& o, int i, const RunSummary& r) { write_snapshot_rows(o, std::to_string(i) + ",", r); });
  return finish_simulate(a.format, j, table.str(), stop, runs.size(), a.batch.droplets, "droplets");
}

}  // namespace softdrop::cli
