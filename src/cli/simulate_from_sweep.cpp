// simulate --from-sweep DB --sweep-droplet P:M:D: one droplet of a stored sweep, run again as the
// sweep ran it (simulate_command.hpp).
#include <algorithm>
#include <filesystem>
#include <iostream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli/file_roles.hpp"
#include "cli/output.hpp"
#include "cli/simulate_command.hpp"
#include "cli/sweep_report_command.hpp"
#include "service/sweep_droplet.hpp"
#include "softdrop/store.hpp"

namespace softdrop::cli {
namespace {

// The options a sweep's droplet leaves to the user: what a run records and writes, and how.
constexpr const char* kStillFree[] = {"--from-sweep", "--sweep-droplet",  "--sweep-id",    "--runs",
                                      "--paths",      "--path-interval",  "--trace",       "--trace-interval",
                                      "--snapshots",  "--snapshot-times", "--format",      "--json",
                                      "--quiet",      "--threads",        "--save-medium", "--help"};

// "P:M:D" as three indices.
void parse_droplet(const std::string& text, int* p, int* m, int* d) {
  std::vector<int> parts;
  std::size_t start = 0;
  try {
    for (;;) {
      const std::size_t colon = text.find(':', start);
      const std::string part = text.substr(start, colon == std::string::npos ? std::string::npos : colon - start);
      std::size_t used = 0;
      parts.push_back(std::stoi(part, &used));
      if (used != part.size() || part.empty()) throw std::invalid_argument(part);
      if (colon == std::string::npos) break;
      start = colon + 1;
    }
  } catch (const std::exception&) {
    parts.clear();
  }
  if (parts.size() != 3)
    throw std::invalid_argument("sweep-droplet = '" + text +
                                "': expected P:M:D, three whole numbers (porosity_index:medium_index:droplet)");
  *p = parts[0], *m = parts[1], *d = parts[2];
}

}  // namespace

void take_sweep_droplet(SimulateArgs& a, const CLI::App& command) {
  if (a.from_sweep.empty() && a.sweep_droplet.empty()) return;
  if (a.from_sweep.empty()) throw std::invalid_argument("sweep-droplet: has no effect without --from-sweep DB");
  if (a.sweep_droplet.empty()) throw std::invalid_argument("from-sweep: --sweep-droplet P:M:D names the droplet");
  std::vector<const CLI::Option*> options;
  options_of(command, &options);
  for (const CLI::Option* o : options) {
    const std::string name = o->get_name();
    if (o->count() > 0 &&
        std::none_of(std::begin(kStillFree), std::end(kStillFree), [&](const char* free) { return name == free; }))
      throw std::invalid_argument(name.substr(std::min(name.find_first_not_of('-'), name.size())) +
                                  ": the sweep's droplet sets it (--from-sweep); leave it out");
  }
  int p = 0, m = 0, d = 0;
  parse_droplet(a.sweep_droplet, &p, &m, &d);
  if (!std::filesystem::exists(a.from_sweep))
    throw std::invalid_argument("--from-sweep '" + a.from_sweep + "': no such file");
  auto store = open_sweep_store(a.from_sweep, OpenMode::read_only);
  if (a.sweep_id > 0) {
    const auto sweeps = store->sweeps();
    if (std::none_of(sweeps.begin(), sweeps.end(), [&](const SweepRecord& r) { return r.id == a.sweep_id; }))
      throw std::invalid_argument("sweep-id = " + std::to_string(a.sweep_id) + ": '" + a.from_sweep +
                                  "' has no such sweep (softdrop sweep-report --db " + a.from_sweep + " lists them)");
  }
  const StoredSweepDroplet s =
      stored_sweep_droplet(*store, a.from_sweep, pick_sweep(*store, a.sweep_id, a.from_sweep), p, m, d);
  a.medium.file.clear();
  a.medium.options = s.medium;
  a.medium.kind = to_string(s.medium.kind);
  a.medium.radii = to_string(s.medium.radii);
  a.medium.walls = !s.medium.periodic;
  a.droplet = s.options.droplet;
  RunOptions run = s.options.run;  // its exit tests; what to record is this run's own
  run.path_interval = a.run.path_interval;
  run.area_interval = a.run.area_interval;
  run.snapshot_times = a.run.snapshot_times;
  a.run = run;
  a.x0 = s.droplet.start_x;
  a.batch.droplets = 1;
  if (!a.quiet)
    std::cerr << "simulate: droplet " << a.sweep_droplet << " of sweep " << s.sweep << " in '" << a.from_sweep
              << "', stored as " << to_string(s.droplet.outcome)
              << (s.droplet.outcome == Outcome::passed ? ", T = " + fmt(s.droplet.tortuosity, 17) : std::string())
              << ", " << s.droplet.steps << " steps\n";
}

}  // namespace softdrop::cli
