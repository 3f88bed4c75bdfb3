// The CMA-ES strategy on a made-up objective: it climbs, its candidates keep the spacing rule,
// proposing changes nothing, and replaying its stored states rebuilds it bit for bit.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "media/spacing.hpp"
#include "optimizer/strategy.hpp"
#include "search_fixtures.hpp"

namespace softdrop {
namespace {

// Made up for the test: T grows with the grains' mean height above the bottom, 1 at the bottom
// and 2 at the top. Smooth and linear, as CMA-ES meets it once close enough to an optimum.
double mean_height_t(const Medium& m) {
  double y = 0;
  for (const Grain& g : m.grains) y += g.y;
  return 1 + y / static_cast<double>(m.grains.size()) / m.height;
}

std::vector<Candidate> evaluated(const Strategy& s, std::int64_t g) {
  std::vector<Candidate> c = s.propose(g);
  for (Candidate& k : c) {
    k.eval.outcome = Outcome::passed;
    k.eval.tortuosity = mean_height_t(k.medium);
  }
  return c;
}

SearchOptions cmaes_options() {
  SearchOptions o = test::small_search_options(8);
  o.strategy.kind = StrategyKind::cmaes;
  return o;
}

Configuration start(const SearchOptions& o) {
  Configuration c = test::small_search_start(o);
  c.eval.tortuosity = mean_height_t(c.medium);
  return c;
}

TEST(Cmaes, ClimbsAMadeUpObjectiveWithCandidatesThatKeepTheSpacingRule) {
  const SearchOptions o = cmaes_options();
  const Configuration s0 = start(o);
  auto s = make_strategy(o, s0, "");
  EXPECT_EQ(s->state(), "");  // nothing told yet
  for (int g = 1; g <= 60; ++g) {
    const std::vector<Candidate> c = evaluated(*s, g);
    ASSERT_EQ(c.size(), 8u);
    for (const Candidate& k : c) {
      EXPECT_EQ(k.kind, MoveKind::all);
      EXPECT_FALSE(find_spacing_violation(k.medium, o.gap)) << "generation " << g << " candidate " << k.index;
    }
    // Proposing is a question, not a step: asked again, the same candidates.
    EXPECT_EQ(s->propose(g, 3).medium, c[3].medium);
    const double before = s->current().eval.tortuosity;
    const int kept = s->tell(g, c);
    // Elitist: the best candidate is kept when it beats the current arrangement, and only then.
    int best = 0;
    for (const Candidate& k : c)
      if (k.eval.tortuosity > c[static_cast<std::size_t>(best)].eval.tortuosity) best = k.index;
    EXPECT_EQ(kept, c[static_cast<std::size_t>(best)].eval.tortuosity > before ? best : -1) << "generation " << g;
  }
  // The grains rose by a good part of the box (a random walk of steps of 1 would move their mean
  // by well under one length unit in 480 samples, keeping only the best).
  const double rise = (s->current().eval.tortuosity - s0.eval.tortuosity) * s0.medium.height;
  EXPECT_GT(rise, 10.0) << "T " << s0.eval.tortuosity << " -> " << s->current().eval.tortuosity;
}

TEST(Cmaes, ReplayingItsStoredStatesRebuildsItBitForBit) {
  const SearchOptions o = cmaes_options();
  auto s = make_strategy(o, start(o), "");
  std::vector<std::string> states;
  for (int g = 1; g <= 12; ++g) {
    s->tell(g, evaluated(*s, g));
    states.push_back(s->state());
    if (g == 6) states.push_back(s->state());  // a migration stores the last told state again
  }
  EXPECT_NE(states.front().find("\"start\""), std::string::npos);  // the first holds the Gaussian's start
  EXPECT_EQ(states.back().find("\"start\""), std::string::npos);
  std::string all = "[";
  for (const std::string& st : states) {
    if (all.size() > 1) all.push_back(',');
    all.append(st);
  }
  all += "]";
  // Resumed from the current arrangement the drive stores, whatever the start was.
  auto again = make_strategy(o, s->current(), all);
  EXPECT_EQ(again->state(), s->state());
  for (int k = 0; k < o.lambda; ++k) EXPECT_EQ(again->propose(13, k).medium, s->propose(13, k).medium) << k;
  const auto next = evaluated(*s, 13);
  EXPECT_EQ(again->tell(13, next), s->tell(13, next));
  EXPECT_EQ(again->state(), s->state());
  EXPECT_EQ(again->propose(14, 0).medium, s->propose(14, 0).medium);

  // Another strategy's state, a state of another population size, one without its start, or no
  // array at all: refused, naming the strategy.
  for (const std::string& bad : {std::string(R"({"step": 1})"), std::string(R"([{"step": 1}])"),
                                 std::string(R"([{"generation": 1, "values": [1, 2]}])"), "[" + states[1] + "]"}) {
    SCOPED_TRACE(bad.substr(0, 60));
    try {
      make_strategy(o, start(o), bad);
      ADD_FAILURE() << "accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("strategy cmaes: stored state"), std::string::npos) << e.what();
    }
  }
  EXPECT_TRUE(resumes_by_replay(StrategyKind::cmaes));
  EXPECT_FALSE(resumes_by_replay(StrategyKind::es));
}

TEST(Cmaes, NeedsAPopulationOfFive) {
  SearchOptions o = cmaes_options();
  o.lambda = 4;
  std::string why;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_EQ(why, "lambda = 4: --strategy cmaes needs a population of at least 5");
  o.lambda = 5;
  EXPECT_TRUE(o.IsValid(&why)) << why;
}

}  // namespace
}  // namespace softdrop
