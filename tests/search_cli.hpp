#pragma once
// Driving `softdrop optimize` from tests: the small scene on the command line, processes spawned
// and killed, and a dump of everything deterministic a run stored (to compare histories).
#include <SQLiteCpp/SQLiteCpp.h>
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>

#include <cstdint>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "balloon.hpp"
#include "cli_run.hpp"

extern char** environ;

namespace softdrop::test {

// The small scene of search_fixtures.hpp, on the command line.
// (without the held-out value at the end: the tests of it ask for it)
// (the paper's single objective: these tests are of the search's machinery, which it runs fastest)
inline const std::string kScene =
    kSmallScene + " --seed 7 --stuck-window 0.1 --stuck-distance 1 --quiet --validate-starts 0 --objective single ";

/// Everything deterministic a run stored: the rows of every table without times and durations.
/// With `upto` >= 0, only generations up to it, and not the runs row (which changes as a run goes on).
inline std::string dump(const std::string& db_path, int run, std::int64_t upto = -1) {
  SQLite::Database db(db_path, SQLite::OPEN_READONLY);
  std::ostringstream out;
  out.precision(17);
  const std::string limit = upto >= 0 ? " AND generation <= " + std::to_string(upto) : "";
  auto table = [&](const std::string& sql) {
    SQLite::Statement q(db, sql);
    q.bind(1, run);
    while (q.executeStep()) {
      for (int c = 0; c < q.getColumnCount(); ++c) out << q.getColumn(c).getText() << '|';
      out << '\n';
    }
  };
  if (upto < 0)
    table(
        "SELECT status, params, seed, lambda, grains, width, height, periodic, generations, evaluations, droplets, "
        "best_t, best_generation FROM runs WHERE id = ?");
  table(
      "SELECT generation, kind, accepted_candidate, best_t, touched, parent_t, parent_passed FROM generations "
      "WHERE run_id = ?" +
      limit + " ORDER BY generation");
  table(
      "SELECT generation, candidate, moved_grain, moved, outcome, reason, tortuosity, steps, touched, droplets, "
      "passed FROM candidates WHERE run_id = ?" +
      limit + " ORDER BY generation, candidate");
  table("SELECT generation, grain, x, y, r, touched FROM grains WHERE run_id = ?" + limit +
        " ORDER BY generation, grain");
  table("SELECT generation, point, x, y FROM paths WHERE run_id = ?" + limit + " ORDER BY generation, point");
  return out.str();
}

/// Everything deterministic a sweep store holds: sweeps, media and droplets without times.
inline std::string sweep_dump(const std::string& db_path) {
  SQLite::Database d(db_path, SQLite::OPEN_READONLY);
  std::ostringstream out;
  for (const char* sql :
       {"SELECT params, units FROM sweeps ORDER BY id",
        "SELECT sweep_id, porosity_index, medium_index, target_porosity, porosity, grains, medium_seed, "
        "droplets, passed, stuck, timeout, diverged, mean_t, standard_error, stuck_fraction "
        "FROM sweep_media ORDER BY 1, 2, 3",
        "SELECT * FROM sweep_droplets ORDER BY 1, 2, 3, 4"}) {
    SQLite::Statement q(d, sql);
    while (q.executeStep()) {
      for (int c = 0; c < q.getColumnCount(); ++c) out << q.getColumn(c).getText() << '|';
      out << '\n';
    }
  }
  return out.str();
}

/// Starts `softdrop ARGS` (words split at spaces) with stdout to /dev/null and stderr to
/// `err_path` (default /dev/null).
inline pid_t spawn(const std::string& args, const std::string& err_path = "/dev/null") {
  std::vector<std::string> words{SOFTDROP_CLI};
  std::istringstream in(args);
  for (std::string w; in >> w;) words.push_back(w);
  std::vector<char*> argv;
  for (auto& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 2, err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t pid = 0;
  EXPECT_EQ(posix_spawn(&pid, SOFTDROP_CLI, &actions, nullptr, argv.data(), environ), 0);
  posix_spawn_file_actions_destroy(&actions);
  return pid;
}

/// Waits for the process: its exit code, or minus the signal that ended it.
inline int wait_for(pid_t pid) {
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -WTERMSIG(status);
}

/// Whether the file holds a committed run (false while it does not exist or has no schema yet).
inline bool has_run(const std::string& db_path) {
  if (!std::filesystem::exists(db_path)) return false;
  try {
    SQLite::Database db(db_path, SQLite::OPEN_READONLY);
    return db.execAndGet("SELECT count(*) FROM runs").getInt() > 0;
  } catch (const SQLite::Exception&) {
    return false;  // killed before the schema was committed
  }
}

/// The last committed generation of run 1, -1 if none.
inline std::int64_t committed_generations(const std::string& db_path) {
  if (!has_run(db_path)) return -1;
  SQLite::Database db(db_path, SQLite::OPEN_READONLY);
  return db.execAndGet("SELECT coalesce(max(generation), -1) FROM generations WHERE run_id = 1").getInt64();
}

}  // namespace softdrop::test
