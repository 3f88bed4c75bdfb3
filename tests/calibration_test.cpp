// The calibration against the paper: scan grids, area traces, one setting's figures and score,
// determinism, and the command's bad input.
#include "studies/calibration.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <type_traits>

#include "cli_run.hpp"
#include "fixtures.hpp"
#include "studies/area_trace.hpp"

namespace {
using namespace softdrop;
using softdrop::test::run;
using softdrop::test::temp_path;

TEST(ScanAxis, ListsAndRanges) {
  EXPECT_EQ(parse_scan_axis("mass=0.01,0.1,1").values, (std::vector<double>{0.01, 0.1, 1}));
  EXPECT_EQ(parse_scan_axis("radius=4:10:4").values, (std::vector<double>{4, 6, 8, 10}));
  const ScanAxis log = parse_scan_axis("nrt=1e5:1e7:3:log");
  ASSERT_EQ(log.values.size(), 3u);
  EXPECT_EQ(log.values[0], 1e5);
  EXPECT_NEAR(log.values[1], 1e6, 1e-6);
  EXPECT_EQ(log.values[2], 1e7);  // the end is exact, not lo * (hi / lo)
  EXPECT_EQ(parse_scan_axis("masses=20,40").name, "masses");
}

TEST(ScanAxis, BadAxesNameWhatIsWrong) {
  struct Case {
    std::string text, says;
  };
  for (const Case& c :
       {Case{"mass", "expected name=values"}, Case{"colour=1", "unknown parameter 'colour'"},
        Case{"mass=", "no values"}, Case{"mass=1,,2", "'' is not a finite number"},
        Case{"mass=nan", "'nan' is not a finite number"}, Case{"mass=1,inf", "'inf' is not"},
        Case{"mass=1:0.1:3", "inverted range"}, Case{"mass=0.1:1:1", "n must be a whole number"},
        Case{"mass=0.1:1:2.5", "n must be"}, Case{"nrt=0:1e6:3:log", "log range needs lo > 0"},
        Case{"mass=1:2", "lo:hi:n"}, Case{"masses=20.5", "whole numbers"}, Case{"masses=1e300", "whole numbers"}}) {
    SCOPED_TRACE(c.text);
    try {
      parse_scan_axis(c.text);
      ADD_FAILURE() << "accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(c.says), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("scan '"), std::string::npos) << e.what();
    }
  }
}

// Every numeric field of the droplet's one field list can be scanned by its option name, and a
// setting of it changes that field and no other; the enum constraint-order cannot.
TEST(ScanAxis, EveryNumericDropletFieldCanBeScanned) {
  const std::vector<std::string> names = scan_parameter_names();
  for (const std::string key :
       {"masses", "radius", "gravity", "dt", "max-strain", "constraint-iterations", "viscosity-dilation"})
    EXPECT_NE(std::find(names.begin(), names.end(), key), names.end()) << key;
  EXPECT_EQ(std::find(names.begin(), names.end(), "constraint-order"), names.end());
  const DropletParams base;
  for (const std::string& name : names) {
    SCOPED_TRACE(name);
    const DropletParams set = apply_setting(base, name + "=3");
    int changed = 0;
    visit_droplet_fields(
        [&](const DropletField& field, const auto& before, const auto& after) {
          if constexpr (std::is_arithmetic_v<std::decay_t<decltype(before)>>) {
            if (field.key == name) {
              EXPECT_EQ(after, 3);
            }
            changed += before != after;
          } else {
            EXPECT_EQ(before, after);
          }
        },
        base, set);
    EXPECT_EQ(changed, 1);
  }
  EXPECT_THROW(parse_scan_axis("constraint-order=1"), std::invalid_argument);
}

TEST(ScanAxis, SettingsVaryTheFirstAxisSlowest) {
  const DropletParams base;
  const auto s = scan_settings(base, {parse_scan_axis("mass=1,2"), parse_scan_axis("masses=20,30,40")});
  ASSERT_EQ(s.size(), 6u);
  EXPECT_EQ(s[0].mass, 1);
  EXPECT_EQ(s[0].masses, 20);
  EXPECT_EQ(s[2].masses, 40);
  EXPECT_EQ(s[3].mass, 2);
  EXPECT_EQ(s[3].masses, 20);
  EXPECT_EQ(s[5].nrt, base.nrt);  // what is not scanned comes from the base
  EXPECT_EQ(scan_settings(base, {}).size(), 1u);
  const auto labels = scan_labels({parse_scan_axis("mass=1,2"), parse_scan_axis("masses=20,30,40")});
  ASSERT_EQ(labels.size(), 6u);
  EXPECT_EQ(labels[0], "mass=1 masses=20");
  EXPECT_EQ(labels[5], "mass=2 masses=40");
  EXPECT_EQ(scan_labels({}), (std::vector<std::string>{"defaults"}));
}

TEST(ScanAxis, ExplicitSettingsOverrideTheBase) {
  const DropletParams base;
  const DropletParams s = apply_setting(base, "radius=5.5  mass=0.5 masses=30 viscosity-dilation=0");
  EXPECT_EQ(s.viscosity_dilation, 0.0);  // the spared breathing mode can be scanned too
  EXPECT_EQ(s.radius, 5.5);
  EXPECT_EQ(s.mass, 0.5);
  EXPECT_EQ(s.masses, 30);
  EXPECT_EQ(s.nrt, base.nrt);
  const DropletParams same = apply_setting(base, "defaults");
  EXPECT_EQ(same.radius, base.radius);
  EXPECT_EQ(same.nrt, base.nrt);
  for (const std::string bad : {"", "mass=1,2", "mass=1:2:3", "bogus=1", "mass=x"}) {
    SCOPED_TRACE(bad);
    EXPECT_THROW(apply_setting(base, bad), std::invalid_argument);
  }
}

TEST(PaperCurve, IsThePapersFit) {
  EXPECT_DOUBLE_EQ(paper_tortuosity(1.0), 1.0);
  EXPECT_NEAR(paper_tortuosity(0.8), 1.58 - 0.58 * std::pow(0.8, 3.87), 1e-15);
  EXPECT_NEAR(paper_tortuosity(0.95), 1.10, 0.01);
  EXPECT_NEAR(paper_tortuosity(0.6), 1.50, 0.01);
}

Medium one_grain() {
  Medium m;
  m.width = m.height = 200;
  m.grains = {{100, 100, 12}};
  return m;
}

TEST(AreaTrace, BelongsToTheRunAndStartsAtS0) {
  DropletParams p;
  RunOptions run;
  const Medium medium = one_grain();
  const AreaTrace t = trace_area(p, medium, 100, run, 50);
  Simulation sim(p, medium);
  const RunSummary alone = sim.run(100, run);
  EXPECT_EQ(t.run.outcome, alone.outcome);
  EXPECT_EQ(t.run.steps, alone.steps);
  EXPECT_EQ(t.run.tortuosity, alone.tortuosity);
  ASSERT_FALSE(std::isnan(t.enter));
  EXPECT_GT(t.enter, 0);
  EXPECT_LE(t.min_ratio, 1.0);  // S0 itself is inside the range
  EXPECT_GE(t.max_ratio, 1.0);
  EXPECT_LT(t.min_ratio, 0.999);  // the grain squeezes it
  ASSERT_EQ(t.t.size(), t.area.size());
  EXPECT_EQ(t.t[1] - t.t[0], 50 * p.dt);
  if (t.run.outcome == Outcome::passed) {
    EXPECT_FALSE(std::isnan(t.leave));
    EXPECT_EQ(t.t.back(), t.leave);
  }
  EXPECT_THROW(trace_area(p, medium, 100, run, 0), std::invalid_argument);
}

TEST(Calibration, FiguresAddUpAndDoNotDependOnThreads) {
  const CalibrationOptions o = test::tiny_calibration();
  const DropletParams p;
  long calls = 0, last = 0, total = 0;
  const CalibrationResult a = run_calibration(o, p, 1, [&](long done, long all) { ++calls, last = done, total = all; });
  const CalibrationResult b = run_calibration(o, p, 2);
  EXPECT_EQ(total, 2 * 2 * 3 + 2);
  EXPECT_EQ(last, total);
  EXPECT_GT(calls, 1);
  ASSERT_EQ(a.points.size(), 2u);
  ASSERT_EQ(b.points.size(), 2u);
  double sum2 = 0, measured2 = 0;
  int within = 0, measured = 0;
  for (std::size_t i = 0; i < 2; ++i) {
    const CalibrationPoint& p1 = a.points[i];
    EXPECT_EQ(p1.droplets, 6);
    EXPECT_LE(p1.passed + p1.stuck + p1.diverged, p1.droplets);
    EXPECT_EQ(p1.paper_t, paper_tortuosity(p1.porosity));
    EXPECT_EQ(p1.mean_t, b.points[i].mean_t);  // bit for bit
    EXPECT_EQ(p1.standard_error, b.points[i].standard_error);
    EXPECT_EQ(p1.media_standard_error, b.points[i].media_standard_error);
    EXPECT_EQ(p1.media_passed, b.points[i].media_passed);
    EXPECT_LE(p1.media_passed, std::min(p1.passed, 2));  // 2 media a porosity
    EXPECT_EQ(p1.media_passed > 0, p1.passed > 0);
    if (p1.media_passed < 2) {
      EXPECT_EQ(p1.media_standard_error, 0);
    }
    const double miss = p1.passed >= 2 ? p1.mean_t - p1.paper_t : p1.paper_t - 1;
    sum2 += miss * miss;
    if (p1.passed >= 2) measured2 += miss * miss, ++measured;
    EXPECT_EQ(p1.within, p1.passed >= 2 && std::abs(miss) <= std::max(0.03, 2 * p1.media_standard_error));
    within += p1.within;
  }
  EXPECT_DOUBLE_EQ(a.rms_distance, std::sqrt(sum2 / 2));
  EXPECT_EQ(a.within, within);
  EXPECT_EQ(a.measured, measured);
  EXPECT_DOUBLE_EQ(a.measured_rms, measured ? std::sqrt(measured2 / measured) : 0.0);
  EXPECT_EQ(a.score, b.score);
  EXPECT_EQ(a.area_min, b.area_min);
  EXPECT_EQ(a.area_max, b.area_max);
  EXPECT_EQ(a.trace_runs, 2);
  EXPECT_EQ(a.resting_travel, b.resting_travel);
  EXPECT_EQ(a.comes_to_rest, a.resting_travel <= 0.01);
  EXPECT_DOUBLE_EQ(a.score, a.rms_distance + a.diverged_fraction + (a.comes_to_rest ? 0 : 1) +
                                0.05 * (a.area_both_sides ? 0 : 1) + 0.05 * a.stuck_fraction);
  EXPECT_EQ(a.area_both_sides, a.area_min < 0.95 && a.area_max > 1.02);
}

// A droplet whose gas pushes each mass hard (about 0.9 % of an edge a step here) buzzes against its
// contacts for ever; the same droplet with a third of the gas comes to rest on a floor.
TEST(Calibration, TheRestingTestTellsABuzzingDropletFromAResting) {
  DropletParams quiet = test::balloon_droplet(), buzzing = quiet;
  quiet.mass = buzzing.mass = 0.5;
  quiet.radius = buzzing.radius = 5.5;
  quiet.masses = buzzing.masses = 30;
  quiet.kc = buzzing.kc = 2e8;
  quiet.cc = buzzing.cc = 2e4;
  quiet.viscosity = buzzing.viscosity = 5000;
  quiet.nrt = 4e8;
  buzzing.nrt = 1.1e9;
  EXPECT_LT(resting_travel(quiet), 1e-6);
  EXPECT_GT(resting_travel(buzzing), 10.0);
}

// The model with every length S times as long and g fixed runs sqrt(S) times slower: k_s, k_c and
// nRT / S^2 keep the forces, k_d, c_c and nu over sqrt(S) keep the damping. At S = 4 every factor is
// a power of two, so the scaled droplet on the scaled floor repeats the droplet's resting test
// exactly, twice as fast.
TEST(Calibration, TheRestingTestScalesWithTheDroplet) {
  DropletParams quiet = test::balloon_droplet();
  quiet.mass = 0.5;
  quiet.radius = 5.5;
  quiet.masses = 30;
  quiet.kc = 2e8;
  quiet.cc = 2e4;
  quiet.viscosity = 5000;
  quiet.nrt = 4e8;
  DropletParams buzzing = quiet;
  buzzing.nrt = 1.1e9;  // buzzes against its contacts for ever (the test above)
  auto scaled_by_4 = [](DropletParams d) {
    d.radius *= 4, d.max_depth *= 4, d.nrt *= 4;
    d.ks /= 4, d.kc /= 4;
    d.kd /= 2, d.cc /= 2, d.viscosity /= 2, d.dt *= 2;
    return d;
  };
  const double buzz = resting_travel(buzzing);
  EXPECT_EQ(resting_travel(scaled_by_4(buzzing), 4), 2 * buzz);  // the same path, to the bit
  EXPECT_GT(buzz, 10.0);
  EXPECT_NE(resting_travel(scaled_by_4(buzzing), 1), 2 * buzz);  // on the default's floor it is not
  const double big_quiet = resting_travel(scaled_by_4(quiet), 4);
  EXPECT_EQ(big_quiet, 2 * resting_travel(quiet));
  EXPECT_LT(big_quiet, resting_limit(4));
  EXPECT_EQ(resting_limit(1), 0.01);
  EXPECT_EQ(resting_limit(4), 0.02);
  CalibrationOptions o = test::tiny_calibration();
  for (const double bad : {0.0, -1.0, std::nan(""), 2e6}) {
    o.rest_scale = bad;
    std::string why;
    EXPECT_FALSE(o.IsValid(&why)) << bad;
    EXPECT_EQ(why.rfind("rest-scale = ", 0), 0u) << why;
  }
}

TEST(Calibration, RefusesBadOptionsAndUnstableDroplets) {
  CalibrationOptions o = test::tiny_calibration();
  DropletParams p;
  p.mass = 1e-4;  // k_d dt / m = 73: the explicit damping would blow up
  EXPECT_THROW(run_calibration(o, p, 1), std::invalid_argument);
  o.trace_porosity = 1.5;
  EXPECT_THROW(run_calibration(o, DropletParams{}, 1), std::invalid_argument);
}

TEST(CalibrateCommand, WritesRankedSettingsAndPoints) {
  const std::string csv = temp_path("cal.csv"), points = temp_path("cal_points.csv"), plot = temp_path("cal.png");
  const auto r =
      run("calibrate --porosities 0.8 --media 1 --droplets 2 --width 200 --height 200 --trace-media 1 "
          "--trace-droplets 1 --scan nrt=1e8,6e8 --scan mass=1,1e-4 --skip-unstable --quiet --format csv "
          "--csv " +
          csv + " --points " + points + " --plot " + plot);
  ASSERT_EQ(r.code, 0) << r.err;
  std::ifstream in(csv);
  std::string header, line;
  std::getline(in, header);
  EXPECT_EQ(header.rfind("setting,status,masses,mass,radius,nrt,", 0), 0u) << header;
  int rows = 0, refused = 0;
  while (std::getline(in, line)) ++rows, refused += line.find(",\"refused: ") != std::string::npos;
  EXPECT_EQ(rows, 4);
  EXPECT_EQ(refused, 2);  // mass 1e-4 is unstable at the default dt (the reason is quoted: it has commas)
  // stdout ranks: the run settings first, by score; the refused last.
  std::istringstream out(r.out);
  std::getline(out, line);
  std::vector<std::string> order;
  while (std::getline(out, line)) order.push_back(line.substr(line.find(',') + 1, 3));
  EXPECT_EQ(order, (std::vector<std::string>{"ok,", "ok,", "\"re", "\"re"}));
  std::ifstream p(points);
  int point_rows = 0;
  while (std::getline(p, line)) ++point_rows;
  EXPECT_EQ(point_rows, 1 + 2);  // the two settings that ran, one porosity each
  EXPECT_TRUE(std::filesystem::exists(plot));
  // Explicit settings instead of a grid: one row each, in the order given.
  const auto two =
      run("calibrate --porosities 0.8 --media 1 --droplets 2 --width 200 --height 200 --trace-media 0 "
          "--quiet --setting 'radius=8 nrt=3e8' --setting 'wider: radius=9' --setting 'as given:' "
          "--radius 7 --csv " +
          csv);
  ASSERT_EQ(two.code, 0) << two.err;
  std::ifstream again(csv);
  std::vector<std::string> lines;
  while (std::getline(again, line)) lines.push_back(line);
  ASSERT_EQ(lines.size(), 4u);
  auto cells = [](const std::string& row) {
    std::vector<std::string> c;
    std::istringstream row_in(row);
    for (std::string cell; std::getline(row_in, cell, ',');) c.push_back(cell);
    return c;
  };
  // Every droplet field has its column, the time step and the breathing mode's share included.
  for (const std::string column : {",gravity,dt,max_strain,", ",constraint_order,", ",viscosity_dilation,"})
    EXPECT_NE(lines[0].find(column), std::string::npos) << lines[0];
  // setting, status, masses, mass, radius, nrt
  const auto first = cells(lines[1]), second = cells(lines[2]), third = cells(lines[3]);
  EXPECT_EQ(first[0] + first[1] + first[4] + first[5], "0ok83e+08") << lines[1];
  EXPECT_EQ(second[0] + second[1] + second[4], "1ok9") << lines[2];
  EXPECT_EQ(std::stod(second[5]), DropletParams{}.nrt);
  EXPECT_EQ(third[0] + third[1] + third[4], "2ok7") << lines[3];  // a name alone: --radius 7 as given
  EXPECT_EQ(first.back(), "radius=8 nrt=3e8");  // the label: the setting's text, or the name before ':'
  EXPECT_EQ(second.back(), "wider");
  EXPECT_EQ(third.back(), "as given");
  for (const auto& f : {csv, points, plot}) std::filesystem::remove(f);
}

TEST(CalibrateCommand, BadInputIsOneLineNamingIt) {
  struct Case {
    std::string args, says;
  };
  for (const Case& c :
       {Case{"--scan mass=1:0.1:3", "scan 'mass=1:0.1:3': inverted range"},
        Case{"--scan mass=", "scan 'mass=': no values"}, Case{"--scan viscosity=nan", "'nan' is not a finite number"},
        Case{"--scan mass=1 --scan mass=2", "mass scanned twice"},
        Case{"--scan mass=1,1e-4", "setting 1: dt = 6e-06: too large for the stiffness"},
        Case{"--porosities 0.5,1.2", "porosit"}, Case{"--trace-media -1", "trace-media = -1"},
        Case{"--best 0", "best = 0"}, Case{"--setting mass=1 --scan nrt=1e8", "--setting and --scan do not mix"},
        Case{"--setting 'mass=1,2'", "must give one value"},
        Case{"--setting 'soft m=1: mass=1'", "'soft' is not name=value (a label goes before"},
        Case{"--setting ' : '", "an empty name and no assignments"}, Case{"--medium x.json", "--medium is not used"}}) {
    SCOPED_TRACE(c.args);
    const auto r = run("calibrate --quiet " + c.args);
    EXPECT_NE(r.code, 0);
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(c.says), std::string::npos) << r.err;
  }
}

}  // namespace
