// Files the store refuses are left exactly as they were found; damaged runs are refused by every
// command that reads them, naming the file; two identical sweeps at once both finish; a database on
// read-only media can be read.
#include <SQLiteCpp/SQLiteCpp.h>
#include <gtest/gtest.h>
#include <sys/mount.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "search_cli.hpp"
#include "softdrop/store.hpp"

namespace {
using namespace softdrop::test;

std::string contents(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

void expect_one_line(const Result& r, const std::string& names) {
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find(names), std::string::npos) << r.err;
}

// A WAL-mode softdrop file, checkpointed, made foreign or newer or damaged by `sql`.
TEST(RefusedFiles, AreLeftAsTheyWereFoundWithNoSideFiles) {
  const std::string seed = fresh("refused_seed.db");
  ASSERT_EQ(run("optimize --db " + seed + kScene + " --generations 2").code, 0);
  ASSERT_FALSE(std::filesystem::exists(seed + "-wal"));
  struct Case {
    std::string sql, names;
  };
  for (const Case& c :
       {Case{"PRAGMA application_id = 5", "not a softdrop database"},
        Case{"PRAGMA user_version = " + std::to_string(softdrop::kHistorySchemaVersion + 1),
             "written by a newer softdrop"},
        Case{"PRAGMA user_version = 99", "schema version 99"}, Case{"DROP TABLE paths", "without its table paths"}}) {
    SCOPED_TRACE(c.sql);
    const std::string db = fresh("refused.db");
    std::filesystem::copy_file(seed, db);
    {
      SQLite::Database w(db, SQLite::OPEN_READWRITE);
      w.exec(c.sql);
    }
    ASSERT_FALSE(std::filesystem::exists(db + "-wal"));
    const std::string before = contents(db);
    for (const std::string& command :
         {"history --db " + db, "optimize --db " + db + " --resume 1 --generations 4 --quiet",
          "optimize --db " + db + kScene + " --generations 1", "sweep --db " + db + " --preset quick --quiet"}) {
      SCOPED_TRACE(command);
      expect_one_line(run(command), c.names);
      EXPECT_EQ(contents(db), before);
      EXPECT_FALSE(std::filesystem::exists(db + "-wal"));
      EXPECT_FALSE(std::filesystem::exists(db + "-shm"));
    }
  }
}

TEST(RefusedFiles, OurIdWithoutOurTablesIsRefusedBeforeAnyWrite) {
  const std::string db = fresh("no_tables.db");
  {
    SQLite::Database w(db, SQLite::OPEN_READWRITE | SQLite::OPEN_CREATE);
    w.exec("PRAGMA application_id = 1396986448; PRAGMA user_version = 2; CREATE TABLE x(a)");
  }
  const std::string before = contents(db);
  for (const std::string& command : {"optimize --db " + db + " --resume 1 --quiet", "optimize --db " + db + kScene,
                                     "sweep --db " + db + " --preset quick --quiet", "history --db " + db}) {
    SCOPED_TRACE(command);
    expect_one_line(run(command), "'" + db + "': softdrop database (schema version 2) without its table runs");
    EXPECT_EQ(contents(db), before);  // not switched to WAL, change counter untouched
  }
}

TEST(DamagedRuns, AreRefusedByResumeAsByHistoryNamingTheFile) {
  const std::string seed = fresh("damaged_run_seed.db");
  ASSERT_EQ(run("optimize --db " + seed + kScene + " --generations 14").code, 0);
  struct Case {
    std::string sql, names;
  };
  for (const Case& c : {
           Case{"UPDATE runs SET params = '{not json'", "run 1: its params are not a JSON object"},
           Case{"UPDATE runs SET params = '{}'", "run 1: stored parameters: 'seed' missing"},
           // A name no build knows is refused in the command line's words, not read as 'paper'.
           Case{"UPDATE runs SET params = json_set(params, '$.strategy', 'tabu')",
                "run 1: stored parameters: strategy = 'tabu': must be paper, es, lahc, anneal or cmaes"},
           Case{"UPDATE runs SET params = json_set(params, '$.constraint-order', 'zigzag')",
                "run 1: stored parameters: constraint-order = 'zigzag': must be sequential or red-black"},
           Case{"DELETE FROM generations WHERE generation = 12",
                "run 1: generation 12 is missing: stores 14 generations numbered 0 to 14"},
           Case{"PRAGMA foreign_keys = ON; DELETE FROM generations WHERE generation = 12",
                "run 1: generation 12 is missing: stores 14 generations numbered 0 to 14"},
           Case{"DELETE FROM generations WHERE generation = 0", "run 1: generation 0 is missing: stores 14"},
           Case{"DELETE FROM candidates WHERE generation = 5", "a generation without candidates"},
       }) {
    SCOPED_TRACE(c.sql);
    const std::string db = fresh("damaged_run.db");
    std::filesystem::copy_file(seed, db);
    {
      SQLite::Database w(db, SQLite::OPEN_READWRITE);
      w.exec(c.sql);
    }
    const std::string before = dump(db, 1);
    const Result resume = run("optimize --db " + db + " --resume 1 --generations 16 --quiet");
    expect_one_line(resume, "'" + db + "'");
    EXPECT_NE(resume.err.find(c.names), std::string::npos) << resume.err;
    EXPECT_EQ(resume.err.rfind("softdrop: error: --db '" + db + "': ", 0), 0u) << resume.err;
    if (c.sql.find("generation") != std::string::npos) {
      EXPECT_NE(resume.err.find("run 1: "), std::string::npos) << resume.err;
      expect_one_line(run("history --db " + db + " --run 1"), "'" + db + "'");
    }
    EXPECT_EQ(dump(db, 1), before);
  }
  const Result missing = run("optimize --db " + seed + " --resume 7 --quiet");
  EXPECT_EQ(missing.code, 1) << missing.err;
  EXPECT_NE(missing.err.find("resume = 7: '" + seed + "' has no run 7"), std::string::npos) << missing.err;
}

TEST(TwoSweepsAtOnce, BothFinishAndTheStoreHoldsEachUnitOnce) {
  const std::string ref = fresh("two_ref.db"), db = fresh("two.db");
  const std::string args = " --preset quick --media 2 --droplets 4 --quiet --threads 1";
  ASSERT_EQ(run("sweep --db " + ref + args).code, 0);
  // The second starts a little later, so it both meets units the first is computing and units
  // the first has stored.
  const std::string err1 = temp_path("two_err1.txt"), err2 = temp_path("two_err2.txt");
  const pid_t first = spawn("sweep --db " + db + args, err1);
  const pid_t second = spawn("sweep --db " + db + args, err2);
  EXPECT_EQ(wait_for(first), 0) << contents(err1);
  EXPECT_EQ(wait_for(second), 0) << contents(err2);
  EXPECT_EQ(sweep_dump(db), sweep_dump(ref));
}

// A real read-only mount (tmpfs, remounted read-only); skipped where this process may not mount.
TEST(ReadOnlyMedia, AHealthyDatabaseIsReadAndAWriteIsRefusedClearly) {
  const std::string dir = fresh("ro_mount");
  std::filesystem::create_directory(dir);
  if (::mount("tmpfs", dir.c_str(), "tmpfs", 0, "size=4m") != 0) {
    std::filesystem::remove(dir);
    GTEST_SKIP() << "cannot mount a tmpfs here (needs root or CAP_SYS_ADMIN)";
  }
  const std::string db = dir + "/h.db", out = fresh("ro_best.json");
  ASSERT_EQ(run("optimize --db " + db + kScene + " --generations 3").code, 0);
  const std::string rows = dump(db, 1);
  ASSERT_EQ(::mount("tmpfs", dir.c_str(), "tmpfs", MS_REMOUNT | MS_RDONLY, "size=4m"), 0);
  const Result h = run("history --db " + db + " --run 1");
  EXPECT_EQ(h.code, 0) << h.err;
  EXPECT_EQ(run("export --db " + db + " --run 1 -o " + out).code, 0);
  expect_one_line(run("optimize --db " + db + " --resume 1 --generations 5 --quiet"), "cannot write to it");
  EXPECT_EQ(dump(db, 1), rows);
  EXPECT_EQ(::umount(dir.c_str()), 0);
  std::filesystem::remove(dir);
}

}  // namespace
