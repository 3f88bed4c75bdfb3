// `softdrop tortuosity`: the droplet's and the pore space's tortuosities of one medium, in a table,
// JSON and CSV that agree; an empty box gives 1; a medium with no pore path, or pixels too coarse
// for its grains, gets one line and writes nothing.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "cli_run.hpp"
#include "csv_table.hpp"

namespace softdrop {
namespace {

using test::fresh_path;
using test::run;

std::string grain_file(const std::string& name, const std::string& grains) {
  const std::string path = fresh_path(name);
  std::ofstream(path) << R"({"format": "softdrop-medium", "version": 1, "width": 100, "height": 100, )"
                      << R"("periodic": true, "grains": [)" << grains << "]}";
  return path;
}

TEST(TortuosityCli, TheTableJsonAndCsvAgreeAndAnEmptyBoxGivesOne) {
  const std::string json = fresh_path("tortuosity.json"), csv = fresh_path("tortuosity.csv");
  const auto r =
      run("tortuosity --porosity 0.75 --width 200 --height 200 --r-min 8 --r-max 16 --pixels 100 "
          "--starts 20 --quiet --json " +
          json + " --csv " + csv);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;
  const auto j = nlohmann::json::parse(std::ifstream(json));
  for (const char* q : {"geometric_tortuosity", "diffusive_tortuosity"}) {
    SCOPED_TRACE(q);
    const double coarse = j[q]["values"][0], fine = j[q]["values"][1];
    EXPECT_GE(coarse, 1.0);
    EXPECT_EQ(j[q]["extrapolated"].get<double>(), 2 * fine - coarse);
    EXPECT_EQ(j[q]["pixels"], nlohmann::json({100, 200}));
    EXPECT_LT(std::abs(fine - coarse) / coarse, 0.05);  // 8 and 16 pixels a smallest radius
  }
  const double per_radius = j["pixels_per_smallest_radius"][0];  // the smallest of radii 8 to 16, at 2 a pixel
  EXPECT_GE(per_radius, 4.0);
  EXPECT_LT(per_radius, 8.0);
  EXPECT_EQ(j["droplet_tortuosity"]["starts"], 20);
  EXPECT_NE(r.out.find("geometric T  "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("diffusive    tau = "), std::string::npos) << r.out;
  const test::CsvTable t = test::read_csv_table(csv);
  ASSERT_EQ(t.header, (std::vector<std::string>{"quantity", "pixels", "pixel", "value", "standard_error"}));
  ASSERT_EQ(t.rows.size(), 13u);  // four values at two resolutions and the extrapolation of each, and the droplet
  EXPECT_EQ(std::stod(t.rows[1][3]), j["diffusive_tortuosity"]["values"][0].get<double>());
  EXPECT_EQ(t.rows[2][0], "hydrodynamic_tortuosity");
  EXPECT_EQ(std::stod(t.rows[7][3]), j["permeability"]["values"][1].get<double>());
  EXPECT_EQ(t.rows[12][0], "droplet_tortuosity");
  // The flow bends round the grains, its T converged to 1 % between the two resolutions, and its
  // permeability to 10 % at these coarse pixels (it converges at first order with the staircase).
  const double flow = j["hydrodynamic_tortuosity"]["values"][1];
  EXPECT_GT(flow, 1.0);
  EXPECT_LT(std::abs(j["hydrodynamic_tortuosity"]["change"].get<double>()), 0.01);
  EXPECT_LT(std::abs(j["permeability"]["change"].get<double>()), 0.1);  // 4 and 8 pixels a smallest radius
  EXPECT_GT(j["permeability"]["values"][0].get<double>(), 0.0);
  EXPECT_NE(r.out.find("flow T       "), std::string::npos) << r.out;

  const std::string png = fresh_path("pore_space.png");
  const auto drawn =
      run("tortuosity --porosity 0.75 --width 200 --height 200 --r-min 8 --r-max 16 --pixels 100 "
          "--starts 0 --quiet --size 300 --picture " +
          png + " --flow-picture " + png + ".flow.png");
  ASSERT_EQ(drawn.code, 0) << drawn.err;
  EXPECT_GT(std::filesystem::file_size(png), 5000u);  // the field, the grains, the paths, the caption
  EXPECT_GT(std::filesystem::file_size(png + ".flow.png"), 5000u);
  EXPECT_NE(std::filesystem::file_size(png + ".flow.png"), std::filesystem::file_size(png));

  const auto empty = run("tortuosity --medium " + grain_file("empty.json", "") +
                         " --pixels 50 --starts 4 --quiet "
                         "--format json");
  ASSERT_EQ(empty.code, 0) << empty.err;
  const auto e = nlohmann::json::parse(empty.out);
  EXPECT_NEAR(e["geometric_tortuosity"]["values"][1].get<double>(), 1.0, 1e-12);
  EXPECT_NEAR(e["diffusive_tortuosity"]["values"][1].get<double>(), 1.0, 1e-9);
  EXPECT_EQ(e["hydrodynamic_tortuosity"]["values"][1].get<double>(), 1.0);
  EXPECT_TRUE(e["permeability"]["values"][1].is_null());  // infinite: nothing holds the flow back
  EXPECT_NEAR(e["droplet_tortuosity"]["mean_tortuosity"].get<double>(), 1.0,
              0.02);  // straight down, but for its own wobble
}

TEST(TortuosityCli, NoPorePathOrTooCoarsePixelsGetOneLineAndWriteNothing) {
  // A row of overlapping grains across the periodic box: no pore path from the top to the bottom.
  std::string row;
  for (int i = 0; i <= 10; ++i)
    row += std::string(i ? "," : "") + R"({"x": )" + std::to_string(10 * i) + R"(, "y": 50, "r": 8})";
  const std::string wall = grain_file("wall.json", row), json = fresh_path("never.json");
  struct Case {
    std::string args, says;
  };
  for (const Case& c :
       {Case{"--medium " + wall + " --pixels 100", "no pore path from the top to the bottom"},
        Case{"--medium " + wall + " --pixels 40", "pixels = 40: 3.2 pixels a radius of the smallest grain"},
        Case{"--porosity 0.8 --pixels 4", "pixels = 4: must be in [8, 4000]"},
        Case{"--porosity 0.8 --starts -1", "starts = -1"}}) {
    SCOPED_TRACE(c.args);
    const auto r = run("tortuosity " + c.args + " --quiet --json " + json);
    EXPECT_EQ(r.code, 1);
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(c.says), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(json));
  }
  // --check finds a resolution too coarse for the medium it would make, and a picture of the flow
  // without the flow, without running.
  for (const Case& c :
       {Case{"--porosity 0.8 --pixels 20", "pixels = 20: 0.681 pixels a radius of the smallest grain"},
        Case{"--porosity 0.8 --no-flow --flow-picture " + fresh_path("f.png"), "flow-picture: needs the flow"}}) {
    SCOPED_TRACE(c.args);
    const auto r = run("--check tortuosity " + c.args);
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find(c.says), std::string::npos) << r.err;
  }
  EXPECT_EQ(run("--check tortuosity --porosity 0.8 --pixels 200").code, 0);
}

}  // namespace
}  // namespace softdrop
