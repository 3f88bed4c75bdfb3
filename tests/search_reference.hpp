#pragma once
// Histories of the search to compare: the reference, generations one at a time on one thread, and
// a drive of the same generations on threads and lanes, which must make the same decisions.

#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "softdrop/search.hpp"

namespace softdrop::test {
// The reference history: generations 1..n one at a time on one thread.
struct Reference {
  std::vector<Generation> history;
  Configuration best;
};
inline Reference one_at_a_time(const SearchOptions& o, const Configuration& best, int n) {
  Search plain(o, best, 0);
  Reference r;
  for (int i = 0; i < n; ++i) r.history.push_back(plain.next(1));
  r.best = plain.best();
  return r;
}

// A drive up to generation d.generations from `best`, with its history.
struct Driven {
  std::vector<Generation> history;
  SearchSummary summary;
  Configuration best;
};
inline Driven drive_recorded(const SearchOptions& o, const Configuration& best, const DriveOptions& d) {
  Search s(o, best, 0);
  Driven r;
  r.summary = drive(s, d, [&](const Generation& g, const Configuration&) {
    r.history.push_back(g);
    return true;
  });
  r.best = s.best();
  return r;
}

// The same decisions, best and candidates, generation by generation, as the reference.
inline void expect_same_history(const Reference& a, const Driven& b) {
  ASSERT_EQ(b.history.size(), a.history.size());
  for (std::size_t i = 0; i < a.history.size(); ++i) {
    SCOPED_TRACE("generation " + std::to_string(i + 1));
    const Generation &x = a.history[i], &y = b.history[i];
    ASSERT_EQ(y.number, x.number);
    ASSERT_EQ(y.accepted, x.accepted);
    ASSERT_EQ(y.best_t, x.best_t);
    ASSERT_EQ(y.state, x.state);
    ASSERT_EQ(y.candidates.size(), x.candidates.size());
    for (std::size_t k = 0; k < x.candidates.size(); ++k) {
      EXPECT_EQ(y.candidates[k].medium, x.candidates[k].medium);
      EXPECT_EQ(y.candidates[k].eval.tortuosity, x.candidates[k].eval.tortuosity);
      EXPECT_EQ(y.candidates[k].eval.steps, x.candidates[k].eval.steps);
    }
  }
  EXPECT_EQ(b.best.medium, a.best.medium);
}

// Drives the generations of `a` from `best` on `threads` threads with `lanes` lanes each, expects
// a's history, and returns the summary.
inline SearchSummary drive_as(const Reference& a, const SearchOptions& o, const Configuration& best, int threads,
                              int lanes) {
  DriveOptions d;
  d.generations = static_cast<std::int64_t>(a.history.size());
  d.threads = threads;
  d.lanes = lanes;
  const Driven b = drive_recorded(o, best, d);
  expect_same_history(a, b);
  return b.summary;
}

}  // namespace softdrop::test
