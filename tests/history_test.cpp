// The SQLite history: what is written reads back exactly; files that are not softdrop databases
// (missing, foreign, truncated, newer) are refused with one line and left byte-for-byte unchanged.
#include <SQLiteCpp/SQLiteCpp.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "cli_run.hpp"
#include "media/spacing.hpp"
#include "search_fixtures.hpp"
#include "softdrop/store.hpp"
#include "store/params_json.hpp"

namespace softdrop {
namespace {

using test::fresh;

std::string bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// A run of `generations` generations written through the interface.
std::int64_t write_run(History& h, const SearchOptions& o, int generations, Search** out = nullptr) {
  Configuration best;
  const Generation g0 = initial_generation(test::small_search_medium(), o, &best);
  const std::int64_t id = h.create_run(search_params_to_json(o), o, g0, best);
  static thread_local std::unique_ptr<Search> search;
  search = std::make_unique<Search>(o, best, 0);
  for (int i = 0; i < generations; ++i) {
    const Generation g = search->next(1);
    h.append(id, g, search->best());
  }
  if (out) *out = search.get();
  return id;
}

TEST(History, WhatIsWrittenReadsBackExactly) {
  const std::string path = fresh("roundtrip.db");
  auto h = open_history(path, OpenMode::create);
  const SearchOptions o = test::small_search_options(2);
  Search* search = nullptr;
  const std::int64_t id = write_run(*h, o, 12, &search);
  EXPECT_EQ(id, 1);

  const RunRecord r = h->run(id);
  EXPECT_EQ(r.status, "running");
  EXPECT_EQ(r.generations, 12);
  EXPECT_EQ(r.evaluations, 1 + 12 * 2);
  EXPECT_EQ(r.grains, 16);
  EXPECT_EQ(r.lambda, 2);
  EXPECT_EQ(r.seed, 7u);
  EXPECT_EQ(r.best_t, search->best().eval.tortuosity);
  EXPECT_EQ(r.best_generation, search->best().generation);
  EXPECT_EQ(search_params_to_json(search_params_from_json(r.params)), search_params_to_json(o));

  const auto gens = h->generations(id);
  ASSERT_EQ(gens.size(), 13u);
  double best = 0;
  for (std::size_t i = 0; i < gens.size(); ++i) {
    EXPECT_EQ(gens[i].generation, static_cast<std::int64_t>(i));
    EXPECT_GE(gens[i].best_t, best);
    best = gens[i].best_t;
    EXPECT_EQ(gens[i].candidates.size(), i == 0 ? 1u : 2u);
    if (gens[i].accepted >= 0) {
      const Configuration c = h->configuration(id, gens[i].generation);
      EXPECT_EQ(c.generation, gens[i].generation);
      EXPECT_EQ(c.eval.tortuosity, gens[i].best_t);
      EXPECT_FALSE(find_spacing_violation(c.medium, o.gap).has_value());
      // Rebuilt from the database alone, the configuration gives its stored T bit for bit.
      const Evaluation again = evaluate(c.medium, o);
      EXPECT_EQ(again.tortuosity, c.eval.tortuosity);
      EXPECT_EQ(again.touched, c.eval.touched);
      EXPECT_EQ(again.path_x, c.eval.path_x);
      EXPECT_EQ(again.path_y, c.eval.path_y);
    }
  }
  const Configuration latest = h->configuration(id, -1);
  EXPECT_EQ(latest.medium, search->best().medium);
  EXPECT_EQ(latest.eval.touched, search->best().eval.touched);

  h->set_status(id, "finished");
  EXPECT_EQ(h->run(id).status, "finished");
  EXPECT_THROW(h->run(99), std::runtime_error);
  // A generation that does not follow the stored one is refused (e.g. two writers on one run).
  Generation stale;
  stale.number = 5;
  EXPECT_THROW(h->append(id, stale, search->best()), std::runtime_error);
  EXPECT_EQ(h->generations(id).size(), 13u);
}

TEST(History, TheWalIsCheckpointedAndStaysBounded) {
  // 600 accepted generations with long paths write ~20 MB of pages; automatic checkpoints must
  // keep folding them into the database so that the WAL never grows far past 1000 pages.
  const std::string path = fresh("wal.db");
  auto h = open_history(path, OpenMode::create);
  const SearchOptions o = test::small_search_options();
  Configuration best;
  const Generation g0 = initial_generation(test::small_search_medium(), o, &best);
  const std::int64_t id = h->create_run(search_params_to_json(o), o, g0, best);
  Generation g = g0;
  g.kind = MoveKind::all;
  g.candidates[0].eval.path_x.assign(2000, 1.5);  // the kept candidate's path is stored
  g.candidates[0].eval.path_y.assign(2000, 2.5);
  for (int i = 1; i <= 600; ++i) {
    g.number = best.generation = i;
    best.eval.tortuosity += 1e-3;
    g.best_t = best.eval.tortuosity;
    h->append(id, g, best);
  }
  EXPECT_GT(std::filesystem::file_size(path), 10'000'000u);
  EXPECT_LT(std::filesystem::file_size(path + "-wal"), 1200u * 4096u);
}

TEST(History, SchemaIsVersionedAndForeignKeysHold) {
  const std::string path = fresh("schema.db");
  {
    auto h = open_history(path, OpenMode::create);
    write_run(*h, test::small_search_options(), 2);
  }
  SQLite::Database db(path, SQLite::OPEN_READWRITE);
  EXPECT_EQ(db.execAndGet("PRAGMA user_version").getInt(), kHistorySchemaVersion);
  EXPECT_EQ(db.execAndGet("PRAGMA application_id").getInt(), kHistoryApplicationId);
  EXPECT_EQ(db.execAndGet("PRAGMA journal_mode").getString(), "wal");
  EXPECT_EQ(db.execAndGet("PRAGMA integrity_check").getString(), "ok");
  db.exec("PRAGMA foreign_keys = ON");
  EXPECT_THROW(db.exec("INSERT INTO candidates VALUES (1, 999, 0, NULL, 0, 'passed', '', 1.0, 1, 0, 0)"),
               SQLite::Exception);
  EXPECT_THROW(db.exec("INSERT INTO generations VALUES (42, 1, 'all', NULL, 1, 0, 0, '')"), SQLite::Exception);
}

TEST(History, TwoWritersOnOneFileLoseNothing) {
  const std::string path = fresh("two_writers.db");
  { auto h = open_history(path, OpenMode::create); }
  std::int64_t ids[2] = {0, 0};
  std::thread a([&] {
    auto h = open_history(path, OpenMode::create);
    ids[0] = write_run(*h, test::small_search_options(), 10);
  });
  std::thread b([&] {
    SearchOptions o = test::small_search_options();
    o.seed = 8;
    auto h = open_history(path, OpenMode::create);
    ids[1] = write_run(*h, o, 10);
  });
  a.join();
  b.join();
  EXPECT_NE(ids[0], ids[1]);
  auto h = open_history(path, OpenMode::read_only);
  ASSERT_EQ(h->runs().size(), 2u);
  for (std::int64_t id : ids) EXPECT_EQ(h->generations(id).size(), 11u);
}

// Each bad file: one line naming the file and what is wrong; the file is not modified.
void expect_refused(const std::string& path, OpenMode mode, const std::string& words) {
  const std::string before = bytes(path);
  try {
    open_history(path, mode);
    FAIL() << path << " was accepted";
  } catch (const std::runtime_error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find(path), std::string::npos) << m;
    EXPECT_NE(m.find(words), std::string::npos) << m;
    EXPECT_EQ(m.find('\n'), std::string::npos) << m;
  }
  EXPECT_EQ(bytes(path), before) << path << " was modified";
}

TEST(History, BadFilesAreRefusedAndLeftUntouched) {
  const std::string missing = fresh("missing.db");
  expect_refused(missing, OpenMode::read_only, "no such file");
  EXPECT_FALSE(std::filesystem::exists(missing));

  const std::string text = fresh("text.db");
  std::ofstream(text) << "x,y,r\n1,2,3\n" << std::string(200, 'z') << "\n";
  expect_refused(text, OpenMode::create, "not an SQLite database");
  expect_refused(text, OpenMode::read_only, "not an SQLite database");

  const std::string foreign = fresh("foreign.db");
  {
    SQLite::Database db(foreign, SQLite::OPEN_READWRITE | SQLite::OPEN_CREATE);
    db.exec("CREATE TABLE accounts (id INTEGER PRIMARY KEY, owner TEXT); INSERT INTO accounts VALUES (1, 'x')");
  }
  expect_refused(foreign, OpenMode::create, "not a softdrop database");

  const std::string good = fresh("good.db");
  {
    auto h = open_history(good, OpenMode::create);
    write_run(*h, test::small_search_options(), 3);
  }
  {  // fold the WAL into the file, so the copies below are self-contained
    SQLite::Database db(good, SQLite::OPEN_READWRITE);
    db.exec("PRAGMA wal_checkpoint(TRUNCATE); PRAGMA journal_mode = DELETE");
  }
  const std::string newer = fresh("newer.db");
  std::filesystem::copy_file(good, newer);
  {
    SQLite::Database db(newer, SQLite::OPEN_READWRITE);
    db.exec("PRAGMA user_version = 99");
  }
  expect_refused(newer, OpenMode::create, "newer softdrop");
  expect_refused(newer, OpenMode::read_only, "newer softdrop");

  const std::string all = bytes(good);
  ASSERT_GT(all.size(), 8192u);
  const std::string truncated = fresh("truncated.db");
  std::ofstream(truncated, std::ios::binary) << all.substr(0, all.size() / 2);
  expect_refused(truncated, OpenMode::create, "truncated");
  const std::string stub = fresh("stub.db");
  std::ofstream(stub, std::ios::binary) << all.substr(0, 60);
  expect_refused(stub, OpenMode::create, "not an SQLite database");

  const std::string garbled = fresh("garbled.db");
  std::string g = all;
  for (std::size_t i = 4096; i < g.size(); i += 7) g[i] = static_cast<char>(g[i] ^ 0x5A);
  std::ofstream(garbled, std::ios::binary) << g;
  expect_refused(garbled, OpenMode::create, "corrupted");

  // The good file is still fine after all that.
  EXPECT_EQ(open_history(good, OpenMode::read_only)->runs().size(), 1u);
}

}  // namespace
}  // namespace softdrop
