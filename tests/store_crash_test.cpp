// Crash and full-disk safety at SQLite's own write level. softdrop_faulty (fault_vfs.hpp) is killed
// before each write a checkpoint makes to the database file, at every position over a whole
// search and a whole sweep, or finds the disk full after N bytes. Each time the file must open
// (history, report), keep every generation or unit committed before the fault unchanged, and run
// on to exactly the records of an uninterrupted run.
#include <gtest/gtest.h>
#include <signal.h>

#include <SQLiteCpp/SQLiteCpp.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>

#include "search_cli.hpp"

namespace {
using namespace softdrop::test;

// Frequent automatic checkpoints (every 4 pages of WAL), so that kills land inside the
// checkpoints of a running search as well as the one at close.
const std::string kCheckpointEvery = "SOFTDROP_FAULT_AUTOCHECKPOINT=4 ";
const std::string kSearch = kScene + " --generations 8 --threads 1";
const std::string kSweep = " --preset quick --media 1 --droplets 3 --quiet --threads 1";

Result run_faulty(const std::string& env, const std::string& args) {
  return run_shell(env + std::string(SOFTDROP_FAULTY_CLI) + " " + args);
}

bool killed(const Result& r) { return r.code == -1 || r.code == 128 + SIGKILL; }

// The writes to the database file over a whole run, and the bytes written to all its files.
std::pair<std::int64_t, std::int64_t> count_writes(const std::string& args) {
  const std::string counts = fresh("crash_counts.txt");
  const Result r = run_faulty(kCheckpointEvery + "SOFTDROP_FAULT_COUNT_FILE=" + counts + " ", args);
  EXPECT_EQ(r.code, 0) << r.err;
  std::int64_t writes = 0, bytes = 0;
  std::ifstream(counts) >> writes >> bytes;
  return {writes, bytes};
}

// Positions to kill at: every one, or every third under AddressSanitizer (3-4x slower).
int kill_stride() { return kAddressSanitizer ? 3 : 1; }

TEST(StoreCrash, SearchKilledAtEveryDatabaseWriteLosesNothingAndResumesToTheSameHistory) {
  const std::string ref = fresh("crash_search_ref.db");
  ASSERT_EQ(run("optimize --db " + ref + kSearch).code, 0);
  const std::string db_args = "optimize --db ";
  const auto [writes, bytes] = count_writes(db_args + fresh("crash_search_count.db") + kSearch);
  ASSERT_GT(writes, 20) << "the scene should checkpoint several times";
  int kills = 0, lost = 0, refused = 0;
  for (std::int64_t k = 1; k <= writes; k += kill_stride()) {
    SCOPED_TRACE("killed before database write " + std::to_string(k) + " of " + std::to_string(writes));
    const std::string db = fresh("crash_search.db");
    const Result r = run_faulty(kCheckpointEvery + "SOFTDROP_FAULT_KILL_AT=" + std::to_string(k) + " ",
                                db_args + db + kSearch);
    ASSERT_TRUE(killed(r)) << "exit " << r.code << ": " << r.err;
    ++kills;
    const std::int64_t committed = committed_generations(db);
    const std::string before = committed >= 0 ? dump(db, 1, committed) : "";
    if (committed >= 0) {
      const Result h = run("history --db " + db);
      refused += h.code != 0;
      EXPECT_EQ(h.code, 0) << h.err;
    }
    const Result again = run(db_args + db + kSearch + (committed >= 0 ? " --resume 1" : ""));
    ASSERT_EQ(again.code, 0) << again.err;
    if (committed >= 0) lost += dump(db, 1, committed) != before;
    EXPECT_EQ(dump(db, 1), dump(ref, 1));
  }
  std::cout << "store crash (search): " << kills << " kills over " << writes << " database writes, " << refused
            << " refusals, " << lost << " lost committed generations\n";
  EXPECT_EQ(lost, 0);
  EXPECT_EQ(refused, 0);
}

TEST(StoreCrash, SweepKilledAtEveryDatabaseWriteLosesNoUnitAndRunsOnToTheSameRecords) {
  const std::string ref = fresh("crash_sweep_ref.db");
  ASSERT_EQ(run("sweep --db " + ref + kSweep).code, 0);
  const std::string reference = sweep_dump(ref);
  const auto [writes, bytes] = count_writes("sweep --db " + fresh("crash_sweep_count.db") + kSweep);
  ASSERT_GT(writes, 5);
  int kills = 0, lost = 0, refused = 0;
  for (std::int64_t k = 1; k <= writes; k += kill_stride()) {
    SCOPED_TRACE("killed before database write " + std::to_string(k) + " of " + std::to_string(writes));
    const std::string db = fresh("crash_sweep.db");
    const Result r = run_faulty(kCheckpointEvery + "SOFTDROP_FAULT_KILL_AT=" + std::to_string(k) + " ",
                                "sweep --db " + db + kSweep);
    ASSERT_TRUE(killed(r)) << "exit " << r.code << ": " << r.err;
    ++kills;
    std::int64_t units = -1;
    std::string before;
    try {
      SQLite::Database d(db, SQLite::OPEN_READONLY);
      units = d.execAndGet("SELECT count(*) FROM sweep_media").getInt64();
      before = sweep_dump(db);
    } catch (const SQLite::Exception&) {  // killed before the schema was committed
    }
    if (units >= 0) {
      const Result report = run("sweep-report --db " + db);
      refused += report.code != 0 && report.err.find("no sweep") == std::string::npos;
      EXPECT_EQ(report.err.find("corrupt"), std::string::npos) << report.err;
    }
    const Result again = run("sweep --db " + db + kSweep);
    ASSERT_EQ(again.code, 0) << again.err;
    const std::string after = sweep_dump(db);
    // Every line stored before the kill (sweep, media, droplets) is still there, unchanged.
    std::istringstream lines(before);
    for (std::string line; std::getline(lines, line);) lost += after.find(line + "\n") == std::string::npos;
    EXPECT_EQ(after, reference);
  }
  std::cout << "store crash (sweep): " << kills << " kills over " << writes << " database writes, " << refused
            << " refusals, " << lost << " lost records\n";
  EXPECT_EQ(lost, 0);
  EXPECT_EQ(refused, 0);
}

// The disk fills after a budget of bytes, at several points of the run: the program stops with one
// line (or, if only the checkpoint at close failed, finishes), and once space is back the same
// command resumes to the uninterrupted history.
TEST(StoreCrash, AFullDiskStopsCleanlyAndTheSearchResumesOnceSpaceIsBack) {
  const std::string ref = fresh("full_search_ref.db");
  ASSERT_EQ(run("optimize --db " + ref + kSearch).code, 0);
  const auto [writes, bytes] = count_writes("optimize --db " + fresh("full_search_count.db") + kSearch);
  ASSERT_GT(bytes, 0);
  int full = 0;
  for (int i = 1; i <= 8; ++i) {
    const std::int64_t budget = bytes * i / 9;
    SCOPED_TRACE("disk full after " + std::to_string(budget) + " of " + std::to_string(bytes) + " bytes");
    const std::string db = fresh("full_search.db");
    const Result r = run_faulty(kCheckpointEvery + "SOFTDROP_FAULT_FULL_AFTER=" + std::to_string(budget) + " ",
                                "optimize --db " + db + kSearch);
    ASSERT_TRUE(r.code == 0 || r.code == 1) << r.err;
    if (r.code == 1) {
      ++full;
      EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
      EXPECT_NE(r.err.find("full"), std::string::npos) << r.err;
    }
    const std::int64_t committed = committed_generations(db);
    const std::string before = committed >= 0 ? dump(db, 1, committed) : "";
    if (r.code == 1 && !std::filesystem::exists(db)) continue;  // nothing was created: nothing to lose
    const Result again = run("optimize --db " + db + kSearch + (committed >= 0 ? " --resume 1" : ""));
    ASSERT_EQ(again.code, 0) << again.err;
    if (committed >= 0) {
      EXPECT_EQ(dump(db, 1, committed), before);
    }
    EXPECT_EQ(dump(db, 1), dump(ref, 1));
  }
  EXPECT_GE(full, 4);
}

TEST(StoreCrash, AFullDiskStopsASweepCleanlyAndItRunsOnOnceSpaceIsBack) {
  const std::string ref = fresh("full_sweep_ref.db");
  ASSERT_EQ(run("sweep --db " + ref + kSweep).code, 0);
  const auto [writes, bytes] = count_writes("sweep --db " + fresh("full_sweep_count.db") + kSweep);
  int full = 0;
  for (int i = 1; i <= 5; ++i) {
    const std::int64_t budget = bytes * i / 6;
    SCOPED_TRACE("disk full after " + std::to_string(budget) + " of " + std::to_string(bytes) + " bytes");
    const std::string db = fresh("full_sweep.db");
    const Result r = run_faulty(kCheckpointEvery + "SOFTDROP_FAULT_FULL_AFTER=" + std::to_string(budget) + " ",
                                "sweep --db " + db + kSweep);
    ASSERT_TRUE(r.code == 0 || r.code == 1) << r.err;
    if (r.code == 1) {
      ++full;
      EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
      EXPECT_NE(r.err.find("full"), std::string::npos) << r.err;
    }
    const Result again = run("sweep --db " + db + kSweep);
    ASSERT_EQ(again.code, 0) << again.err;
    EXPECT_EQ(sweep_dump(db), sweep_dump(ref));
  }
  EXPECT_GE(full, 3);
}

}  // namespace
