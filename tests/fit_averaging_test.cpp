// The two averagings of a porosity's <T> over its media, through the command line: pooled over the
// passed droplets (mean_tortuosity) and per medium first (per_medium_tortuosity). sweep-report's per-porosity
// columns must be the plain aggregates of its own per-medium rows, and `fit --mean per-medium`
// must fit exactly those points, from the store and from a sweep-report file alike.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

#include "cli_run.hpp"
#include "csv_table.hpp"

namespace softdrop {
namespace {

// Four porosities where some media pass few droplets, so the two averagings differ.
const std::string kSweep =
    " --porosities 0.7,0.8,0.9,0.95 --media 4 --droplets 5 --width 160 --height 160 "
    "--stuck-window 0.1 --quiet";

TEST(FitAveraging, PerMediumPointsAreTheMeanOfTheMediaRows) {
  const std::string db = test::fresh_path("avg.db"), points = test::fresh_path("avg_points.csv"),
                    media = test::fresh_path("avg_media.csv");
  ASSERT_EQ(test::run("sweep --db " + db + kSweep).code, 0);
  ASSERT_EQ(test::run("sweep-report --db " + db + " --format csv > " + points).code, 0);
  ASSERT_EQ(test::run("sweep-report --db " + db + " --media --format csv > " + media).code, 0);
  const test::CsvTable p = test::read_csv_table(points), m = test::read_csv_table(media);

  // Each medium's own mean T, gathered per target porosity over the media where one passed.
  std::map<std::string, std::vector<double>> by;
  for (std::size_t i = 0; i < m.rows.size(); ++i)
    if (m.number(i, "passed") > 0) by[m.cell(i, "target_porosity")].push_back(m.number(i, "mean_tortuosity"));
  int differ = 0;
  ASSERT_EQ(p.rows.size(), 4u);
  for (std::size_t i = 0; i < p.rows.size(); ++i) {
    const std::vector<double>& t = by[p.cell(i, "target_porosity")];
    ASSERT_GE(t.size(), 2u) << p.cell(i, "target_porosity");
    double sum = 0;
    for (double x : t) sum += x;
    const double mean = sum / static_cast<double>(t.size());
    double ss = 0;
    for (double x : t) ss += (x - mean) * (x - mean);
    const double se = std::sqrt(ss / static_cast<double>(t.size() - 1) / static_cast<double>(t.size()));
    // The CSV holds 17 significant digits; the per-medium rows were rounded once before this sum.
    EXPECT_NEAR(p.number(i, "per_medium_tortuosity"), mean, 1e-14);
    EXPECT_NEAR(p.number(i, "per_medium_standard_error"), se, 1e-14);
    EXPECT_EQ(p.number(i, "media_passed"), static_cast<double>(t.size()));
    differ += std::abs(p.number(i, "per_medium_tortuosity") - p.number(i, "mean_tortuosity")) > 1e-9;
  }
  EXPECT_GE(differ, 1);  // a medium that passed fewer droplets weighs less when pooled
}

TEST(FitAveraging, FitPerMediumFitsThosePointsFromTheStoreOrItsReport) {
  const std::string db = test::fresh_path("avgfit.db"), report = test::fresh_path("avgfit_report.csv"),
                    own = test::fresh_path("avgfit_own.csv");
  ASSERT_EQ(test::run("sweep --db " + db + kSweep).code, 0);
  ASSERT_EQ(test::run("sweep-report --db " + db + " --format csv > " + report).code, 0);
  const test::CsvTable p = test::read_csv_table(report);
  {
    std::ofstream out(own);  // the same points as a plain points file
    out.precision(17);
    out << "porosity,tortuosity,standard_error\n";
    for (std::size_t i = 0; i < p.rows.size(); ++i)
      out << p.cell(i, "porosity") << ',' << p.cell(i, "per_medium_tortuosity") << ','
          << p.cell(i, "per_medium_standard_error") << '\n';
  }
  const test::Result store = test::run("fit --db " + db + " --mean per-medium --format json");
  ASSERT_EQ(store.code, 0) << store.err;
  const test::Result file = test::run("fit --points " + report + " --mean per-medium --format json");
  ASSERT_EQ(file.code, 0) << file.err;
  const test::Result plain = test::run("fit --points " + own + " --format json");
  ASSERT_EQ(plain.code, 0) << plain.err;
  const test::Result pooled = test::run("fit --db " + db + " --format json");
  ASSERT_EQ(pooled.code, 0) << pooled.err;
  const auto s = nlohmann::json::parse(store.out), f = nlohmann::json::parse(file.out),
             o = nlohmann::json::parse(plain.out), q = nlohmann::json::parse(pooled.out);
  EXPECT_EQ(s["mean"], "per-medium");
  EXPECT_EQ(q["mean"], "pooled");
  for (const char* k : {"a", "b", "c"}) {
    EXPECT_NEAR(s["power"][k]["value"].get<double>(), o["power"][k]["value"].get<double>(), 1e-9) << k;
    EXPECT_NEAR(f["power"][k]["value"].get<double>(), o["power"][k]["value"].get<double>(), 1e-9) << k;
  }
  EXPECT_NE(s["power"]["chi2"], q["power"]["chi2"]);  // other points, another fit

  // The paper's f, nothing fitted, against the same points: its chi2 is the sum of the squared
  // distances in errors, with a degree of freedom a point.
  double chi2 = 0;
  for (std::size_t i = 0; i < p.rows.size(); ++i) {
    const double phi = p.number(i, "porosity");
    const double r = (p.number(i, "per_medium_tortuosity") - (1.58 - 0.58 * std::pow(phi, 3.87))) /
                     p.number(i, "per_medium_standard_error");
    EXPECT_NEAR(s["paper"]["residuals"][i].get<double>(), r, 1e-9);
    chi2 += r * r;
  }
  EXPECT_NEAR(s["paper"]["chi2"].get<double>(), chi2, 1e-9 * chi2);
  EXPECT_EQ(s["paper"]["dof"], p.rows.size());
  EXPECT_NE(test::run("fit --db " + db + " --mean per-medium").out.find("each medium's <T> first"), std::string::npos);

  // A per-medium mean has only the error over its media; an unknown averaging is a usage error.
  const test::Result both = test::run("fit --db " + db + " --mean per-medium --errors droplets");
  EXPECT_EQ(both.code, 1);
  EXPECT_NE(both.err.find("--errors droplets: a per-medium mean has only its error over the media"), std::string::npos)
      << both.err;
  const test::Result wrong = test::run("fit --db " + db + " --mean medians");
  EXPECT_EQ(wrong.code, 2);
  EXPECT_NE(wrong.err.find("--mean"), std::string::npos) << wrong.err;
  // A report from before the column existed is refused by name.
  const std::string old = test::fresh_path("avgfit_old.csv");
  std::ofstream(old) << "target_phi,phi,media,droplets,passed,mean_t,standard_error,media_passed,"
                        "media_standard_error,stuck_fraction\n0.8,0.8,4,20,18,1.3,0.01,4,0.02,0.1\n";
  const test::Result older = test::run("fit --points " + old + " --mean per-medium");
  EXPECT_EQ(older.code, 1);
  EXPECT_NE(older.err.find("no per_medium_tortuosity and per_medium_standard_error columns"), std::string::npos)
      << older.err;
}

// A reader of part of a sweep (a shard's store, a sweep stopped half way) is told whose figures it
// prints; a whole sweep's reader is not.
TEST(FitAveraging, AReportOfPartOfASweepSaysSo) {
  const std::string part = test::fresh_path("part.db"), whole = test::fresh_path("whole.db");
  ASSERT_EQ(test::run("sweep --db " + part + kSweep + " --shard 0/2").code, 0);
  ASSERT_EQ(test::run("sweep --db " + whole + kSweep).code, 0);
  for (const std::string command : {"sweep-report", "fit", "averagings"}) {
    const test::Result r = test::run(command + " --db " + part);
    EXPECT_EQ(r.code, 0) << command << ": " << r.err;
    EXPECT_NE(r.err.find("warning: sweep 1 in '" + part + "' holds 8 of its 16 media (status running; a shard's store"),
              std::string::npos)
        << command << ": " << r.err;
    EXPECT_EQ(test::run(command + " --db " + whole).err.find("holds"), std::string::npos) << command;
  }
}

}  // namespace
}  // namespace softdrop
