// The command-line program: bad input gives one line naming the problem, a non-zero exit and no
// output file; good input gives a parseable summary.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "balloon.hpp"
#include "cli_run.hpp"

namespace {
using softdrop::test::Result;
using softdrop::test::run;

std::string temp(const std::string& name) { return softdrop::test::temp_path("cli_" + name); }

TEST(Cli, BadInputGivesOneLineNamingTheParameterAndNoOutput) {
  const std::string out = temp("runs.csv");
  const std::string bad_grains = temp("bad.csv");
  std::ofstream(bad_grains) << "# width=10\nx,y,r\n1,2,3\n";
  struct Case {
    std::string args, names;
  };
  for (const Case& c :
       {Case{"--r-min -1", "r-min"}, Case{"--radius -1", "radius"}, Case{"--porosity 1.5", "porosity"},
        Case{"--porosity 0", "porosity"}, Case{"--dt 0", "dt"}, Case{"--dt -1e-5", "dt"}, Case{"--dt nan", "dt"},
        Case{"--nrt nan", "nrt"}, Case{"--porosity nan", "porosity"}, Case{"--bogus 3", "bogus"},
        Case{"--droplets abc", "droplets"}, Case{"--medium " + temp("does_not_exist.json"), "does_not_exist.json"},
        Case{"--medium " + bad_grains, "bad.csv"}, Case{"--kind lattice", "kind"}, Case{"--x0 inf", "x0"},
        Case{"--width 1e12 --height 1e12", "width = 1e+12: must be in (0, 1e9]"},
        Case{"--width 1e6 --height 1e6", "1e7"}}) {
    std::filesystem::remove(out);
    const Result r = run("simulate --droplets 2 --runs " + out + " " + c.args);
    SCOPED_TRACE(c.args + " -> " + r.err);
    EXPECT_NE(r.code, 0);
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1);
    EXPECT_EQ(r.err.rfind("softdrop: error: ", 0), 0u);
    EXPECT_NE(r.err.find(c.names), std::string::npos);
    EXPECT_FALSE(std::filesystem::exists(out));
  }
}

// Progress lines say how far a command is in percent (and, before the end, its ETA); the last one
// is always written, and with stderr in a pipe each is a plain line.
TEST(Cli, ProgressLinesEndAtOneHundredPercent) {
  const Result sim = run("simulate --droplets 4 --porosity 0.9");
  ASSERT_EQ(sim.code, 0) << sim.err;
  EXPECT_NE(sim.err.find("simulate: droplets done: 4/4 (100 %)\n"), std::string::npos) << sim.err;
  EXPECT_EQ(sim.err.find('\r'), std::string::npos) << "a pipe gets plain lines";
  const std::string db = softdrop::test::temp_path("progress.db");
  std::filesystem::remove(db);
  const Result opt = run("optimize --db " + db + softdrop::test::kSmallScene +
                         " --generations 3 --starts 4 --validate-starts 4 --stuck-window 0.1 --stuck-distance 1");
  ASSERT_EQ(opt.code, 0) << opt.err;
  EXPECT_NE(opt.err.find("generation 3/3"), std::string::npos) << opt.err;
  EXPECT_NE(opt.err.find(" 100 %\n"), std::string::npos) << opt.err;
  for (const auto* suffix : {"", "-wal", "-shm"}) std::filesystem::remove(db + suffix);
}

TEST(Cli, OutputIntoMissingDirectoryFailsBeforeRunning) {
  const Result r = run("simulate --runs /nonexistent_dir/x.csv");
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.err.find("--runs"), std::string::npos) << r.err;
}

TEST(Cli, SimulateWritesJsonSummaryAndCsvFiles) {
  const std::string runs = temp("ok_runs.csv"), medium = temp("ok_medium.json"), paths = temp("ok_paths.csv");
  const Result r = run("simulate --droplets 3 --seed 4 --format json --runs " + runs + " --save-medium " + medium +
                       " --paths " + paths);
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["droplets"], 3);
  EXPECT_EQ(j["passed"].get<int>() + j["stuck"].get<int>() + j["timeout"].get<int>() + j["diverged"].get<int>(), 3);
  std::ifstream in(runs);
  std::string line;
  int lines = 0;
  while (std::getline(in, line)) ++lines;
  EXPECT_EQ(lines, 4);
  // The saved medium reproduces the same numbers when loaded.
  const Result again = run("simulate --droplets 3 --seed 4 --format json --medium " + medium);
  ASSERT_EQ(again.code, 0) << again.err;
  const auto k = nlohmann::json::parse(again.out);
  EXPECT_EQ(j["mean_tortuosity"], k["mean_tortuosity"]);
  EXPECT_EQ(j["medium"]["porosity"], k["medium"]["porosity"]);
  EXPECT_TRUE(std::filesystem::exists(paths));
}

// A standard error needs two passed droplets. With one, the table says there is none (not "+- 0")
// and the JSON holds null; with more, both give the same number.
TEST(Cli, SimulateGivesNoStandardErrorForOnePassedDroplet) {
  const std::string one = "simulate --porosity 0.7 --droplets 5 --seed 6";
  const Result table = run(one), json = run(one + " --format json");
  ASSERT_EQ(table.code, 0) << table.err;
  ASSERT_EQ(json.code, 0) << json.err;
  const auto j = nlohmann::json::parse(json.out);
  ASSERT_EQ(j["passed"], 1) << "the scene no longer passes exactly one droplet: pick another";
  EXPECT_TRUE(j["standard_error"].is_null());
  EXPECT_NE(table.out.find(" (one droplet passed: no standard error)\n"), std::string::npos) << table.out;
  EXPECT_EQ(table.out.find("+-"), std::string::npos) << table.out;

  const Result many = run("simulate --porosity 0.9 --droplets 5 --seed 3");
  ASSERT_EQ(many.code, 0) << many.err;
  const auto k = nlohmann::json::parse(run("simulate --porosity 0.9 --droplets 5 --seed 3 --format json").out);
  ASSERT_GT(k["passed"].get<int>(), 1);
  std::ostringstream se;
  se << " +- " << k["standard_error"].get<double>() << " (standard error)\n";
  EXPECT_NE(many.out.find(se.str()), std::string::npos) << many.out;
}

TEST(Cli, ConfigFileSetsOptions) {
  const std::string config = temp("config.toml");
  std::ofstream(config) << "porosity = 0.9\nradius = 8\n";
  const Result r = run("simulate --config " + config + " --x0 100 --format json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_NEAR(j["medium"]["porosity"].get<double>(), 0.9, 0.01);
  const std::string bad = temp("bad_config.toml");
  std::ofstream(bad) << "porosity = 2\n";
  const Result b = run("simulate --config " + bad);
  EXPECT_NE(b.code, 0);
  EXPECT_NE(b.err.find("porosity"), std::string::npos) << b.err;
}

// TOML as TOML: a quoted '#' is a character of the string, arrays are lists, tables name commands;
// a file that is not TOML is refused naming its line; .ini files are read as INI.
TEST(Cli, ConfigFilesAreRealToml) {
  const std::string toml = temp("colours.toml"), svg = temp("colours.svg");
  std::ofstream(toml) << "# a comment\ngrain-colour = \"#ff0000\"  # red\n"
                         "porosity = 0.9\nwidth = 100\nheight = 100\nsize = 50\nno-caption = true\n";
  const Result c = run("render medium --config " + toml + " -o " + svg);
  ASSERT_EQ(c.code, 0) << c.err;
  std::ifstream in(svg);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("rgb(100%,0%,0%)"), std::string::npos) << "the grains are drawn in the quoted colour";
  const std::string sweep = temp("sweep_config.toml"), db = temp("sweep_config.db");
  std::filesystem::remove(db);
  std::ofstream(sweep) << "[sweep]\nporosities = [0.8, 0.9]\nmedia = 1\ndroplets = 2\npreset = \"quick\"\n";
  const Result s = run("sweep --config " + sweep + " --db " + db + " --quiet --format json");
  ASSERT_EQ(s.code, 0) << s.err;
  EXPECT_EQ(nlohmann::json::parse(s.out).size(), 2u);  // one point a porosity of the array
  const std::string not_toml = temp("not_toml.toml"), ini = temp("plain.ini");
  std::ofstream(not_toml) << "porosity = 0.8\nkind = non-overlapping\n";
  const Result n = run("simulate --config " + not_toml);
  EXPECT_EQ(n.code, 2);
  EXPECT_EQ(std::count(n.err.begin(), n.err.end(), '\n'), 1) << n.err;
  EXPECT_NE(n.err.find("config file '" + not_toml + "' line 2, column"), std::string::npos) << n.err;
  std::ofstream(ini) << "porosity = 0.8\nkind = non-overlapping\n";
  EXPECT_EQ(run("--check simulate --config " + ini).code, 0);
}

// A command's own table is the later, more specific value: it beats a top-level key (TOML puts
// those first), and the command line beats both.
TEST(Cli, ACommandsTableBeatsTopLevelKeysAndTheCommandLineBeatsBoth) {
  const std::string config = temp("precedence.toml");
  std::ofstream(config) << "porosity = 0.6\nwidth = 200\nheight = 200\n[simulate]\nporosity = 0.9\n";
  auto porosity = [](const std::string& args) {
    const Result r = run("simulate --droplets 1 --format json " + args);
    EXPECT_EQ(r.code, 0) << r.err;
    return nlohmann::json::parse(r.out)["medium"]["porosity"].get<double>();
  };
  const double from_table = porosity("--config " + config);
  EXPECT_EQ(from_table, porosity("--width 200 --height 200 --porosity 0.9"));
  EXPECT_NE(from_table, porosity("--width 200 --height 200 --porosity 0.6"));
  EXPECT_EQ(porosity("--config " + config + " --porosity 0.7"), porosity("--width 200 --height 200 --porosity 0.7"));
}

TEST(Cli, HelpDocumentsUnitsAndDefaults) {
  const Result r = run("simulate --help");
  EXPECT_EQ(r.code, 0);
  EXPECT_NE(r.out.find("--dt"), std::string::npos);
  EXPECT_NE(r.out.find("time units"), std::string::npos);
  EXPECT_NE(r.out.find("6e-06"), std::string::npos);
}

}  // namespace
