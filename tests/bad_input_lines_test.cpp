// Values a command used to take without a word, or refuse with a line the user never wrote: each
// is now refused with one line naming the option or file, and nothing is written.
#include <SQLiteCpp/SQLiteCpp.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "search_cli.hpp"

namespace {
using namespace softdrop::test;
namespace fs = std::filesystem;

struct Case {
  std::string args, names;
};

void expect_lines(const std::vector<Case>& cases) {
  for (const Case& c : cases) {
    SCOPED_TRACE(c.args);
    const Result r = run(c.args);
    EXPECT_GT(r.code, 0) << r.out;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(c.names), std::string::npos) << r.err;
  }
}

void write(const std::string& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

TEST(BadInputLines, EmptyValuesAreRefusedNotReadAsZero) {
  const std::string db = fresh("empty_values.db");
  expect_lines({{"simulate --gravity ''", "--gravity: an empty value"},
                {"simulate --viscosity ''", "--viscosity: an empty value"},
                {"simulate --cc ''", "--cc: an empty value"},
                {"simulate --constraint-iterations ''", "--constraint-iterations: an empty value"},
                {"simulate --threads '' --droplets 2", "--threads: an empty value"},
                {"optimize --db " + db + " --generations ''", "--generations: an empty value"},
                {"render snapshots --times '' -o " + temp_path("t.png"), "--times: an empty value"},
                {"simulate --json ''", "--json: an empty value"}});
  EXPECT_FALSE(fs::exists(db));
}

TEST(BadInputLines, IdsStartAtOne) {
  const std::string db = fresh("ids.db");
  ASSERT_EQ(run("optimize --db " + db + kScene + " --generations 1").code, 0);
  const std::string store = fresh("ids_sweep.db");
  ASSERT_EQ(run("sweep --db " + store + " --porosities 0.8 --media 2 --droplets 2 --quiet").code, 0);
  expect_lines({{"optimize --db " + db + " --resume 0", "--resume: '0' is not an id"},
                {"history --db " + db + " --run 0", "--run: '0' is not an id"},
                {"export --db " + db + " --run -1 -o " + temp_path("x.json"), "--run: '-1' is not an id"},
                {"sweep-report --db " + store + " --sweep 0", "--sweep: '0' is not an id"},
                {"sweep-report --db " + store + " --sweep -1", "--sweep: '-1' is not an id"},
                {"optimize --db " + db + " --generations 18446744073709551616",
                 "--generations: '18446744073709551616' is out of range"}});
}

TEST(BadInputLines, OptionsACommandWouldIgnoreAreRefused) {
  const std::string medium = fresh("ignored.json"), store = fresh("ignored_sweep.db");
  ASSERT_EQ(run("simulate --x0 250 --save-medium " + medium).code, 0);
  ASSERT_EQ(run("sweep --db " + store + " --porosities 0.8 --media 4 --droplets 2 --quiet").code, 0);
  expect_lines(
      {{"simulate --medium " + medium + " --porosity 0.5", "porosity: has no effect with --medium"},
       {"simulate --medium " + medium + " --walls", "walls: has no effect with --medium"},
       {"simulate --snapshot-times 0.1", "snapshot-times: has no effect without --snapshots"},
       {"simulate --trace-interval 50", "trace-interval: has no effect without --trace"},
       {"sweep --db " + store + " --porosity 0.7", "porosity: not an option of sweep, whose media take --porosities"},
       {"sweep --db " + store + " --medium-seed=3",
        "medium-seed: not an option of sweep, whose media take their seeds"},
       {"simulate --trace-interval 0 --trace " + temp_path("t.csv"),
        "--trace-interval: '0' is not a whole number >= 1"},
       {"averagings --db " + store + " --group 0", "--group: '0' is not a whole number >= 1"},
       {"render snapshots --times 0.01,1e308 -o " + temp_path("t.png"), "times: 1e+308 is after the run's last step"}});
  // A config file may name a generated medium's grains (the installed droplets' configs do), and
  // a porosity and a medium seed that a sweep leaves alone.
  const Result r = run("simulate --medium " + medium + " --x0 250 --config " + SOFTDROP_SOURCE_DIR +
                       "/results/calibration/passage.toml");
  EXPECT_EQ(r.code, 0) << r.err;
  const std::string config = fresh("medium.toml");
  std::ofstream(config) << "porosity = 0.6\nmedium-seed = 3\n";
  const Result c =
      run("--config " + config + " --check sweep --db " + store + " --porosities 0.8 --media 4 --droplets 2");
  EXPECT_EQ(c.code, 0) << c.err;
}

TEST(BadInputLines, GrainFilesNameTheFieldNotTheJsonLibrary) {
  const std::string f = fresh("grains.json");
  const std::string head = R"({"format": "softdrop-medium", "version": 1, )";
  for (const auto& [text, says] : std::vector<std::pair<std::string, std::string>>{
           {"{\"format\": ", "not valid JSON (parse error at line 1"},
           {R"({"format": 3, "version": 1})", "\"format\" must be \"softdrop-medium\""},
           {head + R"("height": 10, "grains": []})", "\"width\" is missing"},
           {head + R"("width": "wide", "height": 10, "grains": []})", "\"width\" must be a number, not string"},
           {head + R"("width": 100, "height": 10, "periodic": 1, "grains": []})",
            "\"periodic\" must be true or false, not number"},
           {head + R"("width": 100, "height": 10})", "\"grains\" is missing"},
           {head + R"("width": 100, "height": 10, "grains": {}})", "\"grains\" must be an array"},
           {head + R"("width": 100, "height": 10, "grains": [3]})", "grain 0: must be an object"},
           {head + R"("width": 100, "height": 10, "grains": [{"x": 1, "y": 2}]})", "grain 0: \"r\" is missing"},
           {head + R"("width": 100, "height": 10, "grains": [{"x": 1, "y": null, "r": 2}]})",
            "grain 0: \"y\" must be a number, not null"},
           {head + R"("width": 1e308, "height": 100, "grains": [{"x": 1, "y": 2, "r": 3}]})",
            "width = 1e+308: must be in (0, 1e9]"}}) {
    write(f, text);
    SCOPED_TRACE(text);
    const Result r = run("simulate --medium " + f);
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("grain file '" + f + "': " + says), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("json.exception"), std::string::npos) << r.err;
  }
}

TEST(BadInputLines, MessagesSayWhatIsWrong) {
  const std::string points = fresh("points.csv");
  write(points, "phi,t,se\n0.5,1.2,0.1\n0.6,1.1,-1\n");
  expect_lines({{"render foo -o " + temp_path("f.png"), "unknown command 'foo' of render (one of medium, snapshots"},
                {"render", "render needs a command: one of medium, snapshots"},
                {"fit --points " + points, "--points '" + points + "' line 3: se = -1 must be > 0"},
                {"sweep --db " + temp_path("no_such_folder/s.db") + " --preset quick --quiet", "does not exist"}});
  write(points, "phi,t,se\n0.5,1.2,0.1\n");
  expect_lines({{"fit --points " + points, "--points '" + points + "': fit power: needs at least 3 points"}});
  // A damaged write version made SQLite open the file read-only: "attempt to write a readonly database".
  const std::string db = fresh("write_version.db");
  ASSERT_EQ(run("optimize --db " + db + kScene + " --generations 1").code, 0);
  {
    std::fstream f(db, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(18);
    f.put(static_cast<char>(7));
  }
  expect_lines(
      {{"optimize --db " + db + " --resume 1 --generations 3 --quiet", "damaged SQLite header (file format versions 7"},
       {"history --db " + db, "damaged SQLite header"}});
}

TEST(BadInputLines, AFileTheUserCannotReadIsSaidSo) {
  if (::geteuid() != 0) GTEST_SKIP() << "needs root to act as another user";
  const std::string db = fresh("unreadable.db");
  ASSERT_EQ(run("optimize --db " + db + kScene + " --generations 1").code, 0);
  fs::permissions(db, fs::perms::owner_read | fs::perms::owner_write);
  const Result r = run_shell("setpriv --reuid=65534 --regid=65534 --clear-groups " + std::string(SOFTDROP_CLI) +
                             " history --db " + db);
  if (r.err.find("Permission denied") == std::string::npos && r.code == 126) GTEST_SKIP() << "program not executable";
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("--db '" + db + "': cannot read it (Permission denied)"), std::string::npos) << r.err;
}

// Rows no run of softdrop stores are refused where they are read, naming the file.
TEST(BadInputLines, DamagedRowsAreRefused) {
  const std::string seed = fresh("rows_seed.db");
  ASSERT_EQ(run("optimize --db " + seed + kScene + " --generations 3").code, 0);
  const std::string store_seed = fresh("rows_sweep_seed.db");
  ASSERT_EQ(run("sweep --db " + store_seed + " --porosities 0.8 --media 2 --droplets 2 --quiet").code, 0);
  for (const auto& [sql, says] : std::vector<std::pair<std::string, std::string>>{
           {"UPDATE runs SET generations = -5", "run 1: column generations holds -5"},
           {"UPDATE runs SET best_generation = 999", "run 1: column best_generation holds 999"},
           {"UPDATE runs SET evaluations = -1", "column evaluations holds -1"},
           {"UPDATE runs SET best_t = best_t * 1.5", "differs from its generation 3's best_t"},
           {"UPDATE runs SET params = CAST(x'7bff7d' AS TEXT)", "column params holds text that is not UTF-8"}}) {
    SCOPED_TRACE(sql);
    const std::string db = fresh("rows.db");
    fs::copy_file(seed, db);
    SQLite::Database(db, SQLite::OPEN_READWRITE).exec(sql);
    const Result r = run("optimize --db " + db + " --resume 1 --generations 5 --quiet");
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("--db '" + db + "'"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(says), std::string::npos) << r.err;
  }
  for (const auto& [sql, says] : std::vector<std::pair<std::string, std::string>>{
           {"UPDATE sweeps SET units = -1", "sweep 1: column units holds -1"},
           {"INSERT INTO sweep_droplets SELECT sweep_id, porosity_index, medium_index + 7, droplet, start_x, outcome, "
            "tortuosity, steps, shaken_at, route_tortuosity FROM sweep_droplets",
            "droplets of porosity 0 medium 7 without their medium"}}) {
    SCOPED_TRACE(sql);
    const std::string db = fresh("rows_sweep.db");
    fs::copy_file(store_seed, db);
    {
      SQLite::Database d(db, SQLite::OPEN_READWRITE);
      d.exec("PRAGMA foreign_keys = OFF");
      d.exec(sql);
    }
    const Result r = run("sweep-report --db " + db);
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find(says), std::string::npos) << r.err;
  }
  // An edited copy of a medium no longer merges: every summary column is compared.
  const std::string edited = fresh("rows_edited.db"), into = fresh("rows_into.db");
  fs::copy_file(store_seed, edited);
  SQLite::Database(edited, SQLite::OPEN_READWRITE)
      .exec("UPDATE sweep_media SET mean_t = mean_t + 0.25 WHERE mean_t IS NOT NULL");
  const Result r = run("sweep-merge --into " + into + " " + store_seed + " " + edited);
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("differs from the copy in '" + store_seed + "'"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(into));
}

}  // namespace
