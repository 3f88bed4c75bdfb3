#pragma once
/// \file islands.hpp
/// The island model: K searches of the same options, each with a seed of its own (island i's is
/// derive_seed(seed, i)) and so a lineage of its own, run side by side. Generations whose number
/// is a multiple of migrate_every are migrations: every island takes an immigrant, another
/// island's best as of the generation before, and keeps it if it beats its own best (see
/// Search::immigrate). The islands are independent between migrations, so the histories do not
/// depend on the threads, the processes or the order the islands run in.

#include <atomic>
#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "softdrop/search.hpp"

namespace softdrop {

/// Which island's best each island takes.
enum class Migration {
  ring,      ///< island i takes island (i - 1) mod K's
  broadcast  ///< every island takes the best of all (the lowest-numbered among equals)
};
const char* to_string(Migration migration);
/// Parses "ring" / "broadcast"; throws std::invalid_argument naming the value.
Migration parse_migration(const std::string& name);
/// Every migration's name, in the enum's order.
std::vector<std::string> migration_names();

struct IslandOptions {
  int islands = 1;  ///< K
  /// Generations between migrations; 0: none, the islands are independent lineages (restarts
  /// from the same start, with seeds of their own) and the search's best is the best of them.
  int migrate_every = 50;
  Migration migration = Migration::ring;
  /// False, with the reason naming the option, for islands outside [1, 1024] or migrate_every
  /// neither 0 nor >= 2.
  bool IsValid(std::string* why) const;
  /// The first migration after generation `after` (>= 0); past every generation
  /// (std::numeric_limits<std::int64_t>::max()) for one island or migrate_every = 0.
  std::int64_t next_migration(std::int64_t after) const;
  /// The next migration after generation `after` if it comes by generation `generations`, else
  /// generations + 1: the islands drive to the generation before it, then migrate or stop.
  std::int64_t next_stop(std::int64_t after, std::int64_t generations) const;
};

/// Island i's search options: `options` with the seed derive_seed(options.seed, i).
SearchOptions island_search_options(const SearchOptions& options, int island);
/// Whether generation `generation` (>= 1) is a migration.
bool is_migration(std::int64_t generation, const IslandOptions& options);

/// The immigrant of each island, from the islands' bests (bests[i] is island i's).
std::vector<const Configuration*> immigrants(const std::vector<const Configuration*>& bests, Migration migration);

/// What the islands' drive reports as it goes.
struct IslandCallbacks {
  /// After each island's ordinary generation, one call at a time, on the thread that runs the
  /// island. False stops every island after the generation it has in flight.
  std::function<bool(int island, const Generation&, const Configuration& best)> generation;
  /// After a migration, with every island's migration generation and best after it (gs[i] and
  /// bests[i] are island i's), on the calling thread. False stops.
  std::function<bool(const std::vector<Generation>& gs, const std::vector<Configuration>& bests)> migration;
};

/// Runs every island up to generation options.generations. The islands run their generations on
/// up to options.threads threads (each island on threads / K of them, at least one) until the
/// next migration, which all of them then make at once. Islands may start at different
/// generations (a resumed run), but none past the next migration. The summary's last_generation
/// is the lowest island's, best_t the best of all; stop, time_limit and speculate act as for
/// drive().
SearchSummary drive_islands(std::vector<Search>& islands, const IslandOptions& island_options,
                            const DriveOptions& options, const IslandCallbacks& callbacks);

}  // namespace softdrop
