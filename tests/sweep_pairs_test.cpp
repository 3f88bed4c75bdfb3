// Sweeps of pairs (sweep --second-droplet): each start is a pair's; the firsts are the sweep's
// droplets from the starts a one-droplet sweep uses, the released seconds are stored beside them
// with their pair's contacts, read back, sent between ranks and merged to the bit, and the options
// are stored so that the same command continues the same sweep.
#include <SQLiteCpp/SQLiteCpp.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "cli_run.hpp"
#include "fixtures.hpp"
#include "softdrop/store.hpp"
#include "softdrop/sweep.hpp"
#include "store/params_json.hpp"
#include "studies/sweep_record_bytes.hpp"

namespace softdrop {
namespace {

// The paper's cited case, small: non-overlapping grains at phi = 0.79 in 200 x 200, where about
// half the pairs meet.
SweepOptions pairs() {
  SweepOptions o;
  o.porosities = {0.79};
  o.media = 2;
  o.droplets = 6;
  o.medium.kind = MediumKind::non_overlapping;
  o.medium.width = o.medium.height = 200;
  o.second = SecondDroplet{};
  o.second->after = 20;
  return o;
}

bool same_bits(double a, double b) { return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b); }

void expect_same(const SweepDroplet& a, const SweepDroplet& b) {
  EXPECT_EQ(a.droplet, b.droplet);
  EXPECT_TRUE(same_bits(a.start_x, b.start_x));
  EXPECT_EQ(a.outcome, b.outcome);
  EXPECT_TRUE(same_bits(a.tortuosity, b.tortuosity));
  EXPECT_EQ(a.steps, b.steps);
  EXPECT_TRUE(same_bits(a.shaken_at, b.shaken_at));
  EXPECT_TRUE(same_bits(a.route_tortuosity, b.route_tortuosity));
}

void expect_same(const SweepMedium& a, const SweepMedium& b) {
  EXPECT_EQ(a.unit, b.unit);
  EXPECT_EQ(a.passed, b.passed);
  EXPECT_TRUE(same_bits(a.mean_t, b.mean_t));
  ASSERT_EQ(a.droplets.size(), b.droplets.size());
  for (std::size_t i = 0; i < a.droplets.size(); ++i) expect_same(a.droplets[i], b.droplets[i]);
  ASSERT_EQ(a.second_droplets.size(), b.second_droplets.size());
  for (std::size_t i = 0; i < a.second_droplets.size(); ++i) {
    const SweepSecond &p = a.second_droplets[i], &q = b.second_droplets[i];
    expect_same(p.run, q.run);
    EXPECT_TRUE(same_bits(p.released_at, q.released_at));
    EXPECT_TRUE(same_bits(p.first_held_at, q.first_held_at));
    EXPECT_TRUE(same_bits(p.held_at, q.held_at));
    EXPECT_EQ(p.contact_steps, q.contact_steps);
    EXPECT_EQ(p.shared_touched, q.shared_touched);
  }
}

TEST(SweepPairs, FirstsStartAsTheOneDropletSweepsAndPairsThatNeverMeetRunAsTheyWouldAlone) {
  const SweepOptions o = pairs();
  SweepOptions alone = o;
  alone.second.reset();
  const auto units = sweep_units(o);
  std::vector<SweepMedium> got;
  run_sweep_units(o, units, 2, [&](SweepMedium&& m) { got.push_back(std::move(m)); });
  ASSERT_EQ(got.size(), units.size());
  int met = 0, apart = 0;
  for (std::size_t u = 0; u < units.size(); ++u) {
    SCOPED_TRACE("unit " + std::to_string(u));
    expect_same(got[u], run_sweep_unit(o, units[u], 1));  // the same on any thread count
    const SweepMedium one = run_sweep_unit(alone, units[u], 1);
    ASSERT_EQ(got[u].droplets.size(), one.droplets.size());
    for (std::size_t d = 0; d < one.droplets.size(); ++d)
      EXPECT_TRUE(same_bits(got[u].droplets[d].start_x, one.droplets[d].start_x));
    for (const SweepSecond& s : got[u].second_droplets) {
      const SweepDroplet& first = got[u].droplets[static_cast<std::size_t>(s.run.droplet)];
      EXPECT_TRUE(same_bits(s.run.start_x, first.start_x));  // offset 0
      EXPECT_GT(s.released_at, 0);
      if (s.contact_steps > 0) {
        ++met;
        continue;
      }
      // Never in contact and never held: each ran as it would alone, so both are the one-droplet
      // sweep's droplet from that start, to the bit.
      if (!std::isnan(s.first_held_at) || !std::isnan(s.held_at)) continue;
      ++apart;
      expect_same(first, one.droplets[static_cast<std::size_t>(s.run.droplet)]);
      EXPECT_TRUE(same_bits(s.run.tortuosity, first.tortuosity));
      EXPECT_EQ(s.run.steps, first.steps);
    }
  }
  EXPECT_GT(met, 0);  // the case is one where pairs meet
  EXPECT_GT(apart, 0);
  // The second droplets' points are theirs, the droplets' the firsts'.
  const auto firsts = sweep_points(got), seconds = sweep_points(got, true);
  ASSERT_EQ(seconds.size(), 1U);
  EXPECT_EQ(firsts[0].droplets, o.media * o.droplets);
  int released = 0;
  for (const SweepMedium& m : got) released += static_cast<int>(m.second_droplets.size());
  EXPECT_EQ(seconds[0].droplets, released);
}

TEST(SweepPairs, RecordsAreStoredReadBackAndSentAsBytesToTheBit) {
  const SweepOptions o = pairs();
  SweepMedium m = run_sweep_unit(o, {0, 1}, 2);
  ASSERT_FALSE(m.second_droplets.empty());
  m.second_droplets.front().first_held_at = 0.1 + 0.2;  // held, and not a short decimal
  const std::string db = test::fresh_path("pairs_store.db");
  {
    auto store = open_sweep_store(db, OpenMode::create);
    const std::int64_t id = store->find_or_create(sweep_params_to_json(o), o);
    ASSERT_TRUE(store->add(id, m));
    const std::vector<SweepMedium> back = store->media(id);
    ASSERT_EQ(back.size(), 1U);
    expect_same(back[0], m);
    const std::optional<SweepMedium> alone = store->medium(id, m.unit);  // the one unit, read alone
    ASSERT_TRUE(alone.has_value());
    expect_same(*alone, m);
    EXPECT_FALSE(store->medium(id, {0, 0}).has_value());
  }
  const SweepMedium sent = decode_sweep_medium(encode_sweep_medium(m));
  expect_same(sent, m);
  EXPECT_THROW(decode_sweep_medium(encode_sweep_medium(m) + "x"), std::invalid_argument);
  SQLite::Database v(db, SQLite::OPEN_READONLY);
  EXPECT_EQ(v.execAndGet("SELECT count(*) FROM sweep_second_droplets_view").getInt(),
            static_cast<int>(m.second_droplets.size()));
  int never_held = 0;
  for (const SweepSecond& s : m.second_droplets) never_held += std::isnan(s.held_at);
  EXPECT_EQ(v.execAndGet("SELECT count(*) FROM sweep_second_droplets_view WHERE held_at IS NULL").getInt(),
            never_held);  // NaN ("never") is NULL
}

TEST(SweepPairs, OptionsAreStoredOnlyForPairsAndReadBackExactly) {
  SweepOptions o = pairs();
  SweepOptions alone = o;
  alone.second.reset();
  // A one-droplet sweep's stored options have no second droplet's keys: an existing sweep is
  // found again by the same text.
  EXPECT_EQ(sweep_params_to_json(alone).find("second-"), std::string::npos);
  EXPECT_FALSE(sweep_params_from_json(sweep_params_to_json(alone)).second);
  o.second->release = SecondRelease::delay;
  o.second->after = 0.1 + 0.2;
  o.second->offset_x = -30;
  const std::string j = sweep_params_to_json(o);
  const SweepOptions back = sweep_params_from_json(j);
  ASSERT_TRUE(back.second);
  EXPECT_EQ(back.second->release, SecondRelease::delay);
  EXPECT_EQ(back.second->after, 0.1 + 0.2);
  EXPECT_EQ(back.second->offset_x, -30);
  EXPECT_EQ(sweep_params_to_json(back), j);
  std::string bad = j;
  bad.replace(bad.find("\"delay\""), 7, "\"later\"");
  EXPECT_THROW(sweep_params_from_json(bad), std::runtime_error);
  // A pair that would start overlapping is not a valid sweep.
  o.second->release = SecondRelease::distance;
  o.second->offset_x = 0;
  o.second->after = 5;
  std::string why;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_NE(why.find("second-after = 5"), std::string::npos) << why;
}

TEST(SweepPairs, TheCommandRunsContinuesAndReportsPairsAndRefusesBadOnesInOneLine) {
  const std::string db = test::fresh_path("pairs_cli.db");
  const std::string args =
      " --porosities 0.79 --kind non-overlapping --width 200 --height 200 --media 2 --droplets 4 "
      "--second-droplet distance --second-after 20 --quiet --format json";
  const test::Result r = test::run("sweep --db " + db + args);
  ASSERT_EQ(r.code, 0) << r.err;
  // The same command continues the same sweep: nothing more to run.
  const test::Result again = test::run("sweep --db " + db + args);
  ASSERT_EQ(again.code, 0) << again.err;
  auto store = open_sweep_store(db, OpenMode::read_only);
  ASSERT_EQ(store->sweeps().size(), 1U);
  EXPECT_TRUE(sweep_params_from_json(store->sweep(1).params).second);
  const test::Result report = test::run("sweep-report --db " + db + " --second-droplets --format csv");
  ASSERT_EQ(report.code, 0) << report.err;
  EXPECT_EQ(report.out.rfind("target_porosity,porosity,media,droplets,", 0), 0U) << report.out;
  for (const auto& [bad, message] :
       {std::pair{"--second-droplet distance --second-after 5", "second-after = 5: the second droplet would start"},
        {"--second-droplet distance --walls --second-offset-x 30", "second-offset-x: a sweep between walls takes none"},
        {"--second-after 30", "have no effect without --second-droplet"}}) {
    const std::string refused = test::fresh_path("pairs_refused.db");
    const test::Result no = test::run("sweep --db " + refused + " --preset quick --quiet " + bad);
    EXPECT_NE(no.code, 0) << bad;
    EXPECT_NE(no.err.find(message), std::string::npos) << no.err;
    EXPECT_EQ(std::count(no.err.begin(), no.err.end(), '\n'), 1) << no.err;
    EXPECT_FALSE(std::filesystem::exists(refused)) << bad;
  }
  // A one-droplet sweep has no second droplets to report.
  const std::string one = test::fresh_path("one.db");
  ASSERT_EQ(test::run("sweep --db " + one + " --preset quick --quiet --media 1 --droplets 2").code, 0);
  const test::Result none = test::run("sweep-report --db " + one + " --second-droplets");
  EXPECT_NE(none.code, 0);
  EXPECT_NE(none.err.find("pushes one droplet at a time"), std::string::npos) << none.err;
}

}  // namespace
}  // namespace softdrop
