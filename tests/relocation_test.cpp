// The relocation move: a grain the droplet did not touch is put next to its path. Where it goes,
// its place in the generation schedule, every strategy using it deterministically, and histories
// written before it existed (schema version 3) widened in place to hold it.
#include <SQLiteCpp/SQLiteCpp.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "media/spacing.hpp"
#include "optimizer/strategy.hpp"
#include "search_cli.hpp"
#include "search_fixtures.hpp"
#include "softdrop/store.hpp"

namespace softdrop {
namespace {

using test::dump;
using test::fresh;
using test::kScene;
using test::run;

// Distance from (x, y) to the nearest path point inside the medium, x periodic.
double distance_to_path(const Evaluation& e, const Medium& m, double x, double y) {
  double best = INFINITY;
  for (std::size_t p = 0; p < e.path_x.size(); ++p) {
    if (!(e.path_y[p] > 0 && e.path_y[p] < m.height)) continue;
    double dx = std::fmod(std::abs(e.path_x[p] - x), m.width);
    dx = std::min(dx, m.width - dx);
    best = std::min(best, std::hypot(dx, e.path_y[p] - y));
  }
  return best;
}

TEST(Relocation, MovesOneUntouchedGrainIntoTheDropletsWay) {
  SearchOptions o = test::small_search_options();
  o.relocate_every = 3;
  EXPECT_EQ(move_kind(3, o), MoveKind::relocate);
  EXPECT_EQ(move_kind(4, o), MoveKind::all);
  EXPECT_EQ(move_kind(30, o), MoveKind::single);  // single moves take precedence
  const Configuration parent = test::small_search_start(o);
  const auto& touched = parent.eval.touched;
  ASSERT_LT(touched.size(), parent.medium.grains.size());
  int moved = 0;
  for (int k = 0; k < 20; ++k) {
    const Candidate c = make_candidate(parent, 3, k, o);
    ASSERT_EQ(c.kind, MoveKind::relocate);
    EXPECT_FALSE(std::binary_search(touched.begin(), touched.end(), c.moved_grain)) << c.moved_grain;
    int changed = 0;
    for (std::size_t i = 0; i < c.medium.grains.size(); ++i)
      if (!(c.medium.grains[i] == parent.medium.grains[i])) ++changed;
    EXPECT_EQ(changed, c.moved);
    if (c.moved == 0) continue;
    ++moved;
    const Grain& g = c.medium.grains[static_cast<std::size_t>(c.moved_grain)];
    EXPECT_EQ(g.r, parent.medium.grains[static_cast<std::size_t>(c.moved_grain)].r);
    EXPECT_LE(distance_to_path(parent.eval, parent.medium, g.x, g.y), o.droplet.radius + g.r);
    EXPECT_FALSE(find_spacing_violation(c.medium, o.gap).has_value());
  }
  EXPECT_GE(moved, 15);  // the small scene has room beside the path for nearly every draw
  EXPECT_EQ(make_candidate(parent, 3, 1, o).medium, make_candidate(parent, 3, 1, o).medium);
}

TEST(Relocation, EveryStrategyUsesItAndGivesTheSameHistoryOnAnyThreadCount) {
  for (const StrategyKind kind : {StrategyKind::paper, StrategyKind::es, StrategyKind::lahc, StrategyKind::anneal}) {
    SCOPED_TRACE(to_string(kind));
    SearchOptions o = test::small_search_options(4);
    o.strategy.kind = kind;
    o.relocate_every = 2;
    auto history = [&](int threads, int lanes) {
      Search s(o, test::small_search_start(o), 0);
      std::vector<Generation> out;
      for (int g = 0; g < 6; ++g) out.push_back(s.next(threads, lanes));
      return out;
    };
    const auto one = history(1, 1), two = history(2, 3);
    int relocations = 0;
    for (std::size_t g = 0; g < one.size(); ++g) {
      EXPECT_EQ(one[g].accepted, two[g].accepted);
      EXPECT_EQ(one[g].best_t, two[g].best_t);
      EXPECT_EQ(one[g].state, two[g].state);
      for (const Candidate& c : one[g].candidates) relocations += c.kind == MoveKind::relocate;
    }
    EXPECT_GE(relocations, 4);
  }
}

TEST(Relocation, AVersionThreeHistoryIsWidenedInPlaceAndKeepsItsRuns) {
  const std::string db = fresh("relocate_v3.db");
  ASSERT_EQ(run("optimize --db " + db + kScene + " --generations 3").code, 0);
  {  // make it the file an earlier softdrop wrote: the narrower CHECK, schema version 3
    SQLite::Database w(db, SQLite::OPEN_READWRITE);
    const int v = w.execAndGet("PRAGMA schema_version").getInt();
    w.exec(
        "PRAGMA writable_schema = ON; UPDATE sqlite_master SET sql = replace(sql, ', ''relocate''', '') "
        "WHERE name = 'generations'; PRAGMA schema_version = " +
        std::to_string(v + 1) + "; PRAGMA writable_schema = OFF; PRAGMA user_version = 3");
    EXPECT_THROW(w.exec("UPDATE generations SET kind = 'relocate' WHERE generation = 1"), SQLite::Exception);
  }
  const std::string before = dump(db, 1);
  EXPECT_EQ(open_history(db, OpenMode::read_only)->runs().size(), 1u);  // read as it is
  const auto r = run("optimize --db " + db + kScene + " --generations 4 --relocate-every 2");
  ASSERT_EQ(r.code, 0) << r.err;
  SQLite::Database d(db, SQLite::OPEN_READONLY);
  EXPECT_EQ(d.execAndGet("PRAGMA user_version").getInt(), kHistorySchemaVersion);
  EXPECT_EQ(d.execAndGet("PRAGMA integrity_check").getString(), "ok");
  // es draws each candidate's move: candidate n of the run (from 1) is a single move where n is a
  // multiple of --single-every (10), else a relocation where n is even. Each is stored with its
  // kind, and the generations that hold several kinds are 'mixed'.
  const int lambda = d.execAndGet("SELECT lambda FROM runs WHERE id = 2").getInt();
  int relocations = 0;
  for (int n = 1; n <= 4 * lambda; ++n) relocations += n % 10 != 0 && n % 2 == 0;
  EXPECT_EQ(d.execAndGet("SELECT count(*) FROM candidates WHERE run_id = 2 AND kind = 'relocate'").getInt(),
            relocations);
  EXPECT_EQ(d.execAndGet("SELECT count(*) FROM candidates_view WHERE run = 2 AND kind = 'relocate'").getInt(),
            relocations);
  EXPECT_EQ(d.execAndGet("SELECT count(*) FROM generations WHERE run_id = 2 AND kind = 'mixed'").getInt(), 4);
  EXPECT_EQ(dump(db, 1), before);
  // The history shows the move, and a resume keeps the stored option.
  EXPECT_NE(run("history --db " + db + " --run 2 --candidates").out.find("relocate"), std::string::npos);
  const auto again = run("optimize --db " + db + " --resume 2 --generations 6 --relocate-every 3");
  EXPECT_EQ(again.code, 1);
  EXPECT_NE(again.err.find("relocate-every"), std::string::npos) << again.err;
  const auto bad = run("optimize --db " + fresh("relocate_bad.db") + kScene + " --relocate-every -1");
  EXPECT_EQ(bad.code, 1);
  EXPECT_NE(bad.err.find("relocate-every = -1: must be >= 0"), std::string::npos) << bad.err;
}

}  // namespace
}  // namespace softdrop
