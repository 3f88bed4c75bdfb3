#pragma once
// What `softdrop optimize` needs for one search and for islands alike: its arguments, the
// parameters stored with a run, the start, a resumed run, the drive's options, the events a host
// hears and the summary's delivery.

#include <CLI/CLI.hpp>
#include <atomic>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "cli/common_options.hpp"
#include "cli/host.hpp"
#include "cli/output.hpp"
#include "optimizer/islands.hpp"
#include "softdrop/search.hpp"
#include "softdrop/service.hpp"
#include "softdrop/store.hpp"

namespace softdrop::cli {

/// Where the program tells of a search: the history file it names, the lines on stderr (none with
/// `quiet`; `verbose` adds the speculation's), and the summary (`format` table or json on stdout,
/// and `json_file` if not empty).
struct SearchOutput {
  std::string db = "softdrop.db";
  bool quiet = false;
  bool verbose = false;
  std::string format = "table";
  std::string json_file;
};

/// The options of `softdrop optimize`. The constructor takes the program's defaults
/// (default_search_run: the default scene and the measured best strategy); SearchOptions{} itself
/// stays the paper's algorithm.
struct OptimizeArgs {
  SearchOutput out;
  std::int64_t resume = 0;         ///< run id to continue (0: start a new run)
  std::int64_t generations = 200;  ///< run up to this generation number
  double time_limit = 0;           ///< wall seconds, 0: none
  int threads = 0;
  bool no_speculation = false;  ///< evaluate one generation at a time
  int lanes = 0;                ///< candidates each thread steps together (DriveOptions::lanes)
  int start_attempts = 100;     ///< random starting media tried until the droplet passes
  SearchOptions search;
  IslandOptions islands;  ///< islands > 1: the island model (islands.hpp)
  /// Islands: each starts from a generated medium of its own (island i's medium seed is
  /// derive_seed(medium seed, i)) instead of all from one: restarts that sample starting media.
  bool own_island_starts = false;
  MediumArgs medium;
  std::string preset;         ///< "paper": the paper's algorithm for the search options not given
  int validate_starts = 200;  ///< at the end, the best's held-out value over this many starts (0: none)
  /// The stored keys given on the command line or in a config file, and those the preset set:
  /// SearchRun::given, each compared with the stored run's on resume.
  std::vector<std::string> given;

  OptimizeArgs();
};

/// The options of --objective on the search group `g`: --objective, --starts, --quantile,
/// --se-factor and --margin.
void add_objective_options(CLI::Option_group* g, OptimizeArgs& args);
/// How a new run's first arrangement is made, from the command line (the medium's names read,
/// not yet checked).
SearchStart start_of(const OptimizeArgs& args);
/// The library's run of one search (softdrop/service.hpp) for these options, with args.given as
/// its given keys; `command` (nullptr: none parsed) tells whether --generations was given.
SearchRun search_run_of(const OptimizeArgs& args, const CLI::App* command);
/// The summary's JSON of a stored held-out value; `objective` is NaN but for a robust objective.
nlohmann::json held_out_json(const ValidationRecord& record, double objective);
/// The summary's line for validate_best's JSON (nothing for null).
void print_held_out(std::ostream& out, const nlohmann::json& held_out);

/// What the program's observers of a search share: the lines of a refused start and of the end's
/// validation on stderr (unless quiet), and Ctrl-C when no host handles the signals itself
/// (`interrupt`: what the first Ctrl-C says).
class ProgramSearchObserver : public SearchObserver {
 public:
  ProgramSearchObserver(const SearchOutput& out, Host* host, const char* interrupt);
  void start_refused(int attempt, const std::string& why) override;
  void validating(int done, int total) override;
  const std::atomic<bool>* stop_flag() override { return signals_ ? signals_->flag() : nullptr; }
  int exit_code() const { return signals_ ? signals_->exit_code() : 0; }

 protected:
  const SearchOutput& out_;
  Host* host_;

 private:
  std::optional<StopOnSignal> signals_;  // a host handles the signals itself
  std::optional<Progress> validation_;
};

/// What a host hears after each generation of run `run` (see Host): its number, kind, kept
/// candidate, candidates, seconds, the best T and its generation, and the target generation.
nlohmann::json generation_event(std::int64_t run, const Generation& g, const Configuration& best, std::int64_t target);

/// The summary `j` written to the json file, handed to a host, or printed with format json; false
/// when it is still to be printed as a table.
bool deliver_summary(const SearchOutput& out, const nlohmann::json& j, Host* host);
/// The summary of a search's run (deliver_summary's, or a table on stdout).
void report_optimize(const SearchOutput& out, const SearchRunSummary& summary, Host* host);

/// The program's run of a search, of one or of islands (driven on `ranks`, the MPI ranks; nullptr:
/// this process's threads): run_search with the program's lines on stderr and its summary, or with
/// a host, the host's events and the summary handed to it. Returns the exit code (130 or 143 after
/// a signal the program handled, else 0).
int run_search_run(const SearchRun& run, const SearchOutput& out, Host* host, const IslandsDrive* ranks);

}  // namespace softdrop::cli
