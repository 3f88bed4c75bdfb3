// softdrop validate: the held-out value of a medium is the droplets of `simulate --droplets N`
// from the same starts, at dt and at dt/2, summarised exactly; a stored run is validated with its
// own droplet; bad input gets one line and writes nothing.
#include <SQLiteCpp/SQLiteCpp.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "search_cli.hpp"
#include "softdrop/batch.hpp"
#include "softdrop/medium.hpp"

namespace {
using namespace softdrop::test;

nlohmann::json json_of(const Result& r) {
  EXPECT_EQ(r.code, 0) << r.err;
  return nlohmann::json::parse(r.out);
}

// The passed droplets' T of a simulate --format json run.
std::vector<double> passed_t(const nlohmann::json& j) {
  std::vector<double> t;
  for (const auto& r : j["runs"])
    if (r["outcome"] == "passed") t.push_back(r["tortuosity"].get<double>());
  return t;
}

TEST(Validate, IsTheSimulateBatchOfTheSameStartsAtBothTimeSteps) {
  const std::string medium = fresh("validate_medium.json");
  ASSERT_EQ(run("simulate --x0 250 --porosity 0.85 --width 300 --height 300 --save-medium " + medium).code, 0);
  const std::string starts = " --droplets 24 --seed 9 --format json";
  const nlohmann::json v = json_of(run("validate --medium " + medium + " --starts 24 --seed 9 --format json --quiet"));
  const nlohmann::json at_dt = json_of(run("simulate --medium " + medium + starts));
  const nlohmann::json at_half =
      json_of(run("simulate --medium " + medium + starts + " --dt 3e-6 --max-steps 24000000"));
  EXPECT_EQ(v["at_dt"]["dt"].get<double>(), 6e-6);
  EXPECT_EQ(v["at_half_dt"]["dt"].get<double>(), 3e-6);
  EXPECT_EQ(v["at_dt"]["passed"], at_dt["passed"]);
  EXPECT_EQ(v["at_dt"]["mean_tortuosity"], at_dt["mean_tortuosity"]);
  EXPECT_EQ(v["at_dt"]["standard_error"], at_dt["standard_error"]);
  EXPECT_EQ(v["at_half_dt"]["mean_tortuosity"], at_half["mean_tortuosity"]);
  EXPECT_EQ(v["at_dt"]["pass_fraction"].get<double>(), at_dt["passed"].get<double>() / 24);
  // The median of the passed droplets' T, as numpy.quantile computes it.
  std::vector<double> t = passed_t(at_dt);
  ASSERT_GE(t.size(), 3u);
  std::sort(t.begin(), t.end());
  const double h = 0.5 * static_cast<double>(t.size() - 1);
  const auto lo = static_cast<std::size_t>(h);
  EXPECT_DOUBLE_EQ(v["at_dt"]["median"].get<double>(), t[lo] + (h - static_cast<double>(lo)) * (t[lo + 1] - t[lo]));
  EXPECT_LE(v["at_dt"]["q1"].get<double>(), v["at_dt"]["median"].get<double>());
  EXPECT_LE(v["at_dt"]["median"].get<double>(), v["at_dt"]["q3"].get<double>());
  // The shift is over the starts that passed at both time steps.
  double sum = 0;
  int paired = 0;
  for (std::size_t i = 0; i < 24; ++i)
    if (at_dt["runs"][i]["outcome"] == "passed" && at_half["runs"][i]["outcome"] == "passed")
      sum += at_half["runs"][i]["tortuosity"].get<double>() - at_dt["runs"][i]["tortuosity"].get<double>(), ++paired;
  EXPECT_EQ(v["dt_shift"]["paired"], paired);
  EXPECT_DOUBLE_EQ(v["dt_shift"]["mean"].get<double>(), sum / paired);
  // Without the second time step there is no second record.
  const nlohmann::json once =
      json_of(run("validate --medium " + medium + " --starts 24 --seed 9 --same-dt-only --format json --quiet"));
  EXPECT_FALSE(once.contains("at_half_dt"));
  EXPECT_EQ(once["at_dt"], v["at_dt"]);
}

TEST(Validate, AStoredRunIsValidatedWithItsOwnDroplet) {
  const std::string db = fresh("validate_run.db"), best = fresh("validate_best.json");
  ASSERT_EQ(run("optimize --db " + db + kScene + " --generations 4").code, 0);
  ASSERT_EQ(run("export --db " + db + " --run 1 -o " + best).code, 0);
  const nlohmann::json stored = json_of(run("validate --db " + db + " --run 1 --starts 8 --format json --quiet"));
  // The same arrangement as a grain file, with the balloon the scene's run used.
  const nlohmann::json file =
      json_of(run("validate --medium " + best + " --starts 8 --format json --quiet" + kBalloonOptions));
  EXPECT_EQ(stored["at_dt"], file["at_dt"]);
  EXPECT_EQ(stored["at_half_dt"], file["at_half_dt"]);
  EXPECT_EQ(stored["source"]["run"], 1);
  EXPECT_TRUE(stored["source"]["in_search_tortuosity"].is_number());
}

// The end of a search stores its best's held-out value: what validate computes for it, shown by
// history --best and export beside the in-search T.
TEST(Validate, ASearchStoresItsBestsHeldOutValue) {
  const std::string db = fresh("validate_end.db");
  const Result r = run("optimize --db " + db + kScene + " --generations 3 --validate-starts 16 --format json");
  const nlohmann::json end = json_of(r);
  ASSERT_TRUE(end["held_out"].is_object()) << r.out;
  EXPECT_EQ(end["held_out"]["starts"], 16);
  EXPECT_EQ(end["held_out"]["generation"], end["best_generation"]);
  const nlohmann::json again = json_of(run("validate --db " + db + " --run 1 --starts 16 --format json --quiet"));
  EXPECT_EQ(end["held_out"]["mean_tortuosity"], again["at_dt"]["mean_tortuosity"]);
  EXPECT_EQ(end["held_out"]["half_dt_mean_tortuosity"], again["at_half_dt"]["mean_tortuosity"]);
  const nlohmann::json best = json_of(run("history --db " + db + " --run 1 --best --format json"));
  const nlohmann::json& last = best.back();
  EXPECT_EQ(last["generation"], end["best_generation"]);
  EXPECT_EQ(last["held_out_tortuosity"], again["at_dt"]["mean_tortuosity"]);
  EXPECT_EQ(last["held_out_starts"], 16);
  EXPECT_TRUE(best.front()["held_out_tortuosity"].is_null() || best.size() == 1);
  const Result e = run("export --db " + db + " --run 1 -o " + fresh("validate_end.json"));
  EXPECT_NE(e.err.find("export: held out, <T> = "), std::string::npos) << e.err;
  EXPECT_NE(e.err.find(" over 16 random starts"), std::string::npos) << e.err;
  // validate stores what it computes for any generation; the same again replaces it.
  ASSERT_EQ(run("validate --db " + db + " --run 1 --generation 0 --starts 8 --quiet").code, 0);
  ASSERT_EQ(run("validate --db " + db + " --run 1 --generation 0 --starts 8 --quiet").code, 0);
  SQLite::Database d(db, SQLite::OPEN_READONLY);
  EXPECT_EQ(d.execAndGet("SELECT count(*) FROM validations WHERE generation = 0").getInt(), 1);
  EXPECT_EQ(d.execAndGet("SELECT count(*) FROM validations").getInt(), 2);
  // Islands: the best island's best, stored with its run.
  const std::string islands = fresh("validate_islands.db");
  const nlohmann::json isl = json_of(
      run("optimize --db " + islands + kScene + " --islands 2 --generations 3 --validate-starts 8 --format json"));
  ASSERT_TRUE(isl["held_out"].is_object());
  SQLite::Database di(islands, SQLite::OPEN_READONLY);
  EXPECT_EQ(di.execAndGet("SELECT count(*) FROM validations").getInt(), 1);
  EXPECT_EQ(di.execAndGet("SELECT run_id FROM validations").getInt64(), isl["best_run"].get<std::int64_t>());
  // --validate-starts 0 asks for none.
  const std::string none = fresh("validate_none.db");
  ASSERT_EQ(run("optimize --db " + none + kScene + " --generations 2").code, 0);
  EXPECT_EQ(SQLite::Database(none, SQLite::OPEN_READONLY).execAndGet("SELECT count(*) FROM validations").getInt(), 0);
  EXPECT_EQ(run("optimize --db " + none + kScene + " --generations 2 --validate-starts -1").code, 1);
}

TEST(Validate, BadInputGetsOneLineAndWritesNothing) {
  const std::string db = fresh("validate_bad.db"), medium = fresh("validate_bad.json"),
                    out = fresh("validate_out.json");
  ASSERT_EQ(run("optimize --db " + db + kScene + " --generations 2").code, 0);
  ASSERT_EQ(run("export --db " + db + " --run 1 -o " + medium).code, 0);
  for (const auto& [args, says] : std::vector<std::pair<std::string, std::string>>{
           {"validate", "give --medium FILE or --db FILE --run N"},
           {"validate --medium " + medium + " --db " + db + " --run 1", "give --medium FILE or --db FILE --run N"},
           {"validate --db " + db, "run: --db needs --run"},
           {"validate --medium " + medium + " --starts 0", "starts = 0: must be in [1, 1e6]"},
           {"validate --db " + db + " --run 1 --nrt 1e9", "nrt: the run's droplet is stored with it"},
           {"validate --db " + db + " --run 1 --generation 9", "generation = 9: run 1 has stored generations 0 to 2"},
           {"validate --db " + db + " --run 7", "--run 7: no such run"},
           {"validate --medium " + db, "grain file"},
           {"validate --medium " + medium + " --runs " + medium,
            "--runs '" + medium + "': the same file as --medium"}}) {
    SCOPED_TRACE(args);
    const Result r = run(args + " --json " + out);
    EXPECT_GT(r.code, 0);
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(says), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(out));
  }
}

TEST(Validate, TheLibraryRefusesBadOptionsByName) {
  softdrop::HeldOutOptions o;
  std::string why;
  EXPECT_TRUE(o.IsValid(&why));
  o.starts = softdrop::kMaxHeldOutStarts + 1;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_NE(why.find("starts = 1000001"), std::string::npos) << why;
  o.starts = 10, o.threads = -1;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_NE(why.find("threads = -1"), std::string::npos) << why;
}

}  // namespace
