// `softdrop sweep-report`: a sweep's per-porosity points (or per-medium rows) from its store, and
// the choice of a sweep in a file that holds several.
#include "cli/sweep_report_command.hpp"

#include <iostream>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli/common_options.hpp"
#include "cli/options_diff.hpp"
#include "softdrop/store.hpp"
#include "store/params_json.hpp"

namespace softdrop::cli {

void add_sweep_report_command(CLI::App& app, SweepReportArgs& r) {
  CLI::App* rp = app.add_subcommand("sweep-report", "Per-porosity points (or per-medium rows) of a sweep");
  rp->fallthrough();
  rp->add_option("--db", r.db, "SQLite store")->capture_default_str();
  rp->add_option("--sweep", r.sweep, "Sweep id (default: the only one)")->check(id_check());
  rp->add_flag("--media", r.media, "One row per medium instead of one per porosity");
  rp->add_flag("--second-droplets", r.second_droplets,
               "A sweep of pairs (sweep --second-droplet): the points of the second droplets instead of the firsts")
      ->excludes("--media");
  rp->add_option("--format", r.format, "table, csv or json")
      ->capture_default_str()
      ->check(CLI::IsMember({"table", "csv", "json"}));
  rp->footer(
      "Columns (softdrop columns lists every name, with its unit). Points: target_porosity = the porosity asked "
      "for; porosity = mean exact porosity of the media; mean_tortuosity = <T> over the passed droplets; "
      "standard_error = its error taking every passed droplet as independent; media_passed = media where a "
      "droplet passed; media_standard_error = its error taking each medium's droplets as one cluster (they share "
      "its throats and dead ends: the error to quote, larger); stuck_fraction over all droplets; "
      "per_medium_tortuosity = "
      "the other averaging, each medium's <T> first, then their plain mean over the media_passed media, with "
      "per_medium_standard_error over those media. Media (--media): "
      "one row per medium, mean_tortuosity and standard_error over its own passed droplets; seconds = its wall "
      "time. In a sweep of pairs the droplets are the pairs' firsts; --second-droplets gives the points of the "
      "released seconds (each one row of the database's sweep_second_droplets_view).");
}

namespace {
// A reader of part of a sweep is told so: its figures are of the media stored, not of the sweep.
void warn_if_partial(const SweepRecord& r, const std::string& db) {
  if (r.done >= r.units) return;
  std::cerr << "warning: sweep " << r.id << " in '" << db << "' holds " << r.done << " of its " << r.units
            << " media (status " << r.status
            << "; a shard's store, or a sweep stopped or still running: the same sweep command goes on with "
               "the rest); these figures are of those "
            << r.done << "\n";
}
}  // namespace

std::int64_t pick_sweep(SweepStore& store, std::int64_t id, const std::string& db) {
  if (id > 0) {
    const SweepRecord r = store.sweep(id);
    warn_if_partial(r, db);
    return r.id;
  }
  const auto all = store.sweeps();
  if (all.size() == 1) {
    warn_if_partial(all[0], db);
    return all[0].id;
  }
  throw std::invalid_argument(all.empty() ? "--db '" + db + "': holds no sweep"
                                          : "--sweep: '" + db + "' holds " + std::to_string(all.size()) +
                                                " sweeps; choose one with --sweep ID (softdrop sweep-report --db " +
                                                db + " lists them)");
}

Table points_table(const std::vector<SweepPoint>& points) {
  Table t;
  t.header = {"target_porosity",
              "porosity",
              "media",
              "droplets",
              "passed",
              "mean_tortuosity",
              "standard_error",
              "media_passed",
              "media_standard_error",
              "stuck_fraction",
              "per_medium_tortuosity",
              "per_medium_standard_error"};
  for (const SweepPoint& p : points)
    t.rows.push_back({p.target_porosity, p.porosity, p.media, p.droplets, p.passed,
                      p.passed ? nlohmann::json(p.mean_t) : nlohmann::json(),
                      p.passed > 1 ? nlohmann::json(p.standard_error) : nlohmann::json(), p.media_passed,
                      p.media_passed > 1 ? nlohmann::json(p.media_standard_error) : nlohmann::json(), p.stuck_fraction,
                      p.media_passed ? nlohmann::json(p.per_medium_t) : nlohmann::json(),
                      p.media_passed > 1 ? nlohmann::json(p.per_medium_standard_error) : nlohmann::json()});
  return t;
}

namespace {
// Sweeps are listed by sweep-report when no id is given and the store holds several.
// Each sweep with the options that set it apart from the others (all of them are in the sweeps
// table's params column).
void list_sweeps(SweepStore& store, const std::string& format) {
  const auto sweeps = store.sweeps();
  std::vector<std::string> params;
  for (const SweepRecord& r : sweeps) params.push_back(r.params);
  const std::vector<std::string> keys = varying_options(params);
  Table t;
  t.header = {"sweep", "created", "status", "units", "done", "version", "differs_in"};
  for (const SweepRecord& r : sweeps)
    t.rows.push_back({r.id, r.created, r.status, r.units, r.done, r.version, options_text(r.params, keys)});
  t.print(std::cout, format);
}
}  // namespace

int run_sweep_report(const SweepReportArgs& a) {
  auto store = open_sweep_store(a.db, OpenMode::read_only);
  if (a.sweep == 0 && store->sweeps().size() > 1) {
    list_sweeps(*store, a.format);
    return 0;
  }
  const std::int64_t id = pick_sweep(*store, a.sweep, a.db);
  if (a.second_droplets && !sweep_params_from_json(store->sweep(id).params).second)
    throw std::invalid_argument("second-droplets: sweep " + std::to_string(id) + " in '" + a.db +
                                "' pushes one droplet at a time (no --second-droplet)");
  const auto media = store->media(id);
  if (!a.media) {
    points_table(sweep_points(media, a.second_droplets)).print(std::cout, a.format);
    return 0;
  }
  Table t;
  t.header = {"porosity_index",  "medium_index",   "target_porosity", "porosity", "grains",
              "droplets",        "passed",         "stuck",           "timeout",  "diverged",
              "mean_tortuosity", "standard_error", "stuck_fraction",  "seconds"};
  for (const SweepMedium& m : media)
    t.rows.push_back({m.unit.porosity, m.unit.medium, m.target_porosity, m.porosity, m.grains, m.droplets.size(),
                      m.passed, m.stuck, m.timeout, m.diverged, m.passed ? nlohmann::json(m.mean_t) : nlohmann::json(),
                      m.passed > 1 ? nlohmann::json(m.standard_error) : nlohmann::json(), m.stuck_fraction, m.seconds});
  t.print(std::cout, a.format);
  return 0;
}

}  // namespace softdrop::cli
