// `optimize --objective`: the single objective gives the histories it always gave, a robust run
// resumes bit for bit, and every bad objective option gets one line and leaves the history as it
// was.
#include <SQLiteCpp/SQLiteCpp.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "search_cli.hpp"

namespace {
using namespace softdrop::test;

// The small scene of search_cli.hpp without its objective.
const std::string kBase = kSmallScene + " --seed 7 --stuck-window 0.1 --stuck-distance 1 --quiet --validate-starts 0 ";
const std::string kRobust = kBase + " --objective mean --starts 4 --lambda 2 --strategy es --margin 1";

std::string bytes_of(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// The comparison of strategies in results/search was made before the objectives existed: its
// in-search curve of the default problem, es with relocation, seed 1, is what the single
// objective still gives, to the 15 digits the table keeps.
TEST(ObjectiveCli, TheSingleObjectiveGivesTheStoredComparisonsCurve) {
  const std::string db = fresh("single_curve.db");
  ASSERT_EQ(run("optimize --db " + db + " --config " + std::string(SOFTDROP_SOURCE_DIR) +
                "/results/calibration/balloon.toml --grains 60 --width 300 --height 300 --strategy es "
                "--relocate-every 3 --lambda 8 --seed 1 --medium-seed 1 --generations 12 --quiet "
                "--validate-starts 0 --objective single")
                .code,
            0);
  std::map<int, std::string> stored;
  std::ifstream csv(std::string(SOFTDROP_SOURCE_DIR) + "/results/search/curves.csv");
  for (std::string line; std::getline(csv, line);)
    if (line.rfind("default,es+r3,1,", 0) == 0) {
      std::vector<std::string> f;
      std::stringstream ss(line);
      for (std::string x; std::getline(ss, x, ',');) f.push_back(x);
      stored[std::stoi(f[3])] = f[6];
    }
  ASSERT_GE(stored.size(), 13u);
  SQLite::Database d(db, SQLite::OPEN_READONLY);
  SQLite::Statement q(d, "SELECT generation, printf('%.15g', best_t) FROM generations ORDER BY generation");
  int n = 0;
  while (q.executeStep()) {
    EXPECT_EQ(q.getColumn(1).getString(), stored.at(q.getColumn(0).getInt()))
        << "generation " << q.getColumn(0).getInt();
    ++n;
  }
  EXPECT_EQ(n, 13);
}

TEST(ObjectiveCli, ARobustRunResumedGoesOnBitForBit) {
  const std::string whole = fresh("robust_whole.db"), parts = fresh("robust_parts.db");
  ASSERT_EQ(run("optimize --db " + whole + kRobust + " --generations 6").code, 0);
  ASSERT_EQ(run("optimize --db " + parts + kRobust + " --generations 3").code, 0);
  const Result r = run("optimize --db " + parts + " --resume 1 --generations 6 --quiet");
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string a = dump(whole, 1), b = dump(parts, 1);
  EXPECT_EQ(a, b);
  // Every generation re-ran its parent on its 4 starts, and counts 2 x 4 + 4 droplets.
  SQLite::Database d(whole, SQLite::OPEN_READONLY);
  EXPECT_EQ(
      d.execAndGet("SELECT count(*) FROM generations WHERE generation > 0 AND parent_passed IS NOT NULL").getInt(), 6);
  EXPECT_EQ(d.execAndGet("SELECT droplets FROM runs").getInt64(), 4 + 6 * 12);
  EXPECT_EQ(d.execAndGet("SELECT count(*) FROM candidates WHERE droplets != 4").getInt(), 0);
  EXPECT_EQ(d.execAndGet("SELECT json_extract(params, '$.objective') FROM runs").getString(), "mean");
}

// Islands with a robust objective: a migration runs the immigrant and the island's arrangement on
// the generation's starts; threads and a resume change nothing.
TEST(ObjectiveCli, RobustIslandsAreTheSameOnAnyThreadCountAndThroughAResume) {
  const std::string args = kRobust + " --islands 2 --migrate-every 2";
  const std::string one = fresh("robust_islands_1.db"), two = fresh("robust_islands_2.db"),
                    parts = fresh("robust_islands_r.db");
  ASSERT_EQ(run("optimize --db " + one + args + " --generations 5 --threads 1").code, 0);
  ASSERT_EQ(run("optimize --db " + two + args + " --generations 5 --threads 2").code, 0);
  ASSERT_EQ(run("optimize --db " + parts + args + " --generations 3").code, 0);
  const Result r = run("optimize --db " + parts + " --resume 1 --generations 5 --quiet");
  ASSERT_EQ(r.code, 0) << r.err;
  for (int island = 1; island <= 2; ++island) {
    EXPECT_EQ(dump(one, island), dump(two, island)) << "island " << island;
    EXPECT_EQ(dump(one, island), dump(parts, island)) << "island " << island;
  }
  SQLite::Database d(one, SQLite::OPEN_READONLY);
  EXPECT_EQ(
      d.execAndGet("SELECT count(*) FROM generations WHERE kind = 'migrate' AND parent_passed IS NOT NULL").getInt(),
      4);
}

TEST(ObjectiveCli, BadObjectiveOptionsGetOneLineAndChangeNothing) {
  const std::string db = fresh("objective_bad.db");
  ASSERT_EQ(run("optimize --db " + db + kRobust + " --generations 1").code, 0);
  const std::string before = bytes_of(db), fresh_db = fresh("objective_none.db");
  for (const auto& [args, says] : std::vector<std::pair<std::string, std::string>>{
           {"--db " + fresh_db + kBase + " --objective mean --starts 0", "starts = 0: must be in [1, 4096]"},
           {"--db " + fresh_db + kBase + " --objective mean --starts 5000", "starts = 5000: must be in [1, 4096]"},
           {"--db " + fresh_db + kBase + " --objective median",
            "--objective: median not in {single,mean,quantile,lower-bound}"},
           {"--db " + fresh_db + kBase + " --objective quantile --quantile 1", "quantile = 1: must be in (0, 1)"},
           {"--db " + fresh_db + kBase + " --objective quantile --quantile 0", "quantile = 0: must be in (0, 1)"},
           {"--db " + fresh_db + kBase + " --objective mean --quantile 0.5",
            "quantile: not an option of --objective mean"},
           {"--db " + fresh_db + kBase + " --objective single --starts 8",
            "starts: not an option of --objective single"},
           {"--db " + fresh_db + kBase + " --preset paper --margin 1", "margin: not an option of --objective single"},
           {"--db " + fresh_db + kBase + " --objective lower-bound --margin -1", "margin = -1: must be >= 0"},
           {"--db " + db + " --resume 1 --objective single", "--objective \"single\" (stored \"mean\")"},
           {"--db " + db + " --resume 1 --starts 8", "--starts 8 (stored 4)"},
           {"--db " + db + " --resume 1 --preset paper", "--objective \"single\" (stored \"mean\")"}}) {
    SCOPED_TRACE(args);
    const Result r = run("optimize " + args);
    EXPECT_GT(r.code, 0);
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(says), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(fresh_db));
    EXPECT_TRUE(bytes_of(db) == before) << "the history changed";
  }
}

}  // namespace
