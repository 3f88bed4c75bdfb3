// Crash safety under a long search: many SIGKILLs at random instants, each followed by a resume.
// Every generation committed before a kill must survive unchanged, and the final history must
// equal a search that never stopped, with PRAGMA integrity_check ok.
#include <SQLiteCpp/SQLiteCpp.h>
#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <iostream>
#include <iterator>
#include <random>
#include <thread>
#include <utility>
#include <vector>

#include "search_cli.hpp"

namespace {
using namespace softdrop::test;

TEST(Soak, ManyKillsOverALongSearchLoseNoCommittedGeneration) {
  constexpr int kKills = 40;
  const std::string gens = " --generations 400 --lambda 2 --threads 2 ";
  const std::string ref = fresh("soak_ref.db"), killed = fresh("soak_killed.db");
  const Result r = run("optimize --db " + ref + kScene + " --generations 400 --lambda 2 --threads 1");
  ASSERT_EQ(r.code, 0) << r.err;

  std::mt19937 rng(4242);  // reproducible kill instants
  int kills = 0, resumes = 0, restarts = 0;
  std::vector<std::pair<std::int64_t, std::string>> committed;  // at each kill: last generation, its rows
  for (int attempt = 0; attempt < kKills; ++attempt) {
    const bool resume = has_run(killed);
    (resume ? resumes : restarts)++;
    const std::string err = temp_path("soak_stderr.txt");
    const pid_t pid = spawn("optimize --db " + killed + kScene + gens + (resume ? " --resume 1" : ""), err);
    // Under AddressSanitizer a start (and a resume's re-simulation of the best) takes ~0.3 s, so
    // the window is wider there, or nearly every kill would land before the first generation.
    const int latest = kAddressSanitizer ? 800 : 300;
    std::this_thread::sleep_for(std::chrono::milliseconds(std::uniform_int_distribution<int>(10, latest)(rng)));
    if (kill(pid, SIGKILL) == 0) ++kills;
    const int code = wait_for(pid);
    std::ifstream err_in(err);
    const std::string message((std::istreambuf_iterator<char>(err_in)), {});
    ASSERT_TRUE(code == -SIGKILL || code == 0)
        << "attempt " << attempt << (resume ? " (resume)" : " (fresh start)") << ": exit " << code << ": " << message;
    if (const std::int64_t g = committed_generations(killed); g >= 0) committed.emplace_back(g, dump(killed, 1, g));
  }
  const Result fin = run("optimize --db " + killed + kScene + gens + (has_run(killed) ? " --resume 1" : ""));
  ASSERT_EQ(fin.code, 0) << fin.err;

  int lost = 0;  // kills after which a committed generation later changed or vanished
  for (const auto& [g, rows] : committed) lost += dump(killed, 1, g) != rows;
  SQLite::Database db(killed, SQLite::OPEN_READONLY);
  const std::string integrity = db.execAndGet("PRAGMA integrity_check").getString();
  const std::int64_t at_last_kill = committed.empty() ? -1 : committed.back().first;
  std::cout << "soak: " << kills << " SIGKILLs survived (" << resumes << " resumes, " << restarts << " fresh starts), "
            << at_last_kill << " of 400 generations committed at the last kill, " << lost
            << " kills lost committed generations, integrity_check " << integrity << "\n";
  RecordProperty("kills", kills);
  RecordProperty("lost", lost);
  EXPECT_EQ(kills, kKills) << "every kill must land while the search runs";
  EXPECT_GE(resumes, kKills / 2);
  EXPECT_EQ(lost, 0);
  EXPECT_EQ(integrity, "ok");
  EXPECT_EQ(dump(killed, 1), dump(ref, 1));
  EXPECT_EQ(db.execAndGet("SELECT count(*) FROM runs").getInt(), 1);
}

}  // namespace
