#pragma once
// The tests that two runs, or two pairs of droplets, are the same to the bit: every value of their
// summaries, the doubles compared by their bits.
#include <gtest/gtest.h>

#include <bit>
#include <cstddef>
#include <cstdint>
#include <string>

#include "softdrop/simulation.hpp"

namespace softdrop::test {

inline std::uint64_t bits(double v) { return std::bit_cast<std::uint64_t>(v); }

/// Whether runs a and b ended the same, to the bit; `what` names the pair in a failure.
inline void expect_same_summary(const RunSummary& a, const RunSummary& b, const std::string& what) {
  SCOPED_TRACE(what);
  EXPECT_EQ(a.outcome, b.outcome);
  EXPECT_EQ(a.reason, b.reason);
  EXPECT_EQ(a.steps, b.steps);
  EXPECT_EQ(bits(a.tortuosity), bits(b.tortuosity));
  EXPECT_EQ(bits(a.route_tortuosity), bits(b.route_tortuosity));
  EXPECT_EQ(bits(a.path_length), bits(b.path_length));
  EXPECT_EQ(bits(a.min_area_ratio), bits(b.min_area_ratio));
  EXPECT_EQ(bits(a.max_penetration), bits(b.max_penetration));
  EXPECT_EQ(a.touched, b.touched);
  EXPECT_EQ(bits(a.shaken_at), bits(b.shaken_at));
  EXPECT_EQ(a.path_x, b.path_x);
  EXPECT_EQ(a.path_y, b.path_y);
  EXPECT_EQ(a.area, b.area);
  ASSERT_EQ(a.snapshots.size(), b.snapshots.size());
  for (std::size_t i = 0; i < a.snapshots.size(); ++i) EXPECT_EQ(a.snapshots[i].x, b.snapshots[i].x);
}

/// Whether two pairs of droplets ran the same, to the bit: both droplets, the release, the contacts.
inline void expect_same_pair(const TwoDropletSummary& a, const TwoDropletSummary& b, const std::string& what) {
  SCOPED_TRACE(what);
  expect_same_summary(a.first, b.first, "first droplet");
  expect_same_summary(a.second, b.second, "second droplet");
  EXPECT_EQ(a.released, b.released);
  EXPECT_EQ(bits(a.released_at), bits(b.released_at));
  EXPECT_EQ(a.contact_steps, b.contact_steps);
  EXPECT_EQ(a.shared_touched, b.shared_touched);
}

}  // namespace softdrop::test
