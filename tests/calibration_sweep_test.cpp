// A calibration's sweep is the program's sweep: the same options and droplet give the same media
// (of the kind asked for) and the same figures as `softdrop sweep` reports for them.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <set>
#include <vector>

#include "fixtures.hpp"
#include "softdrop/sweep.hpp"
#include "store/params_json.hpp"
#include "studies/calibration.hpp"

namespace softdrop {
namespace {

TEST(CalibrationSweep, ThePointsAreTheSweepsOnEitherKindOfMedium) {
  const DropletParams droplet;
  std::vector<CalibrationResult> results;
  for (const MediumKind kind : {MediumKind::overlapping, MediumKind::non_overlapping}) {
    CalibrationOptions o = test::tiny_calibration();
    o.sweep.medium.kind = kind;
    o.trace_media = 0;  // the sweep alone
    const CalibrationResult c = run_calibration(o, droplet, 2);
    SweepOptions s = o.sweep;
    s.droplet = droplet;
    std::vector<SweepMedium> media;
    for (const SweepUnit& unit : sweep_units(s)) media.push_back(run_sweep_unit(s, unit, 1));
    const std::vector<SweepPoint> points = sweep_points(media);
    ASSERT_EQ(points.size(), c.points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
      const CalibrationPoint& p = c.points[i];
      EXPECT_EQ(p.target_porosity, points[i].target_porosity);
      EXPECT_DOUBLE_EQ(p.porosity, points[i].porosity);
      EXPECT_EQ(p.droplets, points[i].droplets);
      EXPECT_EQ(p.passed, points[i].passed);
      EXPECT_EQ(p.stuck, points[i].stuck);
      EXPECT_EQ(p.media_passed, points[i].media_passed);
      EXPECT_DOUBLE_EQ(p.mean_t, points[i].mean_t);
      EXPECT_DOUBLE_EQ(p.media_standard_error, points[i].media_standard_error);
    }
    results.push_back(c);
  }
  // The kind reaches the media: non-overlapping media of the same seeds are other media.
  EXPECT_NE(results[0].points[0].porosity, results[1].points[0].porosity);
  EXPECT_NE(results[0].points[1].porosity, results[1].points[1].porosity);
}

// Validation on media the tuning never saw: for every seed, the sweep's media (the held-out
// stream, its default) are not calibrate's (the calibration stream), over the porosities of the
// calibration and of the paper-size study, a paper-size study's 200 media each, and the seeds
// the studies use.
TEST(CalibrationSweep, ASweepsMediaAreNeverTheCalibrations) {
  SweepOptions calibration = CalibrationOptions::default_sweep(), held_out;
  EXPECT_EQ(calibration.stream, MediaStream::calibration);
  EXPECT_EQ(held_out.stream, MediaStream::held_out);  // a sweep's default
  std::set<std::uint64_t> tuned, swept;
  for (const std::uint64_t seed : {1ULL, 2ULL, 3ULL, 777001ULL}) {
    for (SweepOptions* o : {&calibration, &held_out}) {
      o->seed = seed;
      o->porosities = {0.45, 0.5, 0.55, 0.6, 0.65, 0.7, 0.75, 0.8, 0.85, 0.9, 0.95};
      o->media = 200;
    }
    for (const SweepUnit& u : sweep_units(calibration)) tuned.insert(sweep_medium_seed(calibration, u));
    for (const SweepUnit& u : sweep_units(held_out)) swept.insert(sweep_medium_seed(held_out, u));
  }
  ASSERT_EQ(tuned.size(), 4u * 11 * 200);  // no two units of a stream share a medium either
  ASSERT_EQ(swept.size(), 4u * 11 * 200);
  for (const std::uint64_t s : swept) EXPECT_EQ(tuned.count(s), 0u) << s;
}

// calibrate tunes on the calibration stream whatever its options say, and a sweep asked for that
// stream measures those very media: a calibration's figures can be re-measured, in-sample.
TEST(CalibrationSweep, CalibrateAlwaysTunesOnTheCalibrationStream) {
  CalibrationOptions o = test::tiny_calibration();
  o.trace_media = 0;
  o.sweep.stream = MediaStream::held_out;  // overruled
  const CalibrationResult c = run_calibration(o, DropletParams{}, 2);
  SweepOptions s = o.sweep;
  std::vector<SweepMedium> tuned, other;
  for (const MediaStream stream : {MediaStream::calibration, MediaStream::held_out}) {
    s.stream = stream;
    for (const SweepUnit& unit : sweep_units(s))
      (stream == MediaStream::calibration ? tuned : other).push_back(run_sweep_unit(s, unit, 1));
  }
  const std::vector<SweepPoint> in = sweep_points(tuned), out = sweep_points(other);
  ASSERT_EQ(in.size(), c.points.size());
  for (std::size_t i = 0; i < in.size(); ++i) {
    EXPECT_DOUBLE_EQ(c.points[i].porosity, in[i].porosity);
    EXPECT_DOUBLE_EQ(c.points[i].mean_t, in[i].mean_t);
    EXPECT_NE(c.points[i].porosity, out[i].porosity);  // other media
  }
}

// The stream is stored with a sweep; a sweep stored before there were streams drew its media the
// calibration's way, and reads so.
TEST(CalibrationSweep, TheStreamIsStoredAndAnOlderSweepReadsAsTheCalibrations) {
  SweepOptions o;
  EXPECT_EQ(sweep_params_from_json(sweep_params_to_json(o)).stream, MediaStream::held_out);
  o.stream = MediaStream::calibration;
  auto j = nlohmann::json::parse(sweep_params_to_json(o));
  EXPECT_EQ(j["media-stream"], "calibration");
  EXPECT_EQ(sweep_params_from_json(j.dump()).stream, MediaStream::calibration);
  j.erase("media-stream");
  EXPECT_EQ(sweep_params_from_json(j.dump()).stream, MediaStream::calibration);
  j["media-stream"] = "validation";
  try {
    sweep_params_from_json(j.dump());
    ADD_FAILURE() << "an unknown stream was read";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("media-stream"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace softdrop
