// sweep-merge: sweep stores (shards, or copies of one sweep) merged into one, every unit checked
// against its other copies before anything is written.
#include "cli/sweep_merge_command.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "cli/output.hpp"
#include "softdrop/store.hpp"
#include "store/params_json.hpp"

namespace softdrop::cli {

namespace {

// A store older than version 9 did not record shaken_at and route_tortuosity (NaN): compared
// only where both stores hold them.
bool same_if_both(double a, double b) { return std::isnan(a) || std::isnan(b) || a == b; }

bool same_droplet(const SweepDroplet& p, const SweepDroplet& q) {
  return p.droplet == q.droplet && p.start_x == q.start_x && p.outcome == q.outcome && p.tortuosity == q.tortuosity &&
         p.steps == q.steps && same_if_both(p.shaken_at, q.shaken_at) &&
         same_if_both(p.route_tortuosity, q.route_tortuosity);
}

// Equal, or both NaN ("never").
bool same_time(double a, double b) { return a == b || (std::isnan(a) && std::isnan(b)); }

// A medium stored twice (by two shards, or two runs of one sweep) must be the same record to the
// bit: determinism makes it so. Only the wall seconds may differ.
bool same_medium(const SweepMedium& x, const SweepMedium& y) {
  bool equal = x.target_porosity == y.target_porosity && x.porosity == y.porosity && x.grains == y.grains &&
               x.medium_seed == y.medium_seed && x.passed == y.passed && x.stuck == y.stuck && x.timeout == y.timeout &&
               x.diverged == y.diverged && x.mean_t == y.mean_t && x.standard_error == y.standard_error &&
               x.stuck_fraction == y.stuck_fraction && x.droplets.size() == y.droplets.size() &&
               x.second_droplets.size() == y.second_droplets.size();
  for (std::size_t i = 0; equal && i < x.droplets.size(); ++i) equal = same_droplet(x.droplets[i], y.droplets[i]);
  for (std::size_t i = 0; equal && i < x.second_droplets.size(); ++i) {
    const SweepSecond &p = x.second_droplets[i], &q = y.second_droplets[i];
    equal = same_droplet(p.run, q.run) && p.released_at == q.released_at &&
            same_time(p.first_held_at, q.first_held_at) && same_time(p.held_at, q.held_at) &&
            p.contact_steps == q.contact_steps && p.shared_touched == q.shared_touched;
  }
  return equal;
}

// One sweep of one input store, read whole.
struct MergeSource {
  std::string path;
  SweepRecord record;
  SweepOptions options;
  std::vector<SweepMedium> media;
};

// Runs f, naming a store the store's errors call "--db 'PATH'" as the merge's option names it
// (an input, or --into).
template <class F>
auto naming(const std::string& option, F&& f) -> decltype(f()) {
  try {
    return f();
  } catch (const DatabaseError& e) {
    const std::string what = e.what();
    throw DatabaseError(what.rfind("--db '", 0) == 0 ? option + what.substr(4) : what);
  }
}

}  // namespace

void add_sweep_merge_command(CLI::App& app, SweepMergeArgs& m) {
  CLI::App* mg =
      app.add_subcommand("sweep-merge", "Merge sweep stores (e.g. shards) into one; identical units must agree");
  mg->add_option("--into", m.into, "The store to merge into (created if missing)")->required();
  mg->add_option("inputs", m.inputs, "Stores to merge from")->required()->check(CLI::ExistingFile);
}

int run_sweep_merge(const SweepMergeArgs& a) {
  // Every input is read and checked against the others and against the output before anything is
  // written: a refused merge leaves the output as it was, and creates none.
  std::vector<MergeSource> sources;
  for (const std::string& path : a.inputs)
    naming("input", [&] {
      auto in = open_sweep_store(path, OpenMode::read_only);
      for (const SweepRecord& r : in->sweeps()) {
        SweepOptions o;
        try {
          o = sweep_params_from_json(r.params);
        } catch (const std::exception& e) {
          throw std::runtime_error("sweep-merge: '" + path + "' sweep " + std::to_string(r.id) + ": " + e.what());
        }
        sources.push_back({path, r, o, in->media(r.id)});
      }
    });
  // Each unit of each sweep (by its parameters) as first found: in the output, then in the inputs.
  std::map<std::string, std::map<std::pair<int, int>, std::pair<SweepMedium, std::string>>> known;
  auto check_against_known = [&](const std::string& params, const SweepMedium& m, const std::string& origin,
                                 std::int64_t sweep) {
    auto& units = known[params];
    const auto [at, fresh] = units.try_emplace({m.unit.porosity, m.unit.medium}, m, origin);
    if (!fresh && !same_medium(at->second.first, m))
      throw std::runtime_error("sweep-merge: '" + origin + "' sweep " + std::to_string(sweep) + " porosity " +
                               std::to_string(m.unit.porosity) + " medium " + std::to_string(m.unit.medium) +
                               " differs from the copy in '" + at->second.second +
                               "' (made by another build, or edited?); nothing was written");
  };
  if (std::filesystem::exists(a.into)) {
    naming("--into", [&] {
      auto out = open_sweep_store(a.into, OpenMode::read_only);
      for (const SweepRecord& r : out->sweeps())
        for (const SweepMedium& m : out->media(r.id)) check_against_known(r.params, m, a.into, r.id);
    });
  } else {
    naming("--into", [&] { check_database(a.into); });  // a new file: its folder must exist and be writable
  }
  for (const MergeSource& s : sources)
    for (const SweepMedium& m : s.media) check_against_known(s.record.params, m, s.path, s.record.id);

  auto out = open_sweep_store(a.into, OpenMode::create);
  for (const MergeSource& s : sources) {
    const std::int64_t id = out->find_or_create(s.record.params, s.options);
    const std::vector<SweepUnit> have = out->done_units(id);
    long added = 0;
    for (const SweepMedium& m : s.media)
      if (std::find(have.begin(), have.end(), m.unit) == have.end() && out->add(id, m)) ++added;
    const SweepRecord merged = out->sweep(id);
    out->set_status(id, merged.done == merged.units ? "complete" : "running");
    std::cerr << "sweep-merge: " << s.path << " sweep " << s.record.id << ": " << added << " media added; sweep " << id
              << " in " << a.into << " has " << merged.done << " of " << merged.units << "\n";
  }
  return 0;
}

}  // namespace softdrop::cli
