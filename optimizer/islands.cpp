#include "islands.hpp"

#include <algorithm>
#include <chrono>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <thread>

#include "util/enum_names.hpp"
#include "util/random.hpp"
#include "util/validation.hpp"
#include "util/worker_threads.hpp"

namespace softdrop {

constexpr detail::EnumName<Migration> kMigrations[] = {{Migration::ring, "ring"}, {Migration::broadcast, "broadcast"}};

const char* to_string(Migration migration) { return detail::name_of(kMigrations, migration); }

Migration parse_migration(const std::string& name) { return detail::parse_name(kMigrations, name, "migration"); }

std::vector<std::string> migration_names() { return detail::name_list(kMigrations); }

bool IslandOptions::IsValid(std::string* why) const {
  if (islands < 1 || islands > 1024)
    return detail::fail(why, "islands = " + std::to_string(islands) + ": must be in [1, 1024]");
  if (migrate_every < 0 || migrate_every == 1)
    return detail::fail(why, "migrate-every = " + std::to_string(migrate_every) + ": must be 0 (never) or >= 2");
  return true;
}

std::int64_t IslandOptions::next_migration(std::int64_t after) const {
  if (islands <= 1 || migrate_every <= 0) return std::numeric_limits<std::int64_t>::max();
  return (after / migrate_every + 1) * migrate_every;
}

std::int64_t IslandOptions::next_stop(std::int64_t after, std::int64_t generations) const {
  return std::min(next_migration(after), generations + 1);
}

SearchOptions island_search_options(const SearchOptions& options, int island) {
  SearchOptions o = options;
  o.seed = derive_seed(options.seed, static_cast<std::uint64_t>(island));
  return o;
}

bool is_migration(std::int64_t generation, const IslandOptions& options) {
  return options.islands > 1 && options.migrate_every > 0 && generation >= 1 && generation % options.migrate_every == 0;
}

std::vector<const Configuration*> immigrants(const std::vector<const Configuration*>& bests, Migration migration) {
  const std::size_t k = bests.size();
  std::vector<const Configuration*> in(k);
  std::size_t top = 0;
  for (std::size_t i = 1; i < k; ++i)
    if (bests[i]->eval.tortuosity > bests[top]->eval.tortuosity) top = i;
  for (std::size_t i = 0; i < k; ++i) in[i] = migration == Migration::ring ? bests[(i + k - 1) % k] : bests[top];
  return in;
}

SearchSummary drive_islands(std::vector<Search>& islands, const IslandOptions& io, const DriveOptions& options,
                            const IslandCallbacks& callbacks) {
  std::string why;
  if (!io.IsValid(&why) || !options.IsValid(&why)) throw std::invalid_argument(why);
  if (static_cast<int>(islands.size()) != io.islands)
    throw std::invalid_argument("islands = " + std::to_string(io.islands) + ": " + std::to_string(islands.size()) +
                                " searches given");
  const auto t0 = std::chrono::steady_clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };
  const int k = io.islands;
  const int workers = detail::worker_threads(options.threads);
  const int runners = std::min(k, workers);
  SearchSummary s;
  std::atomic<bool> stop{false};
  std::atomic<bool> callback_stopped{false};
  std::mutex reporting;  // one generation callback at a time; also guards s's counters
  auto lowest = [&] {
    std::int64_t g = islands[0].last_generation();
    for (const Search& i : islands) g = std::min(g, i.last_generation());
    return g;
  };
  for (;;) {
    const std::int64_t from = lowest();
    if (from >= options.generations) {
      s.termination = Termination::generations;
      s.message = "reached generation " + std::to_string(options.generations);
      break;
    }
    if (options.stop && options.stop->load()) {
      s.termination = Termination::interrupted;
      s.message = "interrupted after generation " + std::to_string(from);
      break;
    }
    if (options.time_limit > 0 && elapsed() >= options.time_limit) {
      s.termination = Termination::time_limit;
      s.message =
          "time limit of " + detail::num(options.time_limit) + " s reached after generation " + std::to_string(from);
      break;
    }
    // The next migration after the lowest island, if it comes before the end.
    const std::int64_t next = io.next_stop(from, options.generations);
    if (lowest() < next - 1) {  // every island up to the generation before it
      DriveOptions d = options;
      d.generations = next - 1;
      d.stop = &stop;
      d.threads = std::max(1, workers / k);
      if (options.time_limit > 0) d.time_limit = std::max(1e-9, options.time_limit - elapsed());
      std::atomic<int> next_island{0};
      std::exception_ptr error;
      auto runner = [&] {
        for (int i; (i = next_island.fetch_add(1)) < k;) {
          try {
            const SearchSummary r =
                drive(islands[static_cast<std::size_t>(i)], d, [&](const Generation& g, const Configuration& best) {
                  std::lock_guard lock(reporting);
                  ++s.generations_run;
                  s.evaluations += static_cast<std::int64_t>(g.candidates.size());
                  if (g.accepted >= 0) ++s.accepted;
                  const bool go_on = (!callbacks.generation || callbacks.generation(i, g, best)) &&
                                     !(options.stop && options.stop->load());
                  if (!go_on) callback_stopped = !(options.stop && options.stop->load()), stop = true;
                  return go_on;
                });
            if (r.termination == Termination::time_limit) stop = true;
          } catch (...) {
            std::lock_guard lock(reporting);
            if (!error) error = std::current_exception();
            stop = true;
          }
        }
      };
      std::vector<std::thread> pool;
      for (int r = 1; r < runners; ++r) pool.emplace_back(runner);
      runner();
      for (std::thread& t : pool) t.join();
      if (error) std::rethrow_exception(error);
      if (stop) {
        s.termination = callback_stopped                       ? Termination::callback
                        : options.stop && options.stop->load() ? Termination::interrupted
                                                               : Termination::time_limit;
        s.message = std::string(callback_stopped ? "stopped by a callback" : to_string(s.termination)) +
                    " with the islands at generations " + std::to_string(lowest()) + " and above";
        break;
      }
      continue;  // checks the end, the stop and the time again before the migration
    }
    // Every island is at next - 1: the migration, from the bests as they stand.
    std::vector<Configuration> bests;
    for (const Search& i : islands) bests.push_back(i.best());
    std::vector<const Configuration*> pointers;
    for (const Configuration& b : bests) pointers.push_back(&b);
    const std::vector<const Configuration*> in = immigrants(pointers, io.migration);
    std::vector<Generation> gs;
    for (int i = 0; i < k; ++i)
      gs.push_back(islands[static_cast<std::size_t>(i)].immigrate(*in[static_cast<std::size_t>(i)]));
    for (const Generation& g : gs) s.accepted += g.accepted >= 0 ? 1 : 0, ++s.generations_run;
    bests.clear();
    for (const Search& i : islands) bests.push_back(i.best());
    if (callbacks.migration && !callbacks.migration(gs, bests)) {
      s.termination = Termination::callback;
      s.message = "stopped by a callback after the migration of generation " + std::to_string(next);
      break;
    }
  }
  s.last_generation = lowest();
  s.best_t = islands[0].best().eval.tortuosity;
  for (const Search& i : islands) s.best_t = std::max(s.best_t, i.best().eval.tortuosity);
  s.seconds = elapsed();
  return s;
}

}  // namespace softdrop
