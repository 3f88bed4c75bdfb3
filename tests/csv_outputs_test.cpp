// Every CSV softdrop writes is one plain table (the tests' reader takes it with no special case,
// as pandas does), CSV and JSON use the same names, the two area traces share one schema, and the
// points of sweep-report are points fit reads.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>

#include "csv_table.hpp"
#include "search_cli.hpp"

namespace softdrop {
namespace {

using test::CsvTable;
using test::fresh;
using test::read_csv_table;
using test::run;

std::string contents(const std::string& path) {
  std::ifstream in(path);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

TEST(CsvOutputs, SimulateWritesPlainTablesAndItsJsonHasEveryDroplet) {
  const std::string runs = fresh("o_runs.csv"), paths = fresh("o_paths.csv"), trace = fresh("o_trace.csv"),
                    snaps = fresh("o_snaps.csv"), medium = fresh("o_medium.csv"), json = fresh("o_sim.json");
  const auto r = run("simulate --width 200 --height 200 --droplets 3 --seed 2 --runs " + runs + " --paths " + paths +
                     " --trace " + trace + " --snapshots " + snaps + " --snapshot-times 0.01 --save-medium " + medium +
                     " --json " + json + " --quiet");
  ASSERT_EQ(r.code, 0) << r.err;
  for (const std::string& f : {runs, paths, trace, snaps, medium}) {
    SCOPED_TRACE(f);
    EXPECT_NO_THROW(read_csv_table(f));
  }
  const CsvTable t = read_csv_table(trace);
  EXPECT_EQ(t.header, (std::vector<std::string>{"droplet", "time", "area", "area_ratio", "phase"}));
  std::set<std::string> droplets;
  for (std::size_t i = 0; i < t.rows.size(); ++i) droplets.insert(t.cell(i, "droplet"));
  EXPECT_EQ(droplets, (std::set<std::string>{"0", "1", "2"}));
  // The JSON holds each droplet's record under the --runs CSV's names, and the reason.
  const CsvTable rows = read_csv_table(runs);
  const auto j = nlohmann::json::parse(std::ifstream(json));
  ASSERT_EQ(j["runs"].size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    for (const std::string& column : rows.header) EXPECT_TRUE(j["runs"][i].contains(column)) << column;
    EXPECT_EQ(j["runs"][i]["outcome"], rows.cell(i, "outcome"));
    EXPECT_FALSE(j["runs"][i]["reason"].get<std::string>().empty());
  }
  // Shortest exact numbers: the start positions read back as the doubles of the JSON.
  for (std::size_t i = 0; i < 3; ++i) EXPECT_EQ(rows.number(i, "start_x"), j["runs"][i]["start_x"].get<double>());
}

TEST(CsvOutputs, BothAreaTracesAreOneSchemaAndTheSameNumbers) {
  const std::string a = fresh("o_trace_sim.csv"), b = fresh("o_trace_render.csv"), png = fresh("o_trace.png");
  const std::string pore = std::string(SOFTDROP_SOURCE_DIR) + "/examples/pore.json";
  ASSERT_EQ(run("simulate --medium " + pore + " --x0 100 --trace " + a + " --trace-interval 20").code, 0);
  ASSERT_EQ(run("render trace --medium " + pore + " --x0 100 --csv " + b + " -o " + png).code, 0);
  EXPECT_EQ(contents(a), contents(b));
  const CsvTable t = read_csv_table(a);
  std::set<std::string> phases;
  for (std::size_t i = 0; i < t.rows.size(); ++i) phases.insert(t.cell(i, "phase"));
  EXPECT_EQ(phases, (std::set<std::string>{"above", "inside", "below"}));
}

TEST(CsvOutputs, StoresReportPlainTablesAndFitReadsSweepReportPoints) {
  const std::string sweep = fresh("o_sweep.db"), points = fresh("o_points.csv"), groups = fresh("o_groups.csv");
  ASSERT_EQ(run("sweep --db " + sweep + " --preset quick --porosities 0.8,0.85,0.9,0.95 --quiet").code, 0);
  const auto report = run("sweep-report --db " + sweep + " --format csv");
  ASSERT_EQ(report.code, 0);
  std::ofstream(points) << report.out;
  EXPECT_NO_THROW(read_csv_table(points));
  const auto from_points = run("fit --points " + points + " --format json");
  const auto from_db = run("fit --db " + sweep + " --format json");
  ASSERT_EQ(from_points.code, 0) << from_points.err;
  EXPECT_EQ(nlohmann::json::parse(from_points.out)["power"], nlohmann::json::parse(from_db.out)["power"]);
  ASSERT_EQ(run("averagings --db " + sweep + " --csv " + groups).code, 0);
  EXPECT_NO_THROW(read_csv_table(groups));

  const std::string search = fresh("o_search.db");
  ASSERT_EQ(run("optimize --db " + search + test::kScene + " --generations 3").code, 0);
  for (const std::string& args : {std::string(" --run 1"), std::string(" --run 1 --candidates"),
                                  std::string(" --run 1 --best"), std::string("")}) {
    SCOPED_TRACE(args);
    const std::string out = fresh("o_history.csv");
    std::ofstream(out) << run("history --db " + search + args + " --format csv").out;
    EXPECT_NO_THROW(read_csv_table(out));
  }
}

}  // namespace
}  // namespace softdrop
