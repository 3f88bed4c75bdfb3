// `softdrop optimize --islands K`: K searches of one archipelago, each a run of the history
// (runs.island, runs.archipelago = the first run's id); `--resume` of any of them continues all.
#include "cli/islands_command.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <iostream>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "cli/output.hpp"
#include "service/search_start.hpp"
#include "softdrop/medium.hpp"
#include "softdrop/version.hpp"

namespace softdrop::cli {
namespace {

// The program's observer of islands: the lines on stderr (each start, then the progress at most
// once a second on a terminal, every 10 s otherwise), the host's callback with each island's
// generations (the Python module's), and Ctrl-C when no host handles the signals itself.
class IslandsLines : public ProgramSearchObserver {
 public:
  IslandsLines(const SearchOutput& out, Host* host)
      : ProgramSearchObserver(out, host,
                              "\nsoftdrop: stopping after the generations in flight (Ctrl-C again to drop them)\n"),
        tty_(::isatty(2) != 0) {}
  void islands_started(const std::vector<std::int64_t>& runs, const std::vector<std::int64_t>& from,
                       const std::vector<Configuration>& starts, std::int64_t target, bool resumed) override {
    runs_ = runs, last_ = from, target_ = target;
    for (std::size_t i = 0; i < runs.size(); ++i) best_of_.push_back(starts[starts.size() == 1 ? 0 : i]);
    if (out_.quiet) return;
    if (resumed) {
      std::cerr << "optimize: resuming the " << runs.size() << " islands of run " << runs.front() << " in " << out_.db
                << "\n";
      return;
    }
    const bool each = starts.size() > 1;
    for (std::size_t s = 0; s < starts.size(); ++s)
      std::cerr << "optimize: " << (each ? "island " + std::to_string(s) + " of " : std::string()) << runs.size()
                << " islands, runs " << runs.front() << " to " << runs.back() << " in " << out_.db << ": "
                << starts[s].medium.grains.size() << " grains, porosity " << fmt(exact_porosity(starts[s].medium), 6)
                << ", T0 = " << fmt(starts[s].eval.tortuosity, 8) << "\n";
  }
  bool generation(std::int64_t run, int island, const Generation& g, const Configuration& best,
                  std::int64_t target) override {
    const auto i = static_cast<std::size_t>(island);
    last_[i] = g.number;
    best_of_[i] = best;
    evaluations_ += static_cast<std::int64_t>(g.candidates.size());
    update(false);
    if (!host_ || !host_->on_progress) return true;
    nlohmann::json event = generation_event(run, g, best, target);
    event["island"] = island;
    return host_->on_progress(event);
  }
  void update(bool force) {
    if (out_.quiet || last_.empty()) return;
    const auto now = clock::now();
    if (!force && now - shown_ < (tty_ ? std::chrono::seconds(1) : std::chrono::seconds(10))) return;
    shown_ = now;
    const std::int64_t lowest = *std::min_element(last_.begin(), last_.end());
    const std::size_t top = best_island(best_of_);
    const double s = std::chrono::duration<double>(now - t0_).count();
    std::ostringstream line;
    line << "optimize: " << last_.size() << " islands at generation " << lowest << "/" << target_ << "  best T "
         << fmt(best_of_[top].eval.tortuosity, 8) << " (island " << top << ")  "
         << fmt(s > 0 ? static_cast<double>(evaluations_) / s : 0.0, 3) << " eval/s";
    std::cerr << (tty_ ? "\r" : "") << line.str() << (tty_ && !force ? "\033[K" : "\n") << std::flush;
  }

 private:
  using clock = std::chrono::steady_clock;
  bool tty_;
  std::vector<std::int64_t> runs_, last_;
  std::vector<Configuration> best_of_;
  std::int64_t target_ = 0, evaluations_ = 0;
  clock::time_point t0_ = clock::now(), shown_ = t0_;
};

}  // namespace

int run_islands(const SearchOutput& out, const SearchRun& run, Host* host, const IslandsDrive* drive) {
  IslandsLines lines(out, host);
  const SearchRunSummary s = run_search(run, lines, drive);
  lines.update(true);
  const SearchSummary& summary = s.drive;
  nlohmann::json per_island = nlohmann::json::array();
  for (std::size_t i = 0; i < s.islands.size(); ++i)
    per_island.push_back({{"island", i},
                          {"run", s.islands[i].run},
                          {"last_generation", s.islands[i].last_generation},
                          {"best_tortuosity", s.islands[i].best.eval.tortuosity},
                          {"best_generation", s.islands[i].best.generation}});
  const auto top = static_cast<std::size_t>(s.best_island);
  const std::int64_t first = s.islands.front().run, final_run = s.islands.back().run, best_run = s.islands[top].run;
  const nlohmann::json held_out = s.held_out ? held_out_json(*s.held_out, s.held_out_objective) : nlohmann::json();
  nlohmann::json j{{"version", kVersion},
                   {"db", out.db},
                   {"run", first},
                   {"strategy", to_string(s.search.strategy.kind)},
                   {"islands", per_island},
                   {"migrate_every", s.migrate_every},
                   {"migration", s.migration},
                   {"termination", to_string(summary.termination)},
                   {"message", summary.message},
                   {"last_generation", summary.last_generation},
                   {"generations_run", summary.generations_run},
                   {"evaluations", summary.evaluations + s.initial_evaluations},
                   {"accepted", summary.accepted},
                   {"best_tortuosity", summary.best_t},
                   {"best_island", top},
                   {"best_run", best_run},
                   {"held_out", held_out},
                   {"wall_seconds", summary.seconds},
                   {"evaluations_per_second", summary.evaluations_per_second()}};
  if (!deliver_summary(out, j, host)) {
    std::cout << "runs         " << first << " to " << final_run << " in " << out.db << " (" << s.islands.size()
              << " islands, "
              << (s.migrate_every > 0
                      ? s.migration + " migration every " + std::to_string(s.migrate_every) + " generations"
                      : std::string("no migration"))
              << ")\n"
              << "stopped      " << summary.message << "\n"
              << "best T       " << fmt(summary.best_t, 10) << " (island " << top << ", run " << best_run
              << ", generation " << s.best.generation << ")\n"
              << "this session " << summary.generations_run << " generations, " << summary.accepted << " accepted, "
              << summary.evaluations + s.initial_evaluations << " evaluations, "
              << fmt(summary.evaluations_per_second(), 3) << " eval/s\n";
    print_held_out(std::cout, held_out);
  }
  return summary.termination == Termination::interrupted ? lines.exit_code() : 0;
}

}  // namespace softdrop::cli
