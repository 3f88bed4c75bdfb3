#include "cli/mpi_islands.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <exception>
#include <string>
#include <utility>

#include "optimizer/strategy.hpp"
#include "store/params_json.hpp"
#include "util/byte_codec.hpp"

namespace softdrop::cli {
namespace {

using detail::ByteReader;
using detail::ByteWriter;

// Message tags (the decisions go by broadcast).
constexpr int kStart = 11;       // 0 -> rank: its islands, as they start
constexpr int kRecords = 12;     // rank -> 0: its islands' generations of a stretch
constexpr int kImmigrants = 13;  // 0 -> rank: each of its islands' immigrant
constexpr int kMigrated = 14;    // rank -> 0: its islands' migration generations

void put(ByteWriter& w, const Medium& m) {
  w.put(m.width), w.put(m.height), w.put(static_cast<std::uint8_t>(m.periodic)), w.put_vector(m.grains);
}
Medium get_medium(ByteReader& r) {
  Medium m;
  m.width = r.get<double>(), m.height = r.get<double>(), m.periodic = r.get<std::uint8_t>() != 0;
  m.grains = r.get_vector<Grain>();
  return m;
}
void put(ByteWriter& w, const Evaluation& e) {
  w.put(static_cast<std::int32_t>(e.outcome)), w.put_string(e.reason), w.put(e.tortuosity), w.put(e.steps);
  w.put_vector(e.touched), w.put_vector(e.path_x), w.put_vector(e.path_y), w.put(e.seconds);
  w.put(e.droplets), w.put(e.passed), w.put_vector(e.values);
}
Evaluation get_evaluation(ByteReader& r) {
  Evaluation e;
  const auto outcome = r.get<std::int32_t>();
  if (outcome < 0 || outcome > static_cast<std::int32_t>(Outcome::diverged)) r.fail("bad outcome");
  e.outcome = static_cast<Outcome>(outcome);
  e.reason = r.get_string(), e.tortuosity = r.get<double>(), e.steps = r.get<std::int64_t>();
  e.touched = r.get_vector<std::int32_t>(), e.path_x = r.get_vector<double>(), e.path_y = r.get_vector<double>();
  e.seconds = r.get<double>();
  e.droplets = r.get<int>(), e.passed = r.get<int>(), e.values = r.get_vector<double>();
  return e;
}
void put(ByteWriter& w, const Configuration& c) { w.put(c.generation), put(w, c.medium), put(w, c.eval); }
Configuration get_configuration(ByteReader& r) {
  Configuration c;
  c.generation = r.get<std::int64_t>();
  c.medium = get_medium(r);
  c.eval = get_evaluation(r);
  return c;
}
MoveKind get_kind(ByteReader& r) {
  const auto k = r.get<std::int32_t>();
  if (k < 0 || k > static_cast<std::int32_t>(MoveKind::mixed)) r.fail("bad move kind");
  return static_cast<MoveKind>(k);
}
void put(ByteWriter& w, const Generation& g) {
  w.put(g.number), w.put(static_cast<std::int32_t>(g.kind)), w.put<std::uint64_t>(g.candidates.size());
  for (const Candidate& c : g.candidates) {
    w.put(c.index), w.put(static_cast<std::int32_t>(c.kind)), w.put(c.moved_grain), w.put(c.moved);
    put(w, c.medium), put(w, c.eval);
  }
  w.put(g.accepted), w.put(g.best_t), w.put(g.touched), w.put(g.seconds), w.put_string(g.state);
  put(w, g.parent);
}
Generation get_generation(ByteReader& r) {
  Generation g;
  g.number = r.get<std::int64_t>();
  g.kind = get_kind(r);
  const auto n = r.get<std::uint64_t>();
  if (n > 1u << 20) r.fail("too many candidates");
  for (std::uint64_t i = 0; i < n; ++i) {
    Candidate c;
    c.index = r.get<int>(), c.kind = get_kind(r), c.moved_grain = r.get<int>(), c.moved = r.get<int>();
    c.medium = get_medium(r), c.eval = get_evaluation(r);
    g.candidates.push_back(std::move(c));
  }
  g.accepted = r.get<int>(), g.best_t = r.get<double>(), g.touched = r.get<int>(), g.seconds = r.get<double>();
  g.state = r.get_string();
  g.parent = get_evaluation(r);
  return g;
}

// One island's generation, as sent to rank 0.
struct Record {
  int island = 0;
  Generation generation;
  Configuration best;
};
std::string encode(const std::vector<Record>& records) {
  ByteWriter w;
  w.put<std::uint64_t>(records.size());
  for (const Record& rec : records) w.put(rec.island), put(w, rec.generation), put(w, rec.best);
  return w.out;
}
std::vector<Record> decode_records(const std::string& bytes) {
  ByteReader r(bytes, "island records");
  std::vector<Record> out(static_cast<std::size_t>(std::min<std::uint64_t>(r.get<std::uint64_t>(), bytes.size())));
  for (Record& rec : out)
    rec.island = r.get<int>(), rec.generation = get_generation(r), rec.best = get_configuration(r);
  if (!r.at_end()) r.fail("trailing bytes");
  return out;
}

// The islands this rank runs, with their numbers, taken to `upto` (no migration among them).
struct LocalIslands {
  std::vector<Search> searches;
  std::vector<int> number;
  SearchSummary run(std::int64_t upto, DriveOptions d,
                    const std::function<bool(int, const Generation&, const Configuration&)>& on_generation) {
    if (searches.empty()) return {};
    IslandOptions alone;
    alone.islands = static_cast<int>(searches.size());
    alone.migrate_every = 0;  // no migration among them
    d.generations = upto;
    IslandCallbacks cb;
    cb.generation = [&](int i, const Generation& g, const Configuration& best) {
      return on_generation(number[static_cast<std::size_t>(i)], g, best);
    };
    return drive_islands(searches, alone, d, cb);
  }
  Generation immigrate(int island, const Configuration& immigrant) {
    const auto at = std::find(number.begin(), number.end(), island) - number.begin();
    return searches[static_cast<std::size_t>(at)].immigrate(immigrant);
  }
  const Configuration& best(int island) const {
    return searches[static_cast<std::size_t>(std::find(number.begin(), number.end(), island) - number.begin())].best();
  }
};

}  // namespace

SearchSummary drive_islands_on_ranks(const Job& job, std::vector<Search>& islands, const IslandOptions& io,
                                     const DriveOptions& options, const IslandCallbacks& callbacks) {
  const auto t0 = std::chrono::steady_clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };
  const int k = io.islands, ranks = job.size();
  std::vector<std::int64_t> last(static_cast<std::size_t>(k));
  std::vector<Configuration> bests(static_cast<std::size_t>(k));
  LocalIslands local;
  std::vector<ByteWriter> start(static_cast<std::size_t>(ranks));
  for (int i = 0; i < k; ++i) {
    Search& s = islands[static_cast<std::size_t>(i)];
    last[static_cast<std::size_t>(i)] = s.last_generation();
    bests[static_cast<std::size_t>(i)] = s.best();
    ByteWriter& w = start[static_cast<std::size_t>(i % ranks)];
    w.put(i), w.put_string(search_params_to_json(s.options())), w.put(s.last_generation());
    put(w, s.best()), put(w, s.strategy().current()), w.put_string(s.strategy().state());
  }
  SearchSummary sum;
  bool stop_by_callback = false;
  auto report = [&](int i, const Generation& g, const Configuration& best) {
    last[static_cast<std::size_t>(i)] = g.number;
    if (best.generation != bests[static_cast<std::size_t>(i)].generation) bests[static_cast<std::size_t>(i)] = best;
    ++sum.generations_run;
    if (g.kind != MoveKind::migrate) sum.evaluations += static_cast<std::int64_t>(g.candidates.size());
    if (g.accepted >= 0) ++sum.accepted;
  };
  try {
    for (int r = 1; r < ranks; ++r) mpi::send(r, kStart, start[static_cast<std::size_t>(r)].out);
    for (int i = 0; i < k; i += ranks)
      local.searches.push_back(std::move(islands[static_cast<std::size_t>(i)])), local.number.push_back(i);
    for (;;) {
      const std::int64_t from = *std::min_element(last.begin(), last.end());
      const std::int64_t next = io.next_stop(from, options.generations);
      int code = 1 + (next <= options.generations ? 1 : 0);  // 1: a stretch, 2: a stretch and a migration
      if (from >= options.generations)
        code = 0, sum.termination = Termination::generations;
      else if (stop_by_callback)
        code = 0, sum.termination = Termination::callback;
      else if (options.stop && options.stop->load())
        code = 0, sum.termination = Termination::interrupted;
      else if (options.time_limit > 0 && elapsed() >= options.time_limit)
        code = 0, sum.termination = Termination::time_limit;
      std::vector<int> decision{code, static_cast<int>(next)};
      mpi::broadcast(decision);
      if (code == 0) break;
      DriveOptions d = options;
      if (options.time_limit > 0) d.time_limit = std::max(1e-9, options.time_limit - elapsed());
      local.run(next - 1, d, [&](int i, const Generation& g, const Configuration& best) {
        report(i, g, best);
        if (callbacks.generation && !callbacks.generation(i, g, best)) stop_by_callback = true;
        return !stop_by_callback;
      });
      for (int r = 1; r < ranks; ++r)
        for (const Record& rec : decode_records(mpi::receive(r, kRecords))) {
          report(rec.island, rec.generation, rec.best);
          if (callbacks.generation && !callbacks.generation(rec.island, rec.generation, rec.best))
            stop_by_callback = true;
        }
      // The migration, once every island has reached the generation before it.
      std::vector<int> migrate{code == 2 && *std::min_element(last.begin(), last.end()) == next - 1 ? 1 : 0};
      mpi::broadcast(migrate);
      if (migrate[0] == 0) continue;
      std::vector<const Configuration*> pointers;
      for (const Configuration& b : bests) pointers.push_back(&b);
      const std::vector<const Configuration*> in = immigrants(pointers, io.migration);
      std::vector<ByteWriter> out(static_cast<std::size_t>(ranks));
      for (int i = 0; i < k; ++i)
        out[static_cast<std::size_t>(i % ranks)].put(i),
            put(out[static_cast<std::size_t>(i % ranks)], *in[static_cast<std::size_t>(i)]);
      for (int r = 1; r < ranks; ++r) mpi::send(r, kImmigrants, out[static_cast<std::size_t>(r)].out);
      std::vector<Generation> gs(static_cast<std::size_t>(k));
      std::vector<Configuration> after = bests;
      for (std::size_t j = 0; j < local.number.size(); ++j) {
        const int i = local.number[j];
        gs[static_cast<std::size_t>(i)] = local.immigrate(i, *in[static_cast<std::size_t>(i)]);
        after[static_cast<std::size_t>(i)] = local.best(i);
      }
      for (int r = 1; r < ranks; ++r)
        for (Record& rec : decode_records(mpi::receive(r, kMigrated))) {
          gs[static_cast<std::size_t>(rec.island)] = std::move(rec.generation);
          after[static_cast<std::size_t>(rec.island)] = std::move(rec.best);
        }
      for (int i = 0; i < k; ++i) report(i, gs[static_cast<std::size_t>(i)], after[static_cast<std::size_t>(i)]);
      if (callbacks.migration && !callbacks.migration(gs, after)) stop_by_callback = true;
    }
  } catch (const std::exception& e) {
    job.fail(e);
  }
  for (std::size_t j = 0; j < local.number.size(); ++j)  // rank 0's islands back where they were
    islands[static_cast<std::size_t>(local.number[j])] = std::move(local.searches[j]);
  sum.message = std::string(to_string(sum.termination)) + " with the islands at generations " +
                std::to_string(*std::min_element(last.begin(), last.end())) + " and above";
  if (sum.termination == Termination::generations)
    sum.message = "reached generation " + std::to_string(options.generations);
  sum.last_generation = *std::min_element(last.begin(), last.end());
  sum.best_t = bests[0].eval.tortuosity;
  for (const Configuration& b : bests) sum.best_t = std::max(sum.best_t, b.eval.tortuosity);
  sum.seconds = elapsed();
  return sum;
}

void work_on_islands(const Job& job, int threads, int lanes, bool speculate) {
  try {
    LocalIslands local;
    {
      const std::string bytes = mpi::receive(0, kStart);
      ByteReader r(bytes, "island start");
      while (!r.at_end()) {
        const int i = r.get<int>();
        const SearchOptions o = search_params_from_json(r.get_string());
        const auto generation = r.get<std::int64_t>();
        Configuration best = get_configuration(r), current = get_configuration(r);
        const std::string state = r.get_string();
        local.searches.emplace_back(o, std::move(best), std::move(current), state, generation);
        local.number.push_back(i);
      }
    }
    DriveOptions d;
    d.threads = threads, d.lanes = lanes, d.speculate = speculate;
    for (;;) {
      std::vector<int> decision;
      mpi::broadcast(decision);
      if (decision.at(0) == 0) break;
      std::vector<Record> records;
      local.run(decision.at(1) - 1, d, [&](int i, const Generation& g, const Configuration& best) {
        records.push_back({i, g, best});
        return true;
      });
      mpi::send(0, kRecords, encode(records));
      std::vector<int> migrate;
      mpi::broadcast(migrate);
      if (migrate.at(0) == 0) continue;
      const std::string bytes = mpi::receive(0, kImmigrants);
      ByteReader r(bytes, "immigrants");
      std::vector<Record> migrated;
      while (!r.at_end()) {
        const int i = r.get<int>();
        const Configuration immigrant = get_configuration(r);
        Generation g = local.immigrate(i, immigrant);
        migrated.push_back({i, std::move(g), local.best(i)});
      }
      mpi::send(0, kMigrated, encode(migrated));
    }
  } catch (const std::exception& e) {
    job.fail(e);
  }
}

}  // namespace softdrop::cli
