#include "cli/sweep_command.hpp"

#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>

#include "cli/mpi_sweep.hpp"
#include "cli/options_diff.hpp"
#include "cli/output.hpp"
#include "cli/sweep_report_command.hpp"
#include "service/run_values.hpp"
#include "softdrop/medium.hpp"
#include "softdrop/service.hpp"
#include "softdrop/store.hpp"
#include "softdrop/version.hpp"
#include "store/params_json.hpp"

namespace softdrop::cli {

void add_sweep_command(CLI::App& app, SweepArgs& a) {
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
  CLI::Option_group* medium = add_medium_options(s, a.medium, false);
  medium->get_option("--medium")->description("(not used by sweep)");
  medium->get_option("--porosity")->description("(not used by sweep: see --porosities)");
  medium->get_option("--medium-seed")->description("(not used by sweep: each medium's seed comes from --seed)");
  auto* d = add_droplet_options(s, a.sweep.droplet);
  add_exit_options(d, a.sweep.run);
  add_second_droplet_options(s, a.second);
}

namespace {

// The options of a sweep's values (run_values.hpp) given on the command line or in a config file.
std::vector<std::string> given_values(const SweepOptions& sweep, const CLI::App& cmd) {
  const nlohmann::json values = sweep_values(sweep);
  std::vector<std::string> given;
  for (const auto& [key, value] : values.items())
    if (const CLI::Option* o = cmd.get_option_no_throw("--" + key); o && o->count() > 0) given.push_back(key);
  return given;
}

}  // namespace

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

namespace {

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
  apply_sweep_preset(a.preset, given_values(a.sweep, cmd), &a.sweep);
  if (!a.medium.file.empty()) throw std::invalid_argument("medium: sweep generates its media; --medium is not used");
  resolve_medium(a.medium);
  a.sweep.medium = a.medium.options;
  a.sweep.stream = parse_media_stream(a.media_stream);
  check_second_droplet(a.second, a.sweep.droplet);
  if (a.second.on()) a.sweep.second = a.second.second;
  std::string why;
  if (!a.sweep.IsValid(&why)) throw std::invalid_argument(why);
  check_threads(a.threads);
  return parse_shard(a.shard);
}

namespace {
// The program's observer of a sweep's run: its progress line on stderr (with the pace, an ETA and
// the medium just stored), the host's callback (the Python module's), and Ctrl-C when no host
// handles the signals itself.
class SweepProgressLine : public SweepObserver {
 public:
  SweepProgressLine(const SweepRun& run, bool quiet, Host* host) : run_(run), quiet_(quiet), host_(host) {
    if (!host)
      signals_.emplace(
          "\nsoftdrop: finishing the media in flight (Ctrl-C again to leave now; they are then redone next time)\n");
  }
  void started(std::int64_t sweep, std::size_t stored, std::size_t to_do) override {
    if (quiet_) return;
    std::cerr << "sweep " << (sweep > 0 ? std::to_string(sweep) : std::string("(new)")) << " in " << run_.db << ": "
              << run_.sweep.porosities.size() << " porosities x " << run_.sweep.media << " media x "
              << run_.sweep.droplets << " droplets; shard " << run_.shard << "/" << run_.shards << ": " << stored
              << " of " << stored + to_do << " media already stored\n";
  }
  bool stored(const SweepMedium& m, const SweepProgress& p) override {
    const auto now = std::chrono::steady_clock::now();
    if (!quiet_ && (now - last_ > std::chrono::seconds(tty_ ? 1 : 10) || p.done == p.to_do)) {
      last_ = now;
      // The pace so far, and the medium just stored: its porosity, how many passed and their <T>.
      std::cerr << (tty_ ? "\r" : "") << "sweep: " << p.done << "/" << p.to_do << " media ("
                << percent_and_eta(p.seconds, static_cast<double>(p.done), static_cast<double>(p.to_do)) << "), "
                << fmt(static_cast<double>(p.droplets) / p.seconds, 3) << " droplets/s; last medium: phi "
                << fmt(m.target_porosity, 3) << ", " << m.passed << "/" << m.droplets.size() << " passed"
                << (m.passed ? ", <T> " + fmt(m.mean_t, 5) : std::string())
                << (tty_ && p.done != p.to_do ? "\033[K" : "\n") << std::flush;
    }
    return !host_ || !host_->on_progress ||
           host_->on_progress({{"sweep", p.sweep},
                               {"porosity_index", m.unit.porosity},
                               {"medium_index", m.unit.medium},
                               {"target_porosity", m.target_porosity},
                               {"passed", m.passed},
                               {"mean_tortuosity", m.passed ? nlohmann::json(m.mean_t) : nlohmann::json()},
                               {"media_done", p.done},
                               {"media_to_do", p.to_do}});
  }
  bool stop_requested() override { return signals_ && signals_->requested(); }
  int exit_code() const { return signals_ ? signals_->exit_code() : 0; }

 private:
  const SweepRun& run_;
  bool quiet_;
  Host* host_;
  std::optional<StopOnSignal> signals_;  // a host handles the signals itself
  const bool tty_ = ::isatty(2) != 0;
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};
}  // namespace

int run_sweep(SweepArgs& a, const CLI::App& cmd, Host* host) {
  const auto [shard, shards] = check_sweep(a, cmd);
  const Job* job = current_job();
  const bool on_ranks = job && job->size() > 1;
  if (on_ranks && job->rank() != 0) {  // rank 0 has the store and says what to run
    work_on_sweep_units(*job, a.sweep, a.threads);
    return 0;
  }
  SweepUnitsRunner runner;
  if (on_ranks)
    runner = [job](const SweepOptions& options, const std::vector<SweepUnit>& units, int threads,
                   const std::function<void(SweepMedium &&)>& on_done, const std::function<bool()>& stop,
                   const std::function<bool(const SweepUnit&)>& stored) {
      RanksReport r = run_sweep_units_on_ranks(*job, options, units, threads, on_done, stop, stored);
      return SweepUnitsRun{std::move(r.ran), r.serve_seconds};
    };
  return run_sweep_run(SweepRun{a.sweep, a.db, a.threads, shard, shards}, a.quiet, a.format, host, runner);
}

int run_sweep_run(const SweepRun& run, bool quiet, const std::string& format, Host* host,
                  const SweepUnitsRunner& runner) {
  if (!quiet && std::filesystem::exists(run.db))
    say_how_it_differs(*open_sweep_store(run.db, OpenMode::create), run.db, sweep_params_to_json(run.sweep));
  SweepProgressLine progress(run, quiet, host);
  const SweepSummary s = softdrop::run_sweep(run, progress, runner);
  if (host) {
    host->summary = {{"version", kVersion},
                     {"db", run.db},
                     {"sweep", s.sweep},
                     {"status", s.status},
                     {"media", s.media},
                     {"done", s.done},
                     {"media_this_session", s.media_this_session},
                     {"media_by_another_process", s.media_by_another_process},
                     {"droplets_this_session", s.droplets_this_session},
                     {"wall_seconds", s.wall_seconds},
                     {"commit_seconds", s.commit_seconds}};
    return 0;
  }
  points_table(sweep_points(open_sweep_store(run.db, OpenMode::read_only)->media(s.sweep))).print(std::cout, format);
  if (!quiet) {
    std::cerr << "sweep " << s.sweep << ": " << s.done << " of " << s.media << " media stored; this session "
              << s.media_this_session << " media, " << s.droplets_this_session << " droplets in "
              << fmt(s.wall_seconds, 4) << " s"
              << (s.media_by_another_process
                      ? ", " + std::to_string(s.media_by_another_process) + " media stored by another process"
                      : "");
    const auto stored_here = static_cast<double>(s.media_this_session);
    for (std::size_t r = 0; r < s.by_rank.size(); ++r) std::cerr << (r == 0 ? "; by rank: " : ", ") << s.by_rank[r];
    if (stored_here > 0)
      std::cerr << "; storing took " << fmt(1e3 * s.commit_seconds / stored_here, 3) << " ms a medium";
    if (s.by_rank.size() > 1 && stored_here > s.by_rank[0])  // the record's decoding, the answers to the ranks, storing
      std::cerr << ", serving the other ranks " << fmt(1e3 * s.serve_seconds / (stored_here - s.by_rank[0]), 3)
                << " ms a medium of theirs";
    std::cerr << "\n";
  }
  return progress.exit_code();
}

}  // namespace softdrop::cli
