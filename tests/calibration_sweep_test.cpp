// A calibration's sweep is the program's sweep: the same options and droplet give the same media
// (of the kind asked for) and the same figures as `softdrop sweep` reports for them.
#include <gtest/gtest.h>

#include <vector>

#include "fixtures.hpp"
#include "softdrop/calibration.hpp"
#include "softdrop/sweep.hpp"

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

}  // namespace
}  // namespace softdrop
