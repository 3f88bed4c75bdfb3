// The sweep's run on a database (softdrop/service.hpp), as the program and the Python module run
// it: what its observer hears, a run stopped by the observer and run again, and what a refused
// run leaves on disk.
#include "softdrop/service.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli_run.hpp"
#include "fixtures.hpp"
#include "service/calibration_service.hpp"
#include "sim/lane_policy.hpp"
#include "softdrop/store.hpp"

namespace softdrop {
namespace {

SweepRun tiny_run(const std::string& db) {
  SweepRun r;
  r.sweep.porosities = {0.85, 0.95};
  r.sweep.media = 2;
  r.sweep.droplets = 3;
  r.sweep.medium.width = r.sweep.medium.height = 150;
  r.sweep.medium.r_min = test::kBalloonRMin, r.sweep.medium.r_max = test::kBalloonRMax;
  r.sweep.droplet = test::balloon_droplet();  // (a quick droplet: these tests are of the run)
  r.db = db;
  r.threads = 2;
  return r;
}

// Records what it hears; stops after `stop_after` media (0: never).
struct SweepRecorder : SweepObserver {
  std::size_t stop_after = 0;
  std::vector<std::size_t> started_with;  // stored, to_do
  std::vector<SweepProgress> progress;
  void started(std::int64_t, std::size_t stored, std::size_t to_do) override { started_with = {stored, to_do}; }
  bool stored(const SweepMedium&, const SweepProgress& p) override {
    progress.push_back(p);
    return stop_after == 0 || progress.size() < stop_after;
  }
};

// Each stored medium's droplets' T, by unit, to the bit.
std::vector<std::uint64_t> stored_bits(const std::string& db, std::int64_t sweep) {
  std::vector<std::uint64_t> bits;
  for (const SweepMedium& m : open_sweep_store(db, OpenMode::read_only)->media(sweep)) {
    bits.push_back(static_cast<std::uint64_t>(m.unit.porosity * 100 + m.unit.medium));
    for (const SweepDroplet& d : m.droplets) bits.push_back(std::bit_cast<std::uint64_t>(d.tortuosity));
  }
  return bits;
}

TEST(SweepService, ARunStoresEveryMediumAndTellsItsObserver) {
  const std::string db = test::fresh_path("service_whole.db");
  SweepRecorder heard;
  const SweepSummary s = run_sweep(tiny_run(db), heard);
  EXPECT_EQ(s.status, "complete");
  EXPECT_EQ(s.media, 4);
  EXPECT_EQ(s.done, 4);
  EXPECT_EQ(s.media_this_session, 4u);
  EXPECT_EQ(s.media_by_another_process, 0u);
  EXPECT_EQ(s.droplets_this_session, 12);
  EXPECT_EQ(heard.started_with, (std::vector<std::size_t>{0, 4}));
  ASSERT_EQ(heard.progress.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(heard.progress[i].done, i + 1);
    EXPECT_EQ(heard.progress[i].to_do, 4u);
    EXPECT_EQ(heard.progress[i].sweep, s.sweep);
  }
  // Run again: nothing left to do, and nothing changes.
  SweepRecorder again;
  const SweepSummary t = run_sweep(tiny_run(db), again);
  EXPECT_EQ(t.sweep, s.sweep);
  EXPECT_EQ(t.status, "complete");
  EXPECT_EQ(t.media_this_session, 0u);
  EXPECT_EQ(again.started_with, (std::vector<std::size_t>{4, 0}));
  std::filesystem::remove(db);
}

TEST(SweepService, AnObserverThatStopsTheRunLeavesAResumableSweepWithTheSameBits) {
  const std::string whole = test::fresh_path("service_reference.db"), parts = test::fresh_path("service_parts.db");
  // The stop is heard once the first medium is stored, which the first commit makes slow (it
  // creates the database) while the thread goes on stepping. With SSE2 alone a thread steps one
  // droplet at a time, so it starts a few media meanwhile, not all 20: with 24 lanes it had 8 in
  // flight and sometimes started the last 4 before the stop. The bits are the same at every width.
  const test::VectorWidthLimit one_at_a_time(VectorWidth::sse2);
  SweepRecorder reference;
  SweepRecorder first;
  first.stop_after = 1;
  SweepRun run = tiny_run(parts);
  run.sweep.media = 10;
  run.threads = 1;
  SweepRun reference_run = tiny_run(whole);
  reference_run.sweep.media = 10;
  const SweepSummary r = run_sweep(reference_run, reference);
  const SweepSummary s = run_sweep(run, first);
  EXPECT_EQ(s.status, "interrupted");
  EXPECT_GE(s.done, 1);
  EXPECT_LT(s.done, 20);  // the media in flight at the stop are stored, no more
  EXPECT_EQ(static_cast<std::int64_t>(first.progress.size()), s.done);
  EXPECT_EQ(open_sweep_store(parts, OpenMode::read_only)->sweep(s.sweep).status, "interrupted");
  SweepRecorder second;
  const SweepSummary t = run_sweep(run, second);
  const auto before = static_cast<std::size_t>(s.done);
  EXPECT_EQ(second.started_with, (std::vector<std::size_t>{before, 20 - before}));
  EXPECT_EQ(t.status, "complete");
  EXPECT_EQ(t.media_this_session, 20 - before);
  EXPECT_EQ(stored_bits(parts, t.sweep), stored_bits(whole, r.sweep));
  std::filesystem::remove(whole);
  std::filesystem::remove(parts);
}

TEST(SweepService, ARefusedRunNamesTheOptionAndWritesNoFile) {
  const std::string db = test::fresh_path("service_refused.db");
  SweepRecorder heard;
  SweepRun run = tiny_run(db);
  run.shard = 2;
  run.shards = 2;
  try {
    run_sweep(run, heard);
    FAIL() << "a shard outside its count was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("shard = 2/2"), std::string::npos) << e.what();
  }
  run = tiny_run(db);
  run.sweep.porosities.clear();
  EXPECT_THROW(run_sweep(run, heard), std::invalid_argument);
  run = tiny_run(db);
  run.threads = -1;
  EXPECT_THROW(run_sweep(run, heard), std::invalid_argument);
  EXPECT_FALSE(std::filesystem::exists(db));
  EXPECT_TRUE(heard.started_with.empty());
}

TEST(SweepService, AFileThatIsNotADatabaseIsRefusedAndKept) {
  const std::string db = test::fresh_path("service_text.db");
  { std::ofstream(db) << "not a database\n"; }
  SweepRecorder heard;
  EXPECT_THROW(run_sweep(tiny_run(db), heard), DatabaseError);
  EXPECT_EQ(test::first_line(db), "not a database");
  std::filesystem::remove(db);
}

// A calibration scan: each setting heard as it ends, a refused one recorded, the rows ranked, and
// an observer that stops after the first leaves the rest unrun.
TEST(CalibrationService, ASettingsRowsAreRankedAndTheObserverMayStopTheScan) {
  struct Rows : CalibrationObserver {
    std::size_t stop_after = 0;
    std::vector<std::size_t> heard;
    long droplets = 0;
    void progress(int, long done, long, double) override { droplets = std::max(droplets, done); }
    bool finished(const std::vector<CalibrationRow>& rows) override {
      heard.push_back(rows.size());
      return stop_after == 0 || rows.size() < stop_after;
    }
  };
  CalibrationScan scan;
  scan.calibration = test::tiny_calibration();
  scan.calibration.sweep.porosities = {0.9};
  DropletParams unstable;
  unstable.mass = 1e-4;  // refused by the droplet's limits: a row, not an error
  DropletParams soft;
  soft.nrt *= 0.5;
  scan.settings = {DropletParams{}, unstable, soft};
  scan.labels = {"defaults", "unstable", "soft"};
  scan.threads = 2;
  Rows all;
  const std::vector<CalibrationRow> rows = run_calibration_scan(scan, all);
  EXPECT_EQ(all.heard, (std::vector<std::size_t>{1, 2, 3}));
  EXPECT_EQ(all.droplets, 1 * 2 * 3 + 2);  // the setting's sweep and traces
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[2].label, "unstable");  // refused: last
  EXPECT_FALSE(rows[2].refused.empty());
  EXPECT_LE(rows[0].result.score, rows[1].result.score);
  EXPECT_EQ(rows[0].result.score, run_calibration(scan.calibration, rows[0].droplet, 1).score);
  Rows first;
  first.stop_after = 1;
  const std::vector<CalibrationRow> stopped = run_calibration_scan(scan, first);
  ASSERT_EQ(stopped.size(), 1u);
  EXPECT_EQ(stopped[0].label, "defaults");
  scan.labels = {"one"};
  EXPECT_THROW(run_calibration_scan(scan, first), std::invalid_argument);
}

}  // namespace
}  // namespace softdrop
