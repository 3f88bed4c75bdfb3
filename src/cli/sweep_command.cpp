#include "cli/sweep_command.hpp"

#include <unistd.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "cli/mpi_sweep.hpp"
#include "cli/options_diff.hpp"
#include "cli/output.hpp"
#include "softdrop/grain_file.hpp"
#include "softdrop/history.hpp"
#include "softdrop/params_json.hpp"
#include "softdrop/sweep_store.hpp"
#include "softdrop/version.hpp"

namespace softdrop::cli {

void add_sweep_commands(CLI::App& app, SweepArgs& a, SweepMergeArgs& m, SweepReportArgs& r) {
  CLI::App* s = app.add_subcommand(
      "sweep", "Tortuosity-porosity sweep: M media per porosity, K droplets each, into a resumable SQLite store");
  s->fallthrough();
  auto* g = s->add_option_group("Sweep", "stored with the sweep; the same options continue the same sweep");
  g->add_option("--db", a.db, "SQLite store (the search history's file family; created if missing)")
      ->capture_default_str();
  g->add_option("--preset", a.preset,
                "quick (porosities 0.7, 0.8, 0.9 x 2 media x 8 droplets) or paper "
                "(10 porosities x 200 media x 200 droplets): defaults for options not given")
      ->check(CLI::IsMember({"quick", "paper"}));
  g->add_option("--porosities", a.sweep.porosities, "Target porosities, comma-separated")
      ->delimiter(',')
      ->capture_default_str();
  g->add_option("--media", a.sweep.media, "M media per porosity")->capture_default_str();
  g->add_option("--droplets", a.sweep.droplets, "K droplets per medium, from random starts")->capture_default_str();
  g->add_option("--seed", a.sweep.seed, "Seed of media and start positions")
      ->capture_default_str()
      ->check(seed_check());
  g->add_option("--media-stream", a.media_stream,
                "Which media a seed picks: held-out (media no calibrate run ever tunes on) or calibration "
                "(calibrate's own media for that seed: to re-measure what a calibration saw)")
      ->capture_default_str()
      ->check(CLI::IsMember(media_stream_names()));
  g->add_option("--shard", a.shard, "Run only shard i of n (i/n, 0-based); merge the stores with sweep-merge")
      ->capture_default_str();
  g->add_option("--threads", a.threads, "Worker threads (0 = all cores); results do not depend on it")
      ->capture_default_str();
  g->add_flag("--quiet", a.quiet, "No progress on stderr");
  g->add_option("--format", a.format, "Summary on stdout: table, csv or json")
      ->capture_default_str()
      ->check(CLI::IsMember({"table", "csv", "json"}));
  add_medium_options(s, a.medium, false)->get_option("--medium")->description("(not used by sweep)");
  auto* d = add_droplet_options(s, a.sweep.droplet);
  add_exit_options(d, a.sweep.run);

  CLI::App* mg =
      app.add_subcommand("sweep-merge", "Merge sweep stores (e.g. shards) into one; identical units must agree");
  mg->add_option("--into", m.into, "The store to merge into (created if missing)")->required();
  mg->add_option("inputs", m.inputs, "Stores to merge from")->required()->check(CLI::ExistingFile);

  CLI::App* rp = app.add_subcommand("sweep-report", "Per-porosity points (or per-medium rows) of a sweep");
  rp->fallthrough();
  rp->add_option("--db", r.db, "SQLite store")->capture_default_str();
  rp->add_option("--sweep", r.sweep, "Sweep id (default: the only one)")->check(id_check());
  rp->add_flag("--media", r.media, "One row per medium instead of one per porosity");
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
      "time.");
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

namespace {

void apply_preset(SweepArgs& a, const CLI::App& cmd) {
  if (a.preset.empty()) return;
  auto unset = [&](const char* name) { return cmd.get_option_no_throw(name)->count() == 0; };
  const bool quick = a.preset == "quick";
  if (unset("--porosities"))
    a.sweep.porosities = quick ? std::vector<double>{0.7, 0.8, 0.9}
                               : std::vector<double>{0.45, 0.5, 0.55, 0.6, 0.65, 0.7, 0.75, 0.8, 0.85, 0.9};
  if (unset("--media")) a.sweep.media = quick ? 2 : 200;
  if (unset("--droplets")) a.sweep.droplets = quick ? 8 : 200;
}

std::pair<int, int> parse_shard(const std::string& text) {
  const auto slash = text.find('/');
  try {
    if (slash != std::string::npos) {
      std::size_t p1 = 0, p2 = 0;
      const int i = std::stoi(text.substr(0, slash), &p1), n = std::stoi(text.substr(slash + 1), &p2);
      if (p1 == slash && p2 == text.size() - slash - 1 && n >= 1 && i >= 0 && i < n) return {i, n};
    }
  } catch (const std::exception&) {
  }
  throw std::invalid_argument("shard = '" + text + "': expected i/n with 0 <= i < n");
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

// A new sweep in a file that holds others: which one it is nearest, and in what it differs, so a
// sweep meant to continue another is seen not to.
void say_how_it_differs(SweepStore& store, const std::string& db, const std::string& params) {
  std::int64_t nearest = 0;
  std::vector<std::string> fewest;
  for (const SweepRecord& r : store.sweeps()) {
    if (r.params == params) return;  // the same sweep, continued
    const auto keys = varying_options({r.params, params});
    if (nearest == 0 || keys.size() < fewest.size()) nearest = r.id, fewest = keys;
  }
  if (nearest == 0) return;
  std::string diff;
  for (const std::string& k : fewest)
    diff += (diff.empty() ? "" : ", ") + k + " " + options_text(store.sweep(nearest).params, {k}).substr(k.size() + 1) +
            " -> " + options_text(params, {k}).substr(k.size() + 1);
  std::cerr << "sweep: '" << db << "' holds " << store.sweeps().size() << " other sweep(s); this is a new one, "
            << "nearest sweep " << nearest << ", which differs in: " << diff << "\n";
}

}  // namespace

std::pair<int, int> check_sweep(SweepArgs& a, const CLI::App& cmd) {
  apply_preset(a, cmd);
  if (!a.medium.file.empty()) throw std::invalid_argument("medium: sweep generates its media; --medium is not used");
  resolve_medium(a.medium);
  a.sweep.medium = a.medium.options;
  a.sweep.stream = parse_media_stream(a.media_stream);
  std::string why;
  if (!a.sweep.IsValid(&why)) throw std::invalid_argument(why);
  check_threads(a.threads);
  return parse_shard(a.shard);
}

int run_sweep(SweepArgs& a, const CLI::App& cmd, Host* host) {
  const auto [shard, shards] = check_sweep(a, cmd);
  const Job* job = current_job();
  const bool on_ranks = job && job->size() > 1;
  if (on_ranks && job->rank() != 0) {  // rank 0 has the store and says what to run
    work_on_sweep_units(*job, a.sweep, a.threads);
    return 0;
  }

  // Nothing is written before the first medium is stored: a sweep refused at its start (a damaged
  // store, a porosity random placement cannot reach) leaves every file as it was, and creates none.
  const std::string params = sweep_params_to_json(a.sweep);
  std::unique_ptr<SweepStore> store;
  std::int64_t id = 0;
  std::vector<SweepUnit> done;
  if (std::filesystem::exists(a.db)) {
    store = open_sweep_store(a.db, OpenMode::create);
    if (!a.quiet) say_how_it_differs(*store, a.db, params);
    id = store->find(params);
    if (id > 0)  // every stored row read now: a damaged one refuses the sweep here
      for (const SweepMedium& m : store->media(id)) done.push_back(m.unit);
  } else {
    check_database(a.db);  // a new file: its folder must exist and be writable
  }
  const auto sweep_id = [&] {  // the store and the sweep's record, made when first needed
    if (!store) store = open_sweep_store(a.db, OpenMode::create);
    if (id == 0) id = store->find_or_create(params, a.sweep);
    return id;
  };
  std::vector<SweepUnit> todo;
  for (const SweepUnit& u : sweep_units(a.sweep, shard, shards))
    if (std::find(done.begin(), done.end(), u) == done.end()) todo.push_back(u);
  const std::size_t shard_total = sweep_units(a.sweep, shard, shards).size();
  if (!a.quiet)
    std::cerr << "sweep " << (id > 0 ? std::to_string(id) : std::string("(new)")) << " in " << a.db << ": "
              << a.sweep.porosities.size() << " porosities x " << a.sweep.media << " media x " << a.sweep.droplets
              << " droplets; shard " << shard << "/" << shards << ": " << shard_total - todo.size() << " of "
              << shard_total << " media already stored\n";

  std::optional<StopOnSignal> signals;  // a host handles the signals itself
  if (!host)
    signals.emplace(
        "\nsoftdrop: finishing the media in flight (Ctrl-C again to leave now; they are then redone next time)\n");
  std::atomic<bool> host_stop{false};
  auto stopping = [&] { return signals ? signals->requested() : host_stop.load(); };
  const auto t0 = std::chrono::steady_clock::now();
  const bool tty = ::isatty(2) != 0;
  auto last = t0;
  long droplets_done = 0;
  std::size_t units_done = 0, units_elsewhere = 0;
  std::mutex store_lock;      // on_done runs on this thread, skip on the workers
  double commit_seconds = 0;  // in store->add: what rank 0 of an MPI job spends on each medium
  const std::function<void(SweepMedium &&)> commit = [&](SweepMedium&& m) {
    std::lock_guard lock(store_lock);
    const auto c0 = std::chrono::steady_clock::now();
    const std::int64_t sweep = sweep_id();         // before store-> is read: it may make the store
    if (!store->add(sweep, m)) ++units_elsewhere;  // stored meanwhile by another process
    commit_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - c0).count();
    ++units_done;
    droplets_done += static_cast<long>(m.droplets.size());
    const auto now = std::chrono::steady_clock::now();
    if (!a.quiet && (now - last > std::chrono::seconds(tty ? 1 : 10) || units_done == todo.size())) {
      last = now;
      const double s = std::chrono::duration<double>(now - t0).count();
      // The pace so far, and the medium just stored: its porosity, how many passed and their <T>.
      std::cerr << (tty ? "\r" : "") << "sweep: " << units_done << "/" << todo.size() << " media ("
                << percent_and_eta(s, static_cast<double>(units_done), static_cast<double>(todo.size())) << "), "
                << fmt(static_cast<double>(droplets_done) / s, 3) << " droplets/s; last medium: phi "
                << fmt(m.target_porosity, 3) << ", " << m.passed << "/" << m.droplets.size() << " passed"
                << (m.passed ? ", <T> " + fmt(m.mean_t, 5) : std::string())
                << (tty && units_done != todo.size() ? "\033[K" : "\n") << std::flush;
    }
    if (host && host->on_progress &&
        !host->on_progress({{"sweep", id},
                            {"porosity_index", m.unit.porosity},
                            {"medium_index", m.unit.medium},
                            {"target_porosity", m.target_porosity},
                            {"passed", m.passed},
                            {"mean_tortuosity", m.passed ? nlohmann::json(m.mean_t) : nlohmann::json()},
                            {"media_done", units_done},
                            {"media_to_do", todo.size()}}))
      host_stop = true;
  };
  const std::function<bool()> stop_requested = [&] { return stopping(); };
  const std::function<bool(const SweepUnit&)> stored = [&](const SweepUnit& u) {
    std::lock_guard lock(store_lock);
    if (id == 0 && store) id = store->find(params);  // another process may have begun the sweep
    if (id == 0 || !store->has_unit(id, u)) return false;
    ++units_done, ++units_elsewhere;
    return true;
  };
  RanksReport ranks;
  if (on_ranks)
    ranks = run_sweep_units_on_ranks(*job, a.sweep, todo, a.threads, commit, stop_requested, stored);
  else
    run_sweep_units(a.sweep, todo, a.threads, commit, stop_requested, stored);
  sweep_id();  // a sweep stopped before its first medium is recorded as begun
  const SweepRecord rec = store->sweep(id);
  const std::string status = rec.done == rec.units ? "complete" : stopping() ? "interrupted" : "running";
  store->set_status(id, status);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (host) {
    host->summary = {{"version", kVersion},
                     {"db", a.db},
                     {"sweep", id},
                     {"status", status},
                     {"media", rec.units},
                     {"done", rec.done},
                     {"media_this_session", units_done - units_elsewhere},
                     {"media_by_another_process", units_elsewhere},
                     {"droplets_this_session", droplets_done},
                     {"wall_seconds", seconds},
                     {"commit_seconds", commit_seconds}};
    return 0;
  }
  points_table(sweep_points(store->media(id))).print(std::cout, a.format);
  if (!a.quiet) {
    std::cerr << "sweep " << id << ": " << rec.done << " of " << rec.units << " media stored; this session "
              << units_done - units_elsewhere << " media, " << droplets_done << " droplets in " << fmt(seconds, 4)
              << " s"
              << (units_elsewhere ? ", " + std::to_string(units_elsewhere) + " media stored by another process" : "");
    const auto stored_here = static_cast<double>(units_done - units_elsewhere);
    for (std::size_t r = 0; r < ranks.ran.size(); ++r) std::cerr << (r == 0 ? "; by rank: " : ", ") << ranks.ran[r];
    if (stored_here > 0) std::cerr << "; storing took " << fmt(1e3 * commit_seconds / stored_here, 3) << " ms a medium";
    if (ranks.ran.size() > 1 && stored_here > ranks.ran[0])  // the record's decoding, the answers to the ranks, storing
      std::cerr << ", serving the other ranks " << fmt(1e3 * ranks.serve_seconds / (stored_here - ranks.ran[0]), 3)
                << " ms a medium of theirs";
    std::cerr << "\n";
  }
  return signals->exit_code();
}

int run_sweep_report(const SweepReportArgs& a) {
  auto store = open_sweep_store(a.db, OpenMode::read_only);
  if (a.sweep == 0 && store->sweeps().size() > 1) {
    list_sweeps(*store, a.format);
    return 0;
  }
  const std::int64_t id = pick_sweep(*store, a.sweep, a.db);
  const auto media = store->media(id);
  if (!a.media) {
    points_table(sweep_points(media)).print(std::cout, a.format);
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
