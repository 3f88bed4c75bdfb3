// What the commands say of a search's kept arrangement: `history --best`, `export`, `validate`,
// `render search` and the exported simulate config quote the same in-search value and the same
// held-out value; a robust objective's config replays the held-out starts, so that simulate gives
// the stored <T> to the bit.
#include <SQLiteCpp/SQLiteCpp.h>
#include <gtest/gtest.h>

#include <fstream>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "search_cli.hpp"

namespace {
using namespace softdrop::test;

const std::string kKeptBase = kSmallScene + " --seed 7 --stuck-window 0.1 --stuck-distance 1 --quiet ";
const std::string kKeptRobust =
    kKeptBase + " --objective mean --starts 4 --lambda 2 --strategy es --validate-starts 12";

std::string text_of(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string shortest(double v) {  // as the program writes a value in full (fmt with 17 digits)
  std::ostringstream s;
  s << std::setprecision(17) << v;
  return s.str();
}

// The last row of history --best: the best's in-search value and held-out value.
nlohmann::json best_row(const std::string& db) {
  const Result r = run("history --db " + db + " --run 1 --best --format json");
  EXPECT_EQ(r.code, 0) << r.err;
  return nlohmann::json::parse(r.out).back();
}

TEST(KeptArrangement, ARobustRunsExportReplaysItsHeldOutStartsAndEveryCommandQuotesTheSameValues) {
  const std::string db = fresh("kept_robust.db");
  const Result o = run("optimize --db " + db + kKeptRobust + " --generations 6 --format json");
  ASSERT_EQ(o.code, 0) << o.err;
  const nlohmann::json summary = nlohmann::json::parse(o.out);
  const nlohmann::json best = best_row(db);
  const double in_search = best.at("best_tortuosity").get<double>();
  const double held_out = best.at("held_out_tortuosity").get<double>();
  EXPECT_EQ(in_search, summary.at("best_tortuosity").get<double>());
  EXPECT_EQ(held_out, summary.at("held_out").at("mean_tortuosity").get<double>());
  EXPECT_EQ(best.at("held_out_starts"), 12);
  const auto runs = nlohmann::json::parse(run("history --db " + db + " --format json").out);  // the runs table too
  EXPECT_EQ(runs.at(0).at("held_out_tortuosity").get<double>(), held_out);
  EXPECT_EQ(runs.at(0).at("best_tortuosity").get<double>(), in_search);

  // The config has no start; it pushes the 12 held-out droplets, and simulate gives their <T>.
  const std::string grains = fresh("kept_robust.json"), config = fresh("kept_robust.toml");
  const Result e = run("export --db " + db + " --run 1 -o " + grains + " --simulate-config " + config);
  ASSERT_EQ(e.code, 0) << e.err;
  const std::string toml = text_of(config);
  EXPECT_EQ(toml.find("\nx0 = "), std::string::npos) << toml;
  EXPECT_NE(toml.find("\ndroplets = 12\nseed = 1\n"), std::string::npos) << toml;
  EXPECT_NE(toml.find("T = " + shortest(in_search) + " in the search: mean over 4 starts"), std::string::npos) << toml;
  EXPECT_NE(e.err.find("replays the 12 random starts (seed 1) of its held-out value"), std::string::npos) << e.err;
  const Result s = run("simulate --config " + config + " --quiet --format json");
  ASSERT_EQ(s.code, 0) << s.err;
  EXPECT_EQ(nlohmann::json::parse(s.out).at("mean_tortuosity").get<double>(), held_out) << s.out;

  // validate quotes the same in-search value.
  const Result v = run("validate --db " + db + " --run 1 --starts 6 --same-dt-only --quiet --format json");
  ASSERT_EQ(v.code, 0) << v.err;
  EXPECT_EQ(nlohmann::json::parse(v.out).at("source").at("in_search_tortuosity").get<double>(), in_search);
  // That value of 6 starts does not displace the one of 12; one of 24 does, in every command.
  EXPECT_EQ(best_row(db).at("held_out_starts"), 12);
  ASSERT_EQ(run("validate --db " + db + " --run 1 --starts 24 --same-dt-only --quiet").code, 0);
  EXPECT_EQ(best_row(db).at("held_out_starts"), 24);
  ASSERT_EQ(run("export --db " + db + " --run 1 -o " + grains + " --simulate-config " + config).code, 0);
  EXPECT_NE(text_of(config).find("\ndroplets = 24\n"), std::string::npos);

  // render search draws held-out droplets, and its caption and chart say both values.
  const std::string picture = fresh("kept_robust.svg"), chart = fresh("kept_robust_curve.svg");
  const Result r =
      run("render search --db " + db + " --run 1 --droplets 5 --quiet -o " + picture + " --curve " + chart);
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string svg = text_of(picture);
  EXPECT_NE(svg.find("in the search (mean over 4 starts, "), std::string::npos);
  EXPECT_NE(svg.find("held out: &lt;T&gt; = "), std::string::npos);
  EXPECT_NE(svg.find("over 24 random starts"), std::string::npos);
  EXPECT_NE(svg.find("5 held-out paths"), std::string::npos);
  EXPECT_NE(text_of(chart).find("held out: &lt;T&gt; over 24 random starts"), std::string::npos);
  // A run with no held-out value: its paths are those validate would take, and named so.
  const std::string unvalidated = fresh("kept_unvalidated.db");
  ASSERT_EQ(run("optimize --db " + unvalidated + kKeptBase +
                " --objective mean --starts 4 --lambda 2 --strategy es --validate-starts 0 --generations 1")
                .code,
            0);
  ASSERT_EQ(run("render search --db " + unvalidated + " --run 1 --droplets 3 --quiet -o " + picture).code, 0);
  EXPECT_NE(text_of(picture).find("3 paths from random starts"), std::string::npos);
  EXPECT_EQ(text_of(picture).find("held out:"), std::string::npos);
}

TEST(KeptArrangement, TheSingleObjectivesExportAndPictureKeepItsOneDroplet) {
  const std::string db = fresh("kept_single.db");
  ASSERT_EQ(
      run("optimize --db " + db + kKeptBase + " --objective single --lambda 2 --validate-starts 8 --generations 4")
          .code,
      0);
  const nlohmann::json best = best_row(db);
  const std::string grains = fresh("kept_single.json"), config = fresh("kept_single.toml");
  ASSERT_EQ(run("export --db " + db + " --run 1 -o " + grains + " --simulate-config " + config).code, 0);
  const std::string toml = text_of(config);
  EXPECT_NE(toml.find("\nx0 = "), std::string::npos) << toml;
  EXPECT_EQ(toml.find("\ndroplets = "), std::string::npos) << toml;
  const Result s = run("simulate --config " + config + " --format json");
  ASSERT_EQ(s.code, 0) << s.err;
  EXPECT_EQ(nlohmann::json::parse(s.out).at("run").at("tortuosity").get<double>(),
            best.at("best_tortuosity").get<double>());
  const std::string picture = fresh("kept_single.svg");
  ASSERT_EQ(run("render search --db " + db + " --run 1 -o " + picture).code, 0);
  const std::string svg = text_of(picture);
  EXPECT_NE(svg.find("in the search (one droplet from x0 = W/2)"), std::string::npos);
  EXPECT_NE(svg.find("over 8 random starts"), std::string::npos);
  const Result bad = run("render search --db " + db + " --run 1 --droplets 20000 -o " + picture);
  EXPECT_EQ(bad.code, 1);
  EXPECT_NE(bad.err.find("droplets = 20000: must be in [0, 1e4]"), std::string::npos) << bad.err;
}

}  // namespace
