// The rule of docs/reliability.md for every command that writes: a refused command (a damaged file,
// a bad option, an output that is an input, the database or another output) exits non-zero with one
// line naming the option or file, leaves every file byte for byte as it was, and creates none.
#include <SQLiteCpp/SQLiteCpp.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <vector>

#include "search_cli.hpp"

namespace {
using namespace softdrop::test;
namespace fs = std::filesystem;

std::string contents(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

void write(const fs::path& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

// Every entry of a folder: name -> bytes (a symbolic link by its target).
std::map<std::string, std::string> snapshot(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::directory_iterator(dir))
    files[e.path().filename().string()] =
        e.is_symlink() ? "-> " + fs::read_symlink(e.path()).string() : contents(e.path());
  return files;
}

void sql(const fs::path& db, const std::string& statement) {
  SQLite::Database d(db.string(), SQLite::OPEN_READWRITE);
  d.exec(statement);
}

// A folder of the files the cases run on, made once: a search history, a sweep store, a grain
// file, a config, and damaged copies of each.
class FileSafety : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    seed_ = fs::path(fresh("file_safety_seed"));
    fs::remove_all(seed_);
    fs::create_directories(seed_);
    const std::string d = seed_.string() + "/";
    ASSERT_EQ(run("optimize --db " + d + "h.db" + kScene + " --generations 2").code, 0);
    ASSERT_EQ(run("sweep --db " + d + "s.db" + kSweep + " --quiet").code, 0);
    ASSERT_EQ(run("simulate --x0 250 --save-medium " + d + "m.json").code, 0);
    write(seed_ / "c.toml", "porosity = 0.7\n");
    for (const char* copy : {"grain.db", "params.db"}) fs::copy_file(seed_ / "h.db", seed_ / copy);
    fs::copy_file(seed_ / "s.db", seed_ / "mean.db");
    sql(seed_ / "grain.db", "UPDATE grains SET r = -1 WHERE generation = 2 AND grain = 0");
    sql(seed_ / "params.db", "UPDATE runs SET params = '{\"x\": 1}'");
    sql(seed_ / "mean.db", "UPDATE sweep_media SET mean_t = 'x' WHERE medium_index = 0");
    fs::create_symlink("h.db", seed_ / "link.db");
    fs::create_hard_link(seed_ / "h.db", seed_ / "hard.db");
  }
  static void TearDownTestSuite() { fs::remove_all(seed_); }

  // Runs `args` (with {} standing for the case's folder) in a copy of the seed folder; expects a
  // refusal of one line containing `names`, and the folder as it was.
  static void expect_refused(const std::string& args, const std::string& names) {
    SCOPED_TRACE(args);
    const fs::path dir = fs::path(fresh("file_safety_case"));
    fs::remove_all(dir);
    fs::copy(seed_, dir, fs::copy_options::recursive | fs::copy_options::copy_symlinks);
    fs::remove(dir / "hard.db");
    fs::create_hard_link(dir / "h.db", dir / "hard.db");
    const auto before = snapshot(dir);
    std::string line = args;
    for (std::size_t at; (at = line.find("{}")) != std::string::npos;) line.replace(at, 2, dir.string());
    const Result r = run_shell("cd " + dir.string() + " && " + SOFTDROP_CLI + " " + line);
    EXPECT_NE(r.code, 0) << r.out;
    EXPECT_GT(r.code, 0) << "killed by a signal";
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(names), std::string::npos) << r.err;
    const auto after = snapshot(dir);
    for (const auto& [name, bytes] : after) {
      const auto was = before.find(name);
      EXPECT_TRUE(was != before.end()) << "created " << name;
      if (was != before.end()) {
        EXPECT_TRUE(was->second == bytes) << "changed " << name;
      }
    }
    for (const auto& [name, bytes] : before) EXPECT_TRUE(after.count(name)) << "removed " << name;
    fs::remove_all(dir);
  }

  static inline fs::path seed_;
  static inline const std::string kSweep = " --porosities 0.8 --media 2 --droplets 2 --seed 3";
};

TEST_F(FileSafety, AnOutputIsNeverTheDatabaseAnInputOrAnotherOutput) {
  const std::string clash = "the same file as";
  expect_refused("export --db h.db --run 1 -o h.db", "--output 'h.db': the same file as --db 'h.db'");
  expect_refused("export --db h.db --run 1 -o ./h.db", clash);
  expect_refused("export --db link.db --run 1 -o h.db", clash);
  expect_refused("export --db hard.db --run 1 -o h.db", clash);
  expect_refused("export --db {}/h.db --run 1 -o h.db", clash);
  expect_refused("export --db h.db --run 1 -o h.db-wal", "the side file of --db 'h.db'");
  expect_refused("export --db h.db --run 1 -o e.json --simulate-config e.json", clash);
  expect_refused("optimize --db h.db --json h.db --generations 3 --quiet", "--json 'h.db'");
  expect_refused("optimize --db h.db --resume 1 --json ./h.db --generations 3 --quiet", "--json './h.db'");
  expect_refused("fit --db s.db --json s.db", "--json 's.db'");
  expect_refused("averagings --db s.db --csv s.db", "--csv 's.db'");
  expect_refused("sweep-merge --into s.db s.db", "--into 's.db'");
  expect_refused("simulate --medium m.json --runs m.json --droplets 2", "--runs 'm.json'");
  expect_refused("simulate --medium m.json --save-medium ./m.json", "--save-medium './m.json'");
  expect_refused("simulate --runs o.csv --json o.csv --x0 250", "--json 'o.csv'");
  expect_refused("simulate --config c.toml --json c.toml --x0 250", "--json 'c.toml'");
  expect_refused("render trace --csv o.png -o o.png", "'o.png': the same file as");
  expect_refused("render search --db h.db --run 1 -o c.png --curve c.png", clash);
  expect_refused("render medium --medium m.json -o m.json", "--output 'm.json'");
  expect_refused("render paths --medium m.json --droplets 2 -o ./m.json", "--output './m.json'");
  expect_refused("render snapshots --medium m.json --times 0.01 -o c.toml", "'c.toml'");
  expect_refused("render animation --medium m.json -o hard.db", "'hard.db'");
  expect_refused("render curves --db h.db -o link.db", "--output 'link.db'");
  expect_refused("validate --db h.db --run 1 --starts 2 --json hard.db", "--json 'hard.db'");
  expect_refused("calibrate --csv c.csv --points c.csv --quiet", "--points 'c.csv'");
}

TEST_F(FileSafety, ADamagedFileIsRefusedBeforeAnyWrite) {
  expect_refused("optimize --db grain.db --resume 1 --generations 6 --quiet", "radius -1");
  expect_refused("export --db params.db --run 1 -o g.json --simulate-config g.toml", "--db 'params.db': run 1");
  expect_refused("sweep --db mean.db" + kSweep + " --quiet", "column mean_t");
  expect_refused("sweep-merge --into out.db m.json", "'m.json'");
  expect_refused("sweep-merge --into s.db mean.db", "column mean_t");
}

TEST_F(FileSafety, ABadOptionWritesNothing) {
  expect_refused("optimize --db '' --generations 2", "--db: an empty value");
  expect_refused("sweep --db '' --quiet", "--db: an empty value");
  expect_refused("sweep-merge --into '' s.db", "--into: an empty value");
  expect_refused("sweep --db new.db --porosities 0.2 --kind non-overlapping --media 2 --droplets 2 --quiet",
                 "porosity = 0.2: unreachable");
  expect_refused("sweep --db s.db --porosities 0.2 --kind non-overlapping --media 2 --droplets 2 --quiet",
                 "porosity = 0.2: unreachable");
  expect_refused("optimize --db new.db --generations -1", "generations");
  expect_refused("simulate --json ''", "--json: an empty value");
  expect_refused("simulate --medium m.json --porosity 0.5 --runs r.csv", "porosity: has no effect with --medium");
}

// An empty array reached CLI11 as an option without a value, and crashed every command.
TEST_F(FileSafety, ConfigArraysAreCheckedAgainstTheirOptions) {
  for (const std::string key :
       {"porosity", "gravity", "x0", "droplets", "kind", "width", "seed", "medium", "runs", "format"}) {
    write(seed_ / "empty.toml", key + " = []\n");
    expect_refused("simulate --config empty.toml", "config file 'empty.toml': " + key + " = []: an empty array");
  }
  write(seed_ / "empty.toml", "[sweep]\nmedia = []\n");
  expect_refused("sweep --db e.db --config empty.toml", "media = []: an empty array");
  write(seed_ / "empty.toml", "lambda = []\n");
  expect_refused("optimize --db e.db --config empty.toml --generations 2", "lambda = []");
  write(seed_ / "empty.toml", "porosity = [0.5, 0.6]\n");
  expect_refused("simulate --config empty.toml", "--porosity takes one value, not an array of 2");
  write(seed_ / "empty.toml", "porosty = 0.5\n");
  expect_refused("simulate --config empty.toml",
                 "config file 'empty.toml': porosty: simulate has no option --porosty (did you mean porosity?)");
  write(seed_ / "empty.toml", "[sweep]\nmeida = 3\n");  // a command's table: its options and the program's
  expect_refused("sweep --db e.db --config empty.toml", "meida: sweep has no option --meida (did you mean media?)");
  write(seed_ / "empty.toml", "zzzzzz = 1\n");  // nothing near: no guess
  expect_refused("simulate --config empty.toml", "zzzzzz: simulate has no option --zzzzzz\n");
  fs::remove(seed_ / "empty.toml");
  // A list option takes an array, and gives the same sweep as the command line.
  write(seed_ / "list.toml", "porosities = [0.8]\nmedia = 2\ndroplets = 2\nseed = 3\n");
  const Result r =
      run_shell("cd " + seed_.string() + " && " + SOFTDROP_CLI + " sweep --db s.db --config list.toml --quiet");
  EXPECT_EQ(r.code, 0) << r.err;
  fs::remove(seed_ / "list.toml");
}

}  // namespace
