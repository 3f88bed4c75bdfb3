// `softdrop simulate --second-droplet`: pairs of droplets, one pushed after the other, and their
// outputs (the table, JSON, and the CSVs with a row per droplet: droplet is the pair's number,
// order 1 the first and 2 the second).
#include <chrono>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "cli/columns.hpp"
#include "cli/output.hpp"
#include "cli/simulate_command.hpp"
#include "cli/simulate_output.hpp"
#include "softdrop/version.hpp"

namespace softdrop::cli {

namespace {

nlohmann::json or_null(double v) { return std::isnan(v) ? nlohmann::json() : nlohmann::json(v); }

// One droplet of a pair: the run's record (simulate's), and the pair's.
nlohmann::json droplet_json(const TwoDropletSummary& p, int i, int order) {
  nlohmann::json j = run_record(order == 1 ? p.first : p.second);
  j["droplet"] = i;
  j["order"] = order;
  j["released_at"] = or_null(p.released_at);
  j["held_at"] = or_null(order == 1 ? p.first_held_at : p.second_held_at);
  j["contact_steps"] = p.contact_steps;
  j["shared_touched"] = p.shared_touched;
  return j;
}

nlohmann::json stats_json(const BatchStats& s) {
  return {{"droplets", s.droplets},
          {"passed", s.passed},
          {"stuck", s.stuck},
          {"timeout", s.timeout},
          {"diverged", s.diverged},
          {"mean_tortuosity", s.passed ? nlohmann::json(s.mean_tortuosity) : nlohmann::json()},
          {"standard_error", s.passed > 1 ? nlohmann::json(s.standard_error) : nlohmann::json()},
          {"stuck_fraction", s.stuck_fraction}};
}

std::string stats_line(const BatchStats& s) {
  std::ostringstream o;
  o << s.passed << " passed, " << s.stuck << " stuck, " << s.timeout << " timeout, " << s.diverged << " diverged";
  if (s.passed > 1)
    o << "; mean T " << fmt(s.mean_tortuosity, 8) << " +- " << fmt(s.standard_error, 3);
  else if (s.passed == 1)
    o << "; T " << fmt(s.mean_tortuosity, 8);
  return o.str();
}

// The touched set's entries: grains, or an image medium's solid parts.
const char* obstacles(const Medium& medium) { return medium.image ? "solid parts" : "grains"; }

std::string run_line(const RunSummary& r, double dt, const Medium& medium) {
  std::ostringstream o;
  o << to_string(r.outcome);
  if (r.outcome == Outcome::passed) o << ", T " << fmt(r.tortuosity, 10);
  o << " (start x " << fmt(r.start_x, 8) << ", " << r.steps
    << " steps, t = " << fmt(static_cast<double>(r.steps) * dt, 6) << ", " << r.touched.size() << ' '
    << obstacles(medium) << " touched; " << r.reason << ")";
  return o.str();
}

}  // namespace

int run_simulate_two(SimulateArgs& a, const Medium& medium) {
  check_second_start(a.second, a.x0, medium, a.droplet);
  const double porosity = exact_porosity(medium);
  Progress progress("simulate: pairs done");
  const StopOnSignal stop("\nsoftdrop: finishing the pairs in flight (Ctrl-C again to leave now)\n");
  a.batch.stop = stop.flag();
  const auto t0 = std::chrono::steady_clock::now();
  const std::vector<TwoDropletSummary> pairs = run_two_droplet_batch(
      a.droplet, medium, a.run, a.batch, a.second.second,
      a.batch.droplets > 1 && !a.quiet
          ? std::function<void(int, int)>([&](int done, int total) { progress.update(done, total); })
          : std::function<void(int, int)>());
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  std::vector<RunSummary> firsts, seconds_run;
  int released = 0, touched = 0, held = 0, freed = 0, clogged = 0;
  double total_steps = 0;
  for (const TwoDropletSummary& p : pairs) {
    firsts.push_back(p.first);
    if (p.released) seconds_run.push_back(p.second);
    released += p.released;
    touched += p.contact_steps > 0;
    const bool was_held = !std::isnan(p.first_held_at);
    held += was_held;
    freed += was_held && p.first.outcome == Outcome::passed;
    clogged += p.first.outcome == Outcome::stuck && p.second.outcome == Outcome::stuck;
    total_steps += static_cast<double>(p.first.steps + p.second.steps);
  }
  const BatchStats first = summarize(firsts), second = summarize(seconds_run);

  nlohmann::json j;
  j["version"] = kVersion;
  j["medium"] = medium_record(medium, porosity);
  j["second_droplet"] = {{"release", to_string(a.second.second.release)},
                         {"after", a.second.second.after},
                         {"offset_x", a.second.second.offset_x}};
  j["pairs"] = pairs.size();
  j["released"] = released;
  j["in_contact"] = touched;
  j["held"] = held;
  j["freed"] = freed;
  j["clogged"] = clogged;
  j["first"] = stats_json(first);
  j["second"] = stats_json(second);
  j["wall_seconds"] = seconds;
  j["steps_per_second"] = seconds > 0 ? total_steps / seconds : 0.0;
  j["runs"] = nlohmann::json::array();
  for (std::size_t i = 0; i < pairs.size(); ++i)
    for (int order : {1, 2}) j["runs"].push_back(droplet_json(pairs[i], static_cast<int>(i), order));

  std::ostringstream table;
  table << std::setprecision(6);
  table << medium_line(medium, porosity);
  if (pairs.size() == 1) {
    const TwoDropletSummary& p = pairs[0];
    table << "first        " << run_line(p.first, a.droplet.dt, medium) << '\n';
    if (p.released)
      table << "second       released at t = " << fmt(p.released_at, 6) << ": "
            << run_line(p.second, a.droplet.dt, medium) << '\n';
    else
      table << "second       " << p.second.reason << '\n';
    table << "contact      " << p.contact_steps << " steps in contact; " << p.shared_touched << ' ' << obstacles(medium)
          << " touched by both\n";
    if (!std::isnan(p.first_held_at))
      table << "held         the first was held from t = " << fmt(p.first_held_at, 6)
            << " (at rest or stuck while the second still moved)\n";
  } else {
    table << "pairs        " << pairs.size() << ": " << released << " second droplets released, " << touched
          << " pairs in contact\n";
    table << "first        " << stats_line(first) << '\n';
    table << "second       " << stats_line(second) << '\n';
    table << "held         " << held << " first droplets held (at rest or stuck while the second moved): " << freed
          << " then passed; " << clogged << " pairs ended with both stuck\n";
  }
  table << "speed        " << total_steps / seconds << " steps/s (" << seconds << " s wall)\n";

  if (!a.json_file.empty()) write_file_atomically(a.json_file, j.dump(2) + "\n");
  auto csv = [&](const std::string& path, const std::string& header, auto&& rows) {
    write_csv(path, header, [&](std::ostream& out) {
      for (std::size_t i = 0; i < pairs.size(); ++i) {
        const int k = static_cast<int>(i);
        rows(out, std::to_string(i) + ",1,", k, 1, pairs[i].first);
        if (pairs[i].released) rows(out, std::to_string(i) + ",2,", k, 2, pairs[i].second);
      }
    });
  };
  csv(a.runs_csv, std::string("droplet,order,") + kRunColumns + ",released_at,held_at,contact_steps,shared_touched",
      [&](std::ostream& o, const std::string& key, int i, int order, const RunSummary& r) {
        const TwoDropletSummary& p = pairs[static_cast<std::size_t>(i)];
        const double held_at = order == 1 ? p.first_held_at : p.second_held_at;
        o << key;
        write_run_columns(o, r);
        o << ',' << (std::isnan(p.released_at) ? "" : fmt(p.released_at)) << ','
          << (std::isnan(held_at) ? "" : fmt(held_at)) << ',' << p.contact_steps << ',' << p.shared_touched << '\n';
      });
  csv(a.paths_csv, "droplet,order,time,x,y",
      [](std::ostream& o, const std::string& key, int, int, const RunSummary& r) { write_path_rows(o, key, r); });
  csv(a.trace_csv, "droplet,order,time,area",
      [](std::ostream& o, const std::string& key, int, int, const RunSummary& r) {
        for (std::size_t k = 0; k < r.area_t.size(); ++k) o << key << fmt(r.area_t[k]) << ',' << fmt(r.area[k]) << '\n';
      });
  csv(a.snapshots_csv, "droplet,order,time,mass,x,y",
      [](std::ostream& o, const std::string& key, int, int, const RunSummary& r) { write_snapshot_rows(o, key, r); });
  return finish_simulate(a.format, j, table.str(), stop, pairs.size(), a.batch.droplets, "pairs");
}

}  // namespace softdrop::cli
