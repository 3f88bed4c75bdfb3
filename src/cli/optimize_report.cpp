// What `softdrop optimize` says when its drive ends (search_setup.hpp): the summary as JSON, or as
// the table a person reads.
#include <iostream>
#include <nlohmann/json.hpp>

#include "cli/output.hpp"
#include "cli/search_setup.hpp"
#include "softdrop/version.hpp"

namespace softdrop::cli {

namespace {

// A resumed run already at its target.
void report_nothing_to_do(const SearchOutput& out, const SearchRunSummary& s, Host* host) {
  const std::string line = "nothing to do: run " + std::to_string(s.run) + " is at generation " +
                           std::to_string(s.drive.last_generation) + " (target " + std::to_string(s.target) + ")";
  const nlohmann::json j{{"version", kVersion},
                         {"db", out.db},
                         {"run", s.run},
                         {"termination", "nothing to do"},
                         {"message", line},
                         {"last_generation", s.drive.last_generation},
                         {"generations_run", 0},
                         {"evaluations", 0},
                         {"best_tortuosity", s.best.eval.tortuosity},
                         {"best_generation", s.best.generation}};
  if (!out.json_file.empty()) write_file_atomically(out.json_file, j.dump(2) + "\n");
  if (host)
    host->summary = j;
  else
    std::cout << (out.format == "json" ? j.dump(2) : "optimize: " + line) << '\n';
}

}  // namespace

void report_optimize(const SearchOutput& out, const SearchRunSummary& s, Host* host) {
  if (s.nothing_to_do) {
    report_nothing_to_do(out, s, host);
    return;
  }
  const SearchSummary& summary = s.drive;
  const Configuration& best = s.best;
  const SearchOptions& search = s.search;
  const nlohmann::json held_out = s.held_out ? held_out_json(*s.held_out, s.held_out_objective) : nlohmann::json();
  const std::int64_t run = s.run, initial_evaluations = s.initial_evaluations, initial_droplets = s.initial_droplets;
  nlohmann::json j;
  j["version"] = kVersion;
  j["db"] = out.db;
  j["run"] = run;
  j["strategy"] = to_string(search.strategy.kind);
  j["objective"] = to_string(search.objective.kind);
  j["starts"] = search.objective.droplets();
  j["termination"] = to_string(summary.termination);
  j["message"] = summary.message;
  j["last_generation"] = summary.last_generation;
  j["generations_run"] = summary.generations_run;
  j["evaluations"] = summary.evaluations + initial_evaluations;
  j["droplets"] = summary.droplets + initial_droplets;
  j["accepted"] = summary.accepted;
  j["best_tortuosity"] = best.eval.tortuosity;
  j["best_generation"] = best.generation;
  j["grains"] = best.medium.grains.size();
  j["touched"] = best.eval.touched.size();
  j["held_out"] = held_out;
  j["wall_seconds"] = summary.seconds;
  j["evaluations_per_second"] = summary.evaluations_per_second();
  j["speculation"] = {{"threads", summary.speculation.threads},
                      {"lanes", summary.speculation.lanes},
                      {"dropped_evaluations", summary.speculation.dropped},
                      {"dropped_steps", summary.speculation.dropped_steps},
                      {"kept_steps", summary.speculation.kept_steps},
                      {"predictions", summary.speculation.predictions},
                      {"mispredictions", summary.speculation.mispredictions},
                      {"predictions_ahead", summary.speculation.predictions_ahead}};
  if (!deliver_summary(out, j, host)) {
    std::cout << "run          " << run << " in " << out.db << "\n"
              << "stopped      " << summary.message << "\n"
              << "best T       " << fmt(best.eval.tortuosity, 10) << " (generation " << best.generation << ", "
              << best.eval.touched.size() << " of " << best.medium.grains.size() << " grains touched)\n";
    if (search.objective.robust())
      std::cout << "objective    " << to_string(search.objective.kind) << " over " << search.objective.starts
                << " fresh starts a generation; the best T is the mean of the best's "
                << summary.last_generation - best.generation << " re-runs"
                << (summary.last_generation == best.generation ? " (none yet: the value it was kept with)" : "")
                << "\n";
    std::cout << "this session " << summary.generations_run << " generations, " << summary.accepted << " accepted, "
              << summary.evaluations + initial_evaluations << " evaluations (" << summary.droplets + initial_droplets
              << " droplets), " << fmt(summary.evaluations_per_second(), 3) << " eval/s\n";
    print_held_out(std::cout, held_out);
    if (out.verbose) {  // for those who tune --lanes and --threads
      const SpeculationStats& sp = summary.speculation;
      const double dropped_share =
          sp.kept_steps > 0 ? 100.0 * static_cast<double>(sp.dropped_steps) / static_cast<double>(sp.kept_steps) : 0.0;
      if (sp.threads == 0)
        std::cout << "speculation  off (one generation at a time)\n";
      else
        std::cout << "speculation  " << sp.threads << " threads x " << sp.lanes << " lanes, " << sp.dropped
                  << " evaluations dropped (" << sp.dropped_steps << " steps, " << fmt(dropped_share, 3)
                  << " % of the kept evaluations' " << sp.kept_steps << "), " << sp.predictions
                  << " acceptances predicted (" << sp.predictions_ahead << " ahead of an undecided generation, "
                  << sp.mispredictions << " overturned)\n";
    }
  }
}

}  // namespace softdrop::cli
