// The studies: sweep units and shards, deterministic records, the store (resume after SIGKILL,
// shards merged), fits recovering known laws, the two averagings' command.
#include "softdrop/sweep.hpp"

#include <SQLiteCpp/SQLiteCpp.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <thread>

#include "fixtures.hpp"
#include "search_cli.hpp"
#include "softdrop/store.hpp"
#include "store/params_json.hpp"
#include "studies/fit.hpp"
#include "studies/sweep_record_bytes.hpp"

namespace softdrop {
namespace {

using test::fresh;

SweepOptions tiny() {
  SweepOptions o;
  o.porosities = {0.85, 0.95};
  o.media = 3;
  o.droplets = 4;
  o.medium.width = o.medium.height = 150;
  o.medium.r_min = test::kBalloonRMin, o.medium.r_max = test::kBalloonRMax;  // (many grains in a small box)
  o.droplet = test::balloon_droplet();  // (a quick droplet: these tests are of the records)
  return o;
}

TEST(Sweep, ShardsPartitionTheUnits) {
  const SweepOptions o = tiny();
  const auto all = sweep_units(o);
  ASSERT_EQ(all.size(), 6u);
  std::vector<SweepUnit> joined;
  for (int s = 0; s < 4; ++s)
    for (const SweepUnit& u : sweep_units(o, s, 4)) {
      EXPECT_EQ(std::count(joined.begin(), joined.end(), u), 0);
      joined.push_back(u);
    }
  EXPECT_EQ(joined.size(), all.size());
  EXPECT_THROW(sweep_units(o, 2, 2), std::invalid_argument);
  // A unit's medium depends on its porosity's value, not on its position in the list.
  SweepOptions more = o;
  more.porosities = {0.75, 0.85, 0.95};
  EXPECT_EQ(sweep_medium_seed(o, {0, 1}), sweep_medium_seed(more, {1, 1}));
}

TEST(Sweep, UnitRecordsAreCompleteAndThreadIndependent) {
  const SweepOptions o = tiny();
  const SweepMedium a = run_sweep_unit(o, {0, 1}, 1), b = run_sweep_unit(o, {0, 1}, 2);
  ASSERT_EQ(a.droplets.size(), 4u);
  EXPECT_NEAR(a.porosity, 0.85, 0.02);
  EXPECT_EQ(a.porosity, b.porosity);
  EXPECT_EQ(a.passed + a.stuck + a.timeout + a.diverged, 4);
  for (std::size_t i = 0; i < a.droplets.size(); ++i) {
    EXPECT_EQ(a.droplets[i].start_x, b.droplets[i].start_x);
    EXPECT_EQ(a.droplets[i].outcome, b.droplets[i].outcome);
    EXPECT_EQ(a.droplets[i].tortuosity, b.droplets[i].tortuosity);
    EXPECT_EQ(a.droplets[i].steps, b.droplets[i].steps);
    if (a.droplets[i].outcome == Outcome::passed) {
      EXPECT_GE(a.droplets[i].tortuosity, 1.0 - 1e-9);  // a straight fall is 1 to rounding
    }
  }
  EXPECT_EQ(a.mean_t, b.mean_t);
}

TEST(Sweep, UnitsRunAcrossThreadsEqualUnitsRunOneByOne) {
  const SweepOptions o = tiny();
  const auto units = sweep_units(o);
  std::vector<SweepMedium> got;
  run_sweep_units(o, units, 3, [&](SweepMedium&& m) { got.push_back(std::move(m)); });
  ASSERT_EQ(got.size(), units.size());
  std::sort(got.begin(), got.end(), [](const SweepMedium& a, const SweepMedium& b) {
    return std::pair{a.unit.porosity, a.unit.medium} < std::pair{b.unit.porosity, b.unit.medium};
  });
  for (std::size_t i = 0; i < units.size(); ++i) {
    const SweepMedium one = run_sweep_unit(o, units[i], 1);
    SCOPED_TRACE("unit " + std::to_string(i));
    EXPECT_EQ(got[i].unit, one.unit);
    EXPECT_EQ(got[i].porosity, one.porosity);
    EXPECT_EQ(got[i].mean_t, one.mean_t);
    EXPECT_EQ(got[i].passed, one.passed);
    ASSERT_EQ(got[i].droplets.size(), one.droplets.size());
    for (std::size_t d = 0; d < one.droplets.size(); ++d) {
      EXPECT_EQ(got[i].droplets[d].start_x, one.droplets[d].start_x);
      EXPECT_EQ(got[i].droplets[d].tortuosity, one.droplets[d].tortuosity);
      EXPECT_EQ(got[i].droplets[d].steps, one.droplets[d].steps);
    }
  }
  // A stop request lets the units already started finish, complete, and starts no new one.
  int calls = 0;
  std::vector<SweepMedium> some;
  run_sweep_units(
      o, units, 2, [&](SweepMedium&& m) { some.push_back(std::move(m)); }, [&] { return ++calls > 2; });
  EXPECT_GE(some.size(), 1u);
  EXPECT_LT(some.size(), units.size());
  for (const SweepMedium& m : some) EXPECT_EQ(m.droplets.size(), 4u);
  // An error in the store's callback stops the run and reaches the caller.
  EXPECT_THROW(run_sweep_units(o, units, 2, [](SweepMedium&&) { throw std::runtime_error("disk full"); }),
               std::runtime_error);
}

TEST(Sweep, ARecordSentAsBytesArrivesBitForBit) {
  SweepMedium m = run_sweep_unit(tiny(), {1, 0}, 1);
  m.seconds = 0.1 + 0.2;  // not a short decimal
  m.droplets.push_back({7, std::nextafter(3.0, 4.0), Outcome::diverged, 0.0, -1, 0.1 + 0.2, std::nextafter(1.0, 2.0)});
  const std::string bytes = encode_sweep_medium(m);
  const SweepMedium back = decode_sweep_medium(bytes);
  EXPECT_EQ(back.unit, m.unit);
  EXPECT_EQ(std::memcmp(&back.porosity, &m.porosity, sizeof m.porosity), 0);
  EXPECT_EQ(back.grains, m.grains);
  EXPECT_EQ(back.medium_seed, m.medium_seed);
  EXPECT_EQ(back.passed, m.passed);
  EXPECT_EQ(back.stuck, m.stuck);
  EXPECT_EQ(back.mean_t, m.mean_t);
  EXPECT_EQ(back.standard_error, m.standard_error);
  EXPECT_EQ(back.seconds, m.seconds);
  ASSERT_EQ(back.droplets.size(), m.droplets.size());
  for (std::size_t i = 0; i < m.droplets.size(); ++i) {
    EXPECT_EQ(back.droplets[i].droplet, m.droplets[i].droplet);
    EXPECT_EQ(back.droplets[i].start_x, m.droplets[i].start_x);
    EXPECT_EQ(back.droplets[i].outcome, m.droplets[i].outcome);
    EXPECT_EQ(back.droplets[i].tortuosity, m.droplets[i].tortuosity);
    EXPECT_EQ(back.droplets[i].steps, m.droplets[i].steps);
    EXPECT_EQ(std::bit_cast<std::uint64_t>(back.droplets[i].shaken_at),
              std::bit_cast<std::uint64_t>(m.droplets[i].shaken_at));
    EXPECT_EQ(std::bit_cast<std::uint64_t>(back.droplets[i].route_tortuosity),
              std::bit_cast<std::uint64_t>(m.droplets[i].route_tortuosity));
  }
  EXPECT_EQ(encode_sweep_medium(back), bytes);
  // Anything but a whole record is refused.
  EXPECT_THROW(decode_sweep_medium(bytes.substr(0, bytes.size() - 1)), std::invalid_argument);
  EXPECT_THROW(decode_sweep_medium(bytes + "x"), std::invalid_argument);
  EXPECT_THROW(decode_sweep_medium(""), std::invalid_argument);
  std::string bad_outcome = bytes;
  bad_outcome[bytes.size() - 8 - 8 - 8 - 8 - 8 - 4] = 9;  // the last droplet's outcome (then: no second droplets)
  EXPECT_THROW(decode_sweep_medium(bad_outcome), std::invalid_argument);
}

TEST(Sweep, ParamsRoundTripExactly) {
  SweepOptions o = tiny();
  o.medium.kind = MediumKind::non_overlapping;
  o.medium.periodic = false;
  o.porosities = {0.1 + 0.2, 0.9};
  const std::string j = sweep_params_to_json(o);
  const SweepOptions back = sweep_params_from_json(j);
  EXPECT_EQ(back.porosities, o.porosities);
  EXPECT_EQ(back.medium.kind, MediumKind::non_overlapping);
  EXPECT_FALSE(back.medium.periodic);
  EXPECT_EQ(sweep_params_to_json(back), j);
}

// Synthetic data from a law with Gaussian noise of known size.
std::vector<FitPoint> synthetic(FitLaw law, const std::vector<double>& p, double noise, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> n(0, noise);
  std::vector<FitPoint> pts;
  for (int i = 0; i < 12; ++i) {
    const double phi = 0.45 + 0.05 * i;
    pts.push_back({phi, fit_law_value(law, p, phi) + n(rng), noise});
  }
  return pts;
}

TEST(Fit, RecoversThePaperLawFromNoisyData) {
  const std::vector<double> truth{1.58, 3.87, 0.58};
  int within = 0;
  for (unsigned seed = 1; seed <= 5; ++seed) {
    const auto pts = synthetic(FitLaw::power, truth, 0.002, seed);
    const FitResult r = fit_law(FitLaw::power, pts);
    ASSERT_EQ(r.values.size(), 3u);
    for (int k = 0; k < 3; ++k) {
      EXPECT_LT(std::abs(r.values[k] - truth[k]), 5 * r.errors[k]) << r.names[k] << " seed " << seed;
      within += std::abs(r.values[k] - truth[k]) < 2 * r.errors[k];
    }
    EXPECT_GT(r.reduced_chi2, 0.2);
    EXPECT_LT(r.reduced_chi2, 3.0);
    EXPECT_LT(r.aic, fit_law(FitLaw::log, pts).aic) << "the true law must win";
  }
  EXPECT_GE(within, 12) << "about 95 % of 15 estimates should lie within 2 sigma";
}

TEST(Fit, RecoversTheLogLawAndRefusesBadPoints) {
  const auto pts = synthetic(FitLaw::log, {0.77}, 0.002, 9);
  const FitResult r = fit_law(FitLaw::log, pts);
  EXPECT_LT(std::abs(r.values[0] - 0.77), 4 * r.errors[0]);
  EXPECT_LT(r.errors[0], 0.01);
  EXPECT_EQ(r.residuals.size(), pts.size());
  EXPECT_EQ(r.dof, 11);
  // Exact data: chi2 vanishes and the parameter is exact.
  std::vector<FitPoint> exact;
  for (double phi : {0.5, 0.7, 0.9}) exact.push_back({phi, 1 - 0.5 * std::log(phi), 0.01});
  EXPECT_NEAR(fit_law(FitLaw::log, exact).values[0], 0.5, 1e-9);
  EXPECT_THROW(fit_law(FitLaw::power, {{0.5, 1.2, 0.01}, {0.6, 1.1, 0.01}}), std::invalid_argument);
  EXPECT_THROW(fit_law(FitLaw::log, {{0.5, 1.2, 0.0}}), std::invalid_argument);
  EXPECT_THROW(fit_law(FitLaw::log, {{1.5, 1.2, 0.1}}), std::invalid_argument);
}

// ---- the command line ----

using test::sweep_dump;

const std::string kQuick = " --preset quick --quiet --format json ";

TEST(SweepCli, QuickPresetEndToEnd) {
  const std::string db = fresh("quick.db");
  const test::Result r = test::run("sweep --db " + db + kQuick);
  ASSERT_EQ(r.code, 0) << r.err;
  const auto points = nlohmann::json::parse(r.out);
  ASSERT_EQ(points.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(points[i]["media"], 2);
    EXPECT_EQ(points[i]["droplets"], 16);
    EXPECT_GT(points[i]["passed"].get<int>(), 1);
  }
  // <T> rises as phi falls, from phi = 0.9 to 0.7 (16 droplets each are too few to order
  // neighbouring porosities).
  EXPECT_GT(points[0]["mean_tortuosity"].get<double>(), points[2]["mean_tortuosity"].get<double>());
  // Every record is complete.
  SQLite::Database d(db, SQLite::OPEN_READONLY);
  EXPECT_EQ(d.execAndGet("SELECT count(*) FROM sweep_droplets").getInt(), 48);
  EXPECT_EQ(d.execAndGet("SELECT count(*) FROM sweep_droplets WHERE (outcome = 'passed') != (tortuosity IS NOT NULL)")
                .getInt(),
            0);
  EXPECT_EQ(d.execAndGet("SELECT count(*) FROM sweep_droplets WHERE tortuosity < 1 - 1e-9 OR steps <= 0").getInt(), 0);
  EXPECT_EQ(
      d.execAndGet("SELECT count(*) FROM sweep_media WHERE passed + stuck + timeout + diverged != droplets").getInt(),
      0);
  EXPECT_EQ(d.execAndGet("SELECT status FROM sweeps").getString(), "complete");
  // Running it again does nothing new and reports the same points.
  EXPECT_EQ(nlohmann::json::parse(test::run("sweep --db " + db + kQuick).out), points);
}

TEST(SweepCli, KilledAndRunAgainGivesTheSameRecords) {
  const std::string ref = fresh("sweep_ref.db"), killed = fresh("sweep_killed.db");
  const std::string args = " --preset quick --media 3 --quiet --threads 1 ";
  ASSERT_EQ(test::run("sweep --db " + ref + args).code, 0);
  std::mt19937 rng(4);
  for (int k = 0; k < 4; ++k) {
    const pid_t pid = fork();
    if (pid == 0) {
      execl(SOFTDROP_CLI, SOFTDROP_CLI, "sweep", "--db", killed.c_str(), "--preset", "quick", "--media", "3", "--quiet",
            "--threads", "1", static_cast<char*>(nullptr));
      _exit(127);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(std::uniform_int_distribution<int>(100, 900)(rng)));
    kill(pid, SIGKILL);
    waitpid(pid, nullptr, 0);
  }
  ASSERT_EQ(test::run("sweep --db " + killed + args).code, 0);
  EXPECT_EQ(sweep_dump(killed), sweep_dump(ref));
}

TEST(SweepCli, ShardsMergedEqualOneSweep) {
  const std::string whole = fresh("whole.db"), s0 = fresh("shard0.db"), s1 = fresh("shard1.db"),
                    merged = fresh("merged.db");
  ASSERT_EQ(test::run("sweep --db " + whole + " --preset quick --quiet").code, 0);
  ASSERT_EQ(test::run("sweep --db " + s0 + " --preset quick --quiet --shard 0/2").code, 0);
  ASSERT_EQ(test::run("sweep --db " + s1 + " --preset quick --quiet --shard 1/2").code, 0);
  EXPECT_NE(sweep_dump(s0), sweep_dump(whole));
  const test::Result m = test::run("sweep-merge --into " + merged + " " + s0 + " " + s1);
  ASSERT_EQ(m.code, 0) << m.err;
  EXPECT_EQ(sweep_dump(merged), sweep_dump(whole));
  // Merging again adds nothing; a copy that disagrees is refused and named.
  ASSERT_EQ(test::run("sweep-merge --into " + merged + " " + s0).code, 0);
  EXPECT_EQ(sweep_dump(merged), sweep_dump(whole));
  {
    SQLite::Database d(s1, SQLite::OPEN_READWRITE);
    d.exec("UPDATE sweep_droplets SET steps = steps + 1 WHERE droplet = 0");
  }
  const test::Result bad = test::run("sweep-merge --into " + merged + " " + s1);
  EXPECT_EQ(bad.code, 1);
  EXPECT_NE(bad.err.find("differs"), std::string::npos) << bad.err;
}

TEST(SweepCli, FitAndAveragingsRunOnTheStore) {
  const std::string db = fresh("fit.db"), plot = fresh("fit.png"), json = fresh("fit.json"), avg = fresh("avg.svg");
  ASSERT_EQ(test::run("sweep --db " + db + " --preset quick --quiet --porosities 0.8,0.85,0.9,0.95,0.98").code, 0);
  const test::Result f = test::run("fit --db " + db + " --plot " + plot + " --json " + json);
  ASSERT_EQ(f.code, 0) << f.err;
  EXPECT_NE(f.out.find("AIC"), std::string::npos);
  const auto j = nlohmann::json::parse(std::ifstream(json));
  EXPECT_EQ(j["points"], 5);
  EXPECT_TRUE(j["preferred"] == "power" || j["preferred"] == "log");
  EXPECT_TRUE(j["power"].contains("b"));
  EXPECT_TRUE(std::filesystem::exists(plot));
  // Weighed by the media's errors unless told otherwise; 2 media a porosity are too few, and it
  // says so.
  EXPECT_EQ(j["errors"], "media");
  EXPECT_NE(f.out.find("weighed by the media's standard errors"), std::string::npos) << f.out;
  EXPECT_NE(f.err.find("5 of 5 points have their error from fewer than 10 media"), std::string::npos) << f.err;
  const test::Result d = test::run("fit --db " + db + " --errors droplets --format json");
  ASSERT_EQ(d.code, 0) << d.err;
  EXPECT_EQ(d.err.find("fewer than 10 media"), std::string::npos) << d.err;
  const auto dj = nlohmann::json::parse(d.out);
  EXPECT_EQ(dj["errors"], "droplets");
  EXPECT_NE(dj["log"]["chi2"], j["log"]["chi2"]);  // other weights, another fit
  const test::Result wrong = test::run("fit --db " + db + " --errors medium");
  EXPECT_EQ(wrong.code, 2);
  EXPECT_NE(wrong.err.find("--errors"), std::string::npos) << wrong.err;
  const test::Result a = test::run("averagings --db " + db + " --group 3 --plot " + avg);
  ASSERT_EQ(a.code, 0) << a.err;
  EXPECT_TRUE(std::filesystem::exists(avg));
  const std::string pts = fresh("points.csv");
  std::ofstream(pts) << "phi,t,se\n0.5,1.4\n";
  const test::Result bad = test::run("fit --points " + pts);
  EXPECT_EQ(bad.code, 1);
  EXPECT_NE(bad.err.find("line 2"), std::string::npos) << bad.err;
}

TEST(SweepCli, ASecondSweepInAFileIsToldHowItDiffersAndTheListingShowsOnlyThat) {
  const std::string db = fresh("two_sweeps.db");
  const test::Result first = test::run("sweep --db " + db + " --preset quick");
  ASSERT_EQ(first.code, 0);
  EXPECT_EQ(first.err.find("other sweep"), std::string::npos) << first.err;
  const test::Result again = test::run("sweep --db " + db + " --preset quick");  // the same: continued, no word
  EXPECT_EQ(again.err.find("other sweep"), std::string::npos) << again.err;
  const test::Result second = test::run("sweep --db " + db + " --preset quick --droplets 4 --porosities 0.8,0.9");
  ASSERT_EQ(second.code, 0);
  EXPECT_NE(
      second.err.find("holds 1 other sweep(s); this is a new one, nearest sweep 1, which differs in: droplets 8 -> 4, "
                      "porosities [0.7,0.8,0.9] -> [0.8,0.9]"),
      std::string::npos)
      << second.err;
  const test::Result list = test::run("sweep-report --db " + db + " --format csv");
  ASSERT_EQ(list.code, 0) << list.err;
  EXPECT_NE(list.out.find("differs_in"), std::string::npos) << list.out;
  EXPECT_NE(list.out.find(",\"droplets=8 porosities=[0.7,0.8,0.9]\"\n"), std::string::npos) << list.out;
  EXPECT_EQ(list.out.find("\"seed\""), std::string::npos) << "only the options that differ: " << list.out;
}

TEST(SweepCli, TheQuickPresetAveragesAndFitsWithoutAVerdictItCannotGive) {
  const std::string db = fresh("quick.db"), json = fresh("quick_fit.json");
  ASSERT_EQ(test::run("sweep --db " + db + " --preset quick --quiet").code, 0);
  // 3 porosities x 2 media: the paper's groups of 100 cannot be formed; groups of 2 are chosen and said.
  const test::Result a = test::run("averagings --db " + db);
  ASSERT_EQ(a.code, 0) << a.err;
  EXPECT_NE(a.err.find("groups of 2 (from the 6 media"), std::string::npos) << a.err;
  EXPECT_EQ(std::count(a.out.begin(), a.out.end(), '\n'), 1 + 2 * 3) << a.out;  // header, 3 groups a type
  EXPECT_EQ(a.err.find("left out"), std::string::npos) << a.err;
  // Groups of 4 leave 2 media over: dropped, and said; or kept as a last group of 2.
  const test::Result four = test::run("averagings --db " + db + " --group 4");
  EXPECT_NE(four.err.find("2 of the 6 media do not fill a group of 4 and are left out"), std::string::npos) << four.err;
  EXPECT_EQ(std::count(four.out.begin(), four.out.end(), '\n'), 1 + 2 * 1) << four.out;
  const test::Result kept = test::run("averagings --db " + db + " --group 4 --leftover keep");
  EXPECT_EQ(kept.err.find("left out"), std::string::npos) << kept.err;
  EXPECT_EQ(std::count(kept.out.begin(), kept.out.end(), '\n'), 1 + 2 * 2) << kept.out;
  EXPECT_EQ(test::run("averagings --db " + db + " --leftover all").code, 2);
  const test::Result big = test::run("averagings --db " + db + " --group 7");
  EXPECT_EQ(big.code, 1);
  EXPECT_NE(big.err.find("group = 7: larger than the 6 media with a passed droplet (use --group 2)"), std::string::npos)
      << big.err;
  // 3 points for the 3-parameter power law: a warning and no verdict, in the table and the JSON.
  const test::Result f = test::run("fit --db " + db + " --json " + json);
  ASSERT_EQ(f.code, 0) << f.err;
  EXPECT_NE(f.err.find("leave 0 degrees of freedom"), std::string::npos) << f.err;
  EXPECT_NE(f.out.find("no verdict"), std::string::npos) << f.out;
  EXPECT_EQ(f.out.find("is preferred"), std::string::npos) << f.out;
  EXPECT_TRUE(nlohmann::json::parse(std::ifstream(json))["preferred"].is_null());
}

TEST(SweepStore, AVersionOneFileIsMigratedAndKeepsItsRuns) {
  const std::string db = fresh("v1.db");
  ASSERT_EQ(test::run("optimize --db " + db + test::kSmallScene +
                      " --stuck-window 0.1 --stuck-distance 1 --generations 2 --quiet --objective single "
                      "--validate-starts 0")
                .code,
            0);
  {
    SQLite::Database d(db, SQLite::OPEN_READWRITE);
    d.exec("DROP TABLE sweep_droplets; DROP TABLE sweep_media; DROP TABLE sweeps; PRAGMA user_version = 1");
  }
  EXPECT_EQ(open_history(db, OpenMode::read_only)->runs().size(), 1u);  // read as it is
  ASSERT_EQ(test::run("sweep --db " + db + " --preset quick --quiet --media 1 --droplets 2").code, 0);
  SQLite::Database d(db, SQLite::OPEN_READONLY);
  EXPECT_EQ(d.execAndGet("PRAGMA user_version").getInt(), kHistorySchemaVersion);
  EXPECT_EQ(d.execAndGet("SELECT count(*) FROM runs").getInt(), 1);
  EXPECT_EQ(d.execAndGet("SELECT count(*) FROM sweep_media").getInt(), 3);
}

TEST(SweepStore, EachDropletsShakingIsStoredAndAVersionEightFileReadsItAsNotRecorded) {
  // A shaken sweep stores each droplet's shaken_at and route_tortuosity as its run reported them.
  const std::string db = fresh("shaken.db");
  const std::string shaken =
      " --preset quick --quiet --media 1 --droplets 4 --porosities 0.7 --vibration-amplitude 4 "
      "--vibration-frequency 100";
  ASSERT_EQ(test::run("sweep --db " + db + shaken).code, 0);
  const std::vector<SweepMedium> media = open_sweep_store(db, OpenMode::read_only)->media(1);
  ASSERT_EQ(media.size(), 1u);
  int shook = 0;
  for (const SweepDroplet& d : media[0].droplets) {
    shook += !std::isnan(d.shaken_at);
    EXPECT_EQ(d.outcome == Outcome::passed, !std::isnan(d.route_tortuosity));
    if (std::isnan(d.shaken_at) && d.outcome == Outcome::passed) {
      EXPECT_EQ(d.route_tortuosity, d.tortuosity);
    }
  }
  EXPECT_GT(shook, 0);
  SQLite::Database v(db, SQLite::OPEN_READONLY);
  EXPECT_EQ(v.execAndGet("SELECT count(*) FROM sweep_droplets_view WHERE shaken_at IS NOT NULL").getInt(), shook);
  // A file from before version 9: no such columns. It is read as it is, and a write migrates it;
  // its old droplets then say "not recorded" (NaN), and new ones are recorded.
  const std::string old = fresh("v8.db");
  ASSERT_EQ(test::run("sweep --db " + old + " --preset quick --quiet --media 1 --droplets 2").code, 0);
  {
    SQLite::Database d(old, SQLite::OPEN_READWRITE);
    d.exec(
        "DROP VIEW sweep_droplets_view; ALTER TABLE sweep_droplets DROP COLUMN shaken_at; "
        "ALTER TABLE sweep_droplets DROP COLUMN route_tortuosity; PRAGMA user_version = 8");
  }
  ASSERT_EQ(open_sweep_store(old, OpenMode::read_only)->media(1).size(), 3u);
  // A second sweep (other options) writes to it, which migrates the file.
  ASSERT_EQ(test::run("sweep --db " + old + " --preset quick --quiet --media 2 --droplets 2").code, 0);
  const auto store = open_sweep_store(old, OpenMode::read_only);
  for (const std::int64_t sweep : {1, 2})
    for (const SweepMedium& m : store->media(sweep))
      for (const SweepDroplet& d : m.droplets)
        EXPECT_EQ(std::isnan(d.route_tortuosity), sweep == 1 || d.outcome != Outcome::passed) << sweep;
  SQLite::Database d(old, SQLite::OPEN_READONLY);
  EXPECT_EQ(d.execAndGet("PRAGMA user_version").getInt(), kHistorySchemaVersion);
}

}  // namespace
}  // namespace softdrop
