// The island model: islands' seeds and migrations, the same histories on any thread count, a kill
// at random instants resumed bit for bit, and the store's island columns on old and new files.
#include "optimizer/islands.hpp"

#include <SQLiteCpp/SQLiteCpp.h>
#include <gtest/gtest.h>

#include <bit>
#include <chrono>
#include <random>
#include <sstream>
#include <thread>

#include "optimizer/strategy.hpp"
#include "search_cli.hpp"
#include "search_fixtures.hpp"
#include "softdrop/store.hpp"
#include "util/random.hpp"

namespace softdrop {
namespace {

using test::dump;
using test::fresh;
using test::kScene;
using test::run;

// A double's exact bits, as text.
std::string bits(double v) { return std::to_string(std::bit_cast<std::uint64_t>(v)); }

// Every island's stored rows, runs 1 .. k.
std::string islands_dump(const std::string& db, int k, std::int64_t upto = -1) {
  std::string out;
  for (int run_id = 1; run_id <= k; ++run_id) out += dump(db, run_id, upto) + "#\n";
  return out;
}

// The lowest committed generation over the islands (runs 1 .. k), -1 before all exist.
std::int64_t lowest_committed(const std::string& db, int k) {
  if (!test::has_run(db)) return -1;
  SQLite::Database d(db, SQLite::OPEN_READONLY);
  if (d.execAndGet("SELECT count(*) FROM runs").getInt() < k) return -1;
  return d.execAndGet("SELECT min(g) FROM (SELECT max(generation) AS g FROM generations GROUP BY run_id)").getInt64();
}

TEST(Islands, RingAndBroadcastChooseTheirImmigrants) {
  std::vector<Configuration> bests(4);
  const double t[] = {1.3, 1.7, 1.5, 1.7};
  std::vector<const Configuration*> p;
  for (int i = 0; i < 4; ++i) bests[i].eval.tortuosity = t[i], p.push_back(&bests[i]);
  const auto ring = immigrants(p, Migration::ring), broadcast = immigrants(p, Migration::broadcast);
  EXPECT_EQ(ring[0], &bests[3]);
  EXPECT_EQ(ring[1], &bests[0]);
  EXPECT_EQ(ring[3], &bests[2]);
  for (const Configuration* c : broadcast) EXPECT_EQ(c, &bests[1]);  // the lowest of the two best
  EXPECT_TRUE(is_migration(10, {4, 5, Migration::ring}));
  EXPECT_FALSE(is_migration(11, {4, 5, Migration::ring}));
  EXPECT_FALSE(is_migration(10, {1, 5, Migration::ring}));  // one island: no migrations
  EXPECT_FALSE(is_migration(10, {4, 0, Migration::ring}));  // migrate-every 0: none either
  EXPECT_EQ((IslandOptions{4, 5, Migration::ring}.next_migration(0)), 5);
  EXPECT_EQ((IslandOptions{4, 5, Migration::ring}.next_migration(9)), 10);
  EXPECT_EQ((IslandOptions{4, 5, Migration::ring}.next_migration(10)), 15);
  EXPECT_EQ((IslandOptions{4, 0, Migration::ring}.next_migration(10)), std::numeric_limits<std::int64_t>::max());
  EXPECT_EQ((IslandOptions{1, 5, Migration::ring}.next_migration(10)), std::numeric_limits<std::int64_t>::max());
  EXPECT_EQ((IslandOptions{4, 5, Migration::ring}.next_stop(9, 12)), 10);
  EXPECT_EQ((IslandOptions{4, 5, Migration::ring}.next_stop(10, 15)), 15);
  EXPECT_EQ((IslandOptions{4, 5, Migration::ring}.next_stop(10, 14)), 15);  // past the end: 14 + 1
  EXPECT_EQ((IslandOptions{4, 5, Migration::ring}.next_stop(10, 12)), 13);
  EXPECT_EQ((IslandOptions{1, 5, Migration::ring}.next_stop(10, 12)), 13);
  EXPECT_EQ(island_search_options(SearchOptions{}, 2).seed, derive_seed(SearchOptions{}.seed, 2));
}

TEST(Islands, AnImmigrantIsKeptOnlyIfItBeatsTheIslandsBest) {
  const SearchOptions o = test::small_search_options();
  Search a(o, test::small_search_start(o), 0), b(island_search_options(o, 1), test::small_search_start(o), 0);
  for (int g = 0; g < 6; ++g) a.next(1), b.next(1);
  Search& better = a.best().eval.tortuosity >= b.best().eval.tortuosity ? a : b;
  Search& worse = &better == &a ? b : a;
  ASSERT_GT(better.best().eval.tortuosity, worse.best().eval.tortuosity) << "the two lineages tie";
  const Configuration incoming = better.best(), own = worse.best();
  const Generation kept = worse.immigrate(incoming);
  EXPECT_EQ(kept.kind, MoveKind::migrate);
  EXPECT_EQ(kept.number, 7);
  EXPECT_EQ(kept.accepted, 0);
  ASSERT_EQ(kept.candidates.size(), 1u);
  EXPECT_GT(kept.candidates[0].moved, 0);
  EXPECT_EQ(worse.best().medium, incoming.medium);
  EXPECT_EQ(worse.best().generation, 7);
  EXPECT_EQ(worse.strategy().current().medium, incoming.medium);  // the lineage goes on from it
  const Generation refused = better.immigrate(own);
  EXPECT_EQ(refused.accepted, -1);
  EXPECT_EQ(better.best().medium, incoming.medium);
}

TEST(Islands, DrivenOnTwoThreadsTheyMakeWhatOneThreadMakes) {
  const SearchOptions o = test::small_search_options(2);
  const IslandOptions io{2, 3, Migration::broadcast};
  auto islands_of = [&] {
    std::vector<Search> v;
    for (int i = 0; i < io.islands; ++i) v.emplace_back(island_search_options(o, i), test::small_search_start(o), 0);
    return v;
  };
  auto trace = [](std::string* out) {
    IslandCallbacks cb;
    cb.generation = [out](int i, const Generation& g, const Configuration& best) {
      std::ostringstream line;
      line << i << ':' << g.number << ':' << g.accepted << ':' << bits(best.eval.tortuosity) << '\n';
      *out += line.str();
      return true;
    };
    cb.migration = [out](const std::vector<Generation>& gs, const std::vector<Configuration>& bests) {
      std::ostringstream lines;
      for (std::size_t i = 0; i < gs.size(); ++i)
        lines << 'm' << i << ':' << gs[i].accepted << ':' << bits(bests[i].eval.tortuosity) << '\n';
      *out += lines.str();
      return true;
    };
    return cb;
  };
  DriveOptions d;
  d.generations = 8;
  std::vector<Search> one = islands_of(), two = islands_of();
  std::string a, b;
  d.threads = 1;
  const SearchSummary sa = drive_islands(one, io, d, trace(&a));
  d.threads = 2;
  const SearchSummary sb = drive_islands(two, io, d, trace(&b));
  // The order of the islands' reports may differ; what each island reported may not.
  auto sorted = [](std::string s) {
    std::vector<std::string> lines;
    for (std::size_t at = 0, end; (end = s.find('\n', at)) != std::string::npos; at = end + 1)
      lines.push_back(s.substr(at, end - at));
    std::stable_sort(lines.begin(), lines.end(),
                     [](const std::string& x, const std::string& y) { return x[0] < y[0]; });
    std::ostringstream joined;
    for (const std::string& l : lines) joined << l << '\n';
    return joined.str();
  };
  EXPECT_EQ(sorted(a), sorted(b));
  EXPECT_EQ(sa.termination, Termination::generations);
  EXPECT_EQ(sa.last_generation, 8);
  EXPECT_EQ(sa.best_t, sb.best_t);
  EXPECT_EQ(sa.evaluations, 2 * 6 * 2);  // generations 3 and 6 are migrations
  for (int i = 0; i < 2; ++i) EXPECT_EQ(one[i].best().medium, two[i].best().medium);
}

TEST(Islands, WithoutMigrationEachIslandIsTheSearchOfItsOwnSeed) {
  // --migrate-every 0: independent lineages from the same start. Island i's history is, row for
  // row, that of one search with island i's seed, and the summary's best is the best of them.
  const std::string db = fresh("islands_apart.db"), alone = fresh("islands_alone.db");
  const auto r = run("optimize --db " + db + kScene + " --islands 2 --migrate-every 0 --generations 8 --lambda 2");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("no migration"), std::string::npos) << r.out;
  for (int island = 0; island < 2; ++island) {
    SearchOptions scene;
    scene.seed = 7;  // kScene's
    std::string args = kScene;
    args.replace(args.find("--seed 7"), 8, "--seed " + std::to_string(island_search_options(scene, island).seed));
    std::filesystem::remove(alone);
    ASSERT_EQ(run("optimize --db " + alone + args + " --generations 8 --lambda 2").code, 0);
    EXPECT_EQ(dump(db, island + 1, 8), dump(alone, 1, 8)) << "island " << island;
  }
  SQLite::Database d(db, SQLite::OPEN_READONLY);
  EXPECT_EQ(d.execAndGet("SELECT count(*) FROM generations WHERE kind = 'migrate'").getInt(), 0);
}

TEST(Islands, OwnStartsGiveEachIslandTheMediumOfItsOwnSeed) {
  // --island-starts own: island i starts from the medium a plain run with medium seed
  // derive_seed(medium seed, i) starts from; a resume that says otherwise is refused untouched.
  const std::string db = fresh("islands_own.db"), alone = fresh("islands_own_alone.db");
  ASSERT_EQ(
      run("optimize --db " + db + kScene + " --islands 3 --migrate-every 0 --island-starts own --generations 2").code,
      0);
  std::string starts;
  for (int island = 0; island < 3; ++island) {
    std::string args = kScene;
    args.replace(args.find("--medium-seed 2"), 15,
                 "--medium-seed " + std::to_string(derive_seed(2, static_cast<std::uint64_t>(island))));
    std::filesystem::remove(alone);
    ASSERT_EQ(run("optimize --db " + alone + args + " --generations 0").code, 0);
    EXPECT_EQ(dump(db, island + 1, 0), dump(alone, 1, 0)) << "island " << island;
    EXPECT_EQ(starts.find(dump(alone, 1, 0)), std::string::npos) << "island " << island << " starts as another";
    starts += dump(alone, 1, 0);
  }
  const std::string before = islands_dump(db, 3);
  const auto r = run("optimize --db " + db + " --resume 2 --island-starts shared --generations 4");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("--island-starts \"shared\" (stored \"own\")"), std::string::npos) << r.err;
  EXPECT_EQ(islands_dump(db, 3), before);
  ASSERT_EQ(run("optimize --db " + db + " --resume 2 --generations 4").code, 0);  // every island goes on
  EXPECT_EQ(lowest_committed(db, 3), 4);
}

TEST(Islands, TheSameHistoryOnAnyThreadCountWithAndWithoutSpeculation) {
  for (const auto& [strategy, lambda] : {std::pair<std::string, int>{"paper", 2}, {"es", 2}, {"cmaes", 5}}) {
    SCOPED_TRACE(strategy);
    const std::string args = kScene + " --islands 3 --migrate-every 4 --generations 13 --lambda " +
                             std::to_string(lambda) + " --strategy " + strategy;
    const std::string one = fresh("islands_1.db"), two = fresh("islands_2.db"), plain = fresh("islands_ns.db");
    ASSERT_EQ(run("optimize --db " + one + args + " --threads 1").code, 0);
    ASSERT_EQ(run("optimize --db " + two + args + " --threads 2").code, 0);
    ASSERT_EQ(run("optimize --db " + plain + args + " --threads 2 --no-speculation").code, 0);
    EXPECT_EQ(islands_dump(one, 3), islands_dump(two, 3));
    EXPECT_EQ(islands_dump(one, 3), islands_dump(plain, 3));
    SQLite::Database d(one, SQLite::OPEN_READONLY);
    EXPECT_EQ(d.execAndGet("SELECT group_concat(island || ':' || archipelago) FROM runs").getString(), "0:1,1:1,2:1");
    EXPECT_EQ(d.execAndGet("SELECT count(*) FROM generations WHERE kind = 'migrate'").getInt(), 3 * 3);  // 4, 8, 12
    EXPECT_EQ(d.execAndGet("SELECT count(DISTINCT seed) FROM runs").getInt(), 3);
    // A migration counts no evaluation: each island has generation 0's and lambda a generation.
    EXPECT_EQ(d.execAndGet("SELECT min(evaluations) || ',' || max(evaluations) FROM runs").getString(),
              std::to_string(1 + 10 * lambda) + "," + std::to_string(1 + 10 * lambda));
  }
}

// CMA-ES resumes by replaying the values told in every stored generation, migrations among them
// (which tell it nothing): stopped after a migration and resumed, the islands go on as if never
// stopped.
TEST(Islands, CmaesStoppedAfterAMigrationResumesToTheSameHistory) {
  const std::string args = kScene + " --islands 2 --migrate-every 3 --lambda 5 --threads 2 --strategy cmaes";
  const std::string whole = fresh("islands_cmaes.db"), parts = fresh("islands_cmaes_parts.db");
  ASSERT_EQ(run("optimize --db " + whole + args + " --generations 10").code, 0);
  ASSERT_EQ(run("optimize --db " + parts + args + " --generations 4").code, 0);
  const auto r = run("optimize --db " + parts + args + " --resume 1 --generations 10");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(islands_dump(parts, 2), islands_dump(whole, 2));
  SQLite::Database d(whole, SQLite::OPEN_READONLY);
  EXPECT_EQ(d.execAndGet("SELECT count(*) FROM generations WHERE kind = 'migrate'").getInt(), 2 * 3);  // 3, 6, 9
}

TEST(Islands, KilledAtRandomInstantsTheyResumeBitForBit) {
  const std::string args =
      kScene + " --islands 3 --migrate-every 5 --generations 40 --lambda 2 --threads 2 --strategy lahc";
  const std::string ref = fresh("islands_ref.db"), killed = fresh("islands_killed.db");
  ASSERT_EQ(run("optimize --db " + ref + args).code, 0);
  std::mt19937 rng(5);
  std::vector<std::pair<std::int64_t, std::string>> committed;
  for (int attempt = 0; attempt < 6; ++attempt) {
    if (lowest_committed(killed, 3) < 0) std::filesystem::remove(killed);  // killed while the islands were being made
    const bool resume = test::has_run(killed);
    const pid_t pid = test::spawn("optimize --db " + killed + args + (resume ? " --resume 2" : ""));
    std::this_thread::sleep_for(
        std::chrono::milliseconds(std::uniform_int_distribution<int>(20, test::kAddressSanitizer ? 900 : 300)(rng)));
    kill(pid, SIGKILL);
    const int code = test::wait_for(pid);
    ASSERT_TRUE(code == -SIGKILL || code == 0) << code;
    if (const std::int64_t g = lowest_committed(killed, 3); g >= 0)
      committed.emplace_back(g, islands_dump(killed, 3, g));
  }
  if (lowest_committed(killed, 3) < 0) std::filesystem::remove(killed);  // killed while the islands were being made
  const auto fin = run("optimize --db " + killed + args + (test::has_run(killed) ? " --resume 1" : ""));
  ASSERT_EQ(fin.code, 0) << fin.err;
  for (const auto& [g, rows] : committed) EXPECT_EQ(islands_dump(killed, 3, g), rows) << "generation " << g;
  EXPECT_EQ(islands_dump(killed, 3), islands_dump(ref, 3));
}

TEST(Islands, BadOptionsAndContradictionsGetOneLine) {
  const std::string db = fresh("islands_bad.db");
  for (const auto& [args, says] : std::vector<std::pair<std::string, std::string>>{
           {" --islands 0", "islands = 0: must be in [1, 1024]"},
           {" --islands 3 --migrate-every 1", "migrate-every = 1: must be 0 (never) or >= 2"},
           {" --islands 3 --migrate-every -4", "migrate-every = -4: must be 0 (never) or >= 2"},
           {" --islands 3 --migration star", "star"},
           {" --island-starts own", "island-starts = own: an option of --islands K (K > 1)"},
           {" --islands 2 --island-starts own --medium grains.json",
            "island-starts = own: needs generated media, not --medium grains.json"},
           {" --islands 2 --island-starts mine", "mine"}}) {
    // (with --medium, the scene's medium options would be refused first)
    const bool file = args.find("--medium") != std::string::npos;
    const auto r = run("optimize --db " + db + (file ? std::string(" --quiet ") : kScene) + args);
    EXPECT_NE(r.code, 0) << args;
    EXPECT_NE(r.err.find(says), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(db));
  }
  ASSERT_EQ(run("optimize --db " + db + kScene + " --islands 2 --generations 3").code, 0);
  const std::string before = islands_dump(db, 2);
  const auto r = run("optimize --db " + db + " --resume 1 --migrate-every 7 --generations 6");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("--migrate-every 7 (stored 50)"), std::string::npos) << r.err;
  EXPECT_EQ(islands_dump(db, 2), before);
  // A plain run resumed with islands is refused too.
  ASSERT_EQ(run("optimize --db " + db + kScene + " --generations 2").code, 0);
  const auto p = run("optimize --db " + db + " --resume 3 --islands 2 --generations 4");
  EXPECT_EQ(p.code, 1);
  EXPECT_NE(p.err.find("--islands 2 (stored nothing)"), std::string::npos) << p.err;
}

TEST(Islands, AVersionFourHistoryGainsTheIslandColumnsAndKeepsItsRuns) {
  const std::string db = fresh("islands_v4.db");
  ASSERT_EQ(run("optimize --db " + db + kScene + " --generations 3").code, 0);
  {  // the file an earlier softdrop wrote: no island columns, no 'migrate' kind, schema version 4
    SQLite::Database w(db, SQLite::OPEN_READWRITE);
    w.exec("DROP VIEW runs_view");  // the views came with version 8
    w.exec("ALTER TABLE runs DROP COLUMN island; ALTER TABLE runs DROP COLUMN archipelago");
    const int v = w.execAndGet("PRAGMA schema_version").getInt();
    w.exec(
        "PRAGMA writable_schema = ON; UPDATE sqlite_master SET sql = replace(sql, ', ''migrate''', '') "
        "WHERE name = 'generations'; PRAGMA schema_version = " +
        std::to_string(v + 1) + "; PRAGMA writable_schema = OFF; PRAGMA user_version = 4");
  }
  const std::string before = dump(db, 1);
  const auto old = open_history(db, OpenMode::read_only)->runs();  // read as it is
  ASSERT_EQ(old.size(), 1u);
  EXPECT_EQ(old[0].island, -1);
  ASSERT_EQ(run("optimize --db " + db + kScene + " --islands 2 --migrate-every 2 --generations 3").code, 0);
  SQLite::Database d(db, SQLite::OPEN_READONLY);
  EXPECT_EQ(d.execAndGet("PRAGMA user_version").getInt(), kHistorySchemaVersion);
  EXPECT_EQ(d.execAndGet("PRAGMA integrity_check").getString(), "ok");
  EXPECT_EQ(d.execAndGet("SELECT count(*) FROM generations WHERE kind = 'migrate'").getInt(), 2);
  EXPECT_EQ(dump(db, 1), before);
  const auto runs = open_history(db, OpenMode::read_only)->runs();
  EXPECT_EQ(runs[0].island, -1);
  EXPECT_EQ(runs[2].island, 1);
  EXPECT_EQ(runs[2].archipelago, 2);
}

}  // namespace
}  // namespace softdrop
