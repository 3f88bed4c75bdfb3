// The search history (History) on a softdrop SQLite database (see sqlite_file.hpp).
#include <SQLiteCpp/SQLiteCpp.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

#include "generation_rows.hpp"
#include "softdrop/store.hpp"
#include "softdrop/version.hpp"
#include "sqlite_file.hpp"
#include "validation_rows.hpp"

namespace softdrop {
namespace {
using detail::kNow;

std::int64_t to_i64(std::uint64_t v) { return static_cast<std::int64_t>(v); }

class SqliteHistory final : public History, private detail::SqliteConnection {
 public:
  SqliteHistory(const std::string& path, OpenMode mode) : SqliteConnection(path, mode) {}

  std::int64_t create_run(const std::string& params_json, const SearchOptions& o, const Generation& g0,
                          const Configuration& best) override {
    return guarded([&] {
      SQLite::Transaction t(db_, SQLite::TransactionBehavior::IMMEDIATE);
      SQLite::Statement q(db_, std::string("INSERT INTO runs (created, updated, version, status, params, "
                                           "seed, lambda, grains, width, height, periodic, generations, "
                                           "evaluations, droplets, best_t, best_generation) VALUES (") +
                                   kNow + ", " + kNow + ", ?, 'running', ?, ?, ?, ?, ?, ?, ?, 0, ?, ?, ?, 0)");
      detail::insert_row(q, kVersion, params_json, to_i64(o.seed), o.lambda,
                         static_cast<std::int64_t>(best.medium.grains.size()), best.medium.width, best.medium.height,
                         best.medium.periodic ? 1 : 0, static_cast<std::int64_t>(g0.candidates.size()), droplets_of(g0),
                         best.eval.tortuosity);
      const std::int64_t run = db_.getLastInsertRowid();
      write_generation(run, g0);
      t.commit();
      return run;
    });
  }

  void append(std::int64_t run, const Generation& g, const Configuration& best) override {
    guarded([&] {
      SQLite::Transaction t(db_, SQLite::TransactionBehavior::IMMEDIATE);
      append_in_transaction(run, g, best);
      t.commit();
      return 0;
    });
  }

  void append_together(const std::vector<std::int64_t>& runs, const std::vector<Generation>& gs,
                       const std::vector<Configuration>& bests) override {
    if (runs.size() != gs.size() || runs.size() != bests.size())
      throw std::logic_error("History::append_together: runs, generations and bests differ in number");
    guarded([&] {
      SQLite::Transaction t(db_, SQLite::TransactionBehavior::IMMEDIATE);
      for (std::size_t i = 0; i < runs.size(); ++i) append_in_transaction(runs[i], gs[i], bests[i]);
      t.commit();
      return 0;
    });
  }

  void set_status(std::int64_t run, const std::string& status) override {
    guarded([&] {
      detail::set_row_status(db_, "runs", run, status, "run");
      return 0;
    });
  }

  void set_island(std::int64_t run, int island, std::int64_t archipelago) override {
    guarded([&] {
      SQLite::Statement q(db_, "UPDATE runs SET island = ?, archipelago = ? WHERE id = ?");
      q.bind(1, island);
      q.bind(2, archipelago);
      q.bind(3, run);
      if (q.exec() != 1) throw std::runtime_error("no run " + std::to_string(run));
      return 0;
    });
  }

  void set_param(std::int64_t run, const std::string& key, const std::string& json_value) override {
    guarded([&] {
      SQLite::Statement q(db_, "UPDATE runs SET params = json_set(params, ?, json(?)) WHERE id = ?");
      q.bind(1, "$.\"" + key + "\"");
      q.bind(2, json_value);
      q.bind(3, run);
      if (q.exec() != 1) throw std::runtime_error("no run " + std::to_string(run));
      return 0;
    });
  }

  std::vector<RunRecord> runs() override {
    return guarded([&] {
      return detail::read_rows(db_, detail::select_runs(schema_version()) + " ORDER BY id", detail::read_run);
    });
  }

  RunRecord run(std::int64_t id) override {
    return guarded([&] {
      return detail::read_row(db_, detail::select_runs(schema_version()) + " WHERE id = ?", id, "run", path_,
                              detail::read_run);
    });
  }

  std::vector<GenerationRecord> generations(std::int64_t run_id) override {
    return guarded([&] {
      run(run_id);  // names a missing run
      // One read transaction, so a writer in another process cannot slip a generation in between.
      SQLite::Transaction t(db_, SQLite::TransactionBehavior::DEFERRED);
      std::vector<GenerationRecord> out = detail::read_generations(db_, run_id, schema_version());
      t.commit();
      return out;
    });
  }

  void check_run(std::int64_t run_id) override {
    guarded([&] {
      const RunRecord r = run(run_id);
      const std::string where = "run " + std::to_string(run_id) + ": ";
      if (const auto params = nlohmann::json::parse(r.params, nullptr, false); !params.is_object())
        throw std::runtime_error(where + "its params are not a JSON object (damaged or edited file?)");
      SQLite::Transaction t(db_, SQLite::TransactionBehavior::DEFERRED);
      SQLite::Statement q(db_,
                          "SELECT count(*), coalesce(min(generation), -1), coalesce(max(generation), -1), "
                          "(SELECT count(*) FROM generations g WHERE g.run_id = ?1 AND NOT EXISTS "
                          "  (SELECT 1 FROM candidates c WHERE c.run_id = ?1 AND c.generation = g.generation)), "
                          "(SELECT count(*) FROM candidates c WHERE c.run_id = ?1 AND NOT EXISTS "
                          "  (SELECT 1 FROM generations g WHERE g.run_id = ?1 AND g.generation = c.generation)) "
                          "FROM generations WHERE run_id = ?1");
      q.bind(1, run_id);
      q.executeStep();
      const std::int64_t count = detail::as_int64(q.getColumn(0)), first = detail::as_int64(q.getColumn(1)),
                         last = detail::as_int64(q.getColumn(2));
      if (first != 0 || last != r.generations || count != r.generations + 1) {
        // The first generation of the run's range that is not stored, if any is missing.
        SQLite::Statement gap(db_,
                              "SELECT CASE WHEN NOT EXISTS (SELECT 1 FROM generations WHERE run_id = ?1 AND "
                              "generation = 0) THEN 0 ELSE (SELECT min(g.generation) + 1 FROM generations g "
                              "WHERE g.run_id = ?1 AND g.generation < ?2 AND NOT EXISTS (SELECT 1 FROM "
                              "generations h WHERE h.run_id = ?1 AND h.generation = g.generation + 1)) END");
        gap.bind(1, run_id);
        gap.bind(2, r.generations);
        gap.executeStep();
        const std::string missing =
            gap.getColumn(0).isNull() ? "" : "generation " + gap.getColumn(0).getString() + " is missing: ";
        throw std::runtime_error(where + missing + "stores " + std::to_string(count) + " generations numbered " +
                                 std::to_string(first) + " to " + std::to_string(last) + ", the run has 0 to " +
                                 std::to_string(r.generations) + " (damaged or edited file?)");
      }
      if (detail::as_int64(q.getColumn(3)) != 0)
        throw std::runtime_error(where + "a generation without candidates (damaged or edited file?)");
      if (detail::as_int64(q.getColumn(4)) != 0)
        throw std::runtime_error(where + "candidates of a missing generation (damaged or edited file?)");
      q.reset();
      // The run's best is its last generation's best so far, to the bit.
      SQLite::Statement b(db_, "SELECT best_t FROM generations WHERE run_id = ? AND generation = ?");
      b.bind(1, run_id);
      b.bind(2, r.generations);
      if (b.executeStep() && detail::as_real(b.getColumn(0)) != r.best_t)
        throw std::runtime_error(where + "best_t " + nlohmann::json(r.best_t).dump() + " differs from its generation " +
                                 std::to_string(r.generations) + "'s best_t " +
                                 nlohmann::json(detail::as_real(b.getColumn(0))).dump() + " (damaged or edited file?)");
      b.reset();
      t.commit();
      return 0;
    });
  }

  std::string strategy_state(std::int64_t run_id, std::int64_t generation) override {
    return guarded([&] {
      if (schema_version() < 3) return std::string();
      SQLite::Statement q(db_, "SELECT state FROM generations WHERE run_id = ? AND generation = ?");
      q.bind(1, run_id);
      q.bind(2, generation);
      if (!q.executeStep())
        throw std::runtime_error("run " + std::to_string(run_id) + ": no generation " + std::to_string(generation));
      return q.getColumn(0).isNull() ? std::string() : detail::as_text(q.getColumn(0));
    });
  }

  std::string strategy_states(std::int64_t run_id, std::int64_t last) override {
    return guarded([&] {
      std::string out = "[";
      if (schema_version() >= 3) {
        SQLite::Statement q(db_,
                            "SELECT state FROM generations WHERE run_id = ? AND generation BETWEEN 1 AND ? "
                            "AND state IS NOT NULL AND state != '' ORDER BY generation");
        q.bind(1, run_id);
        q.bind(2, last);
        while (q.executeStep()) {
          if (out.size() > 1) out.push_back(',');
          out.append(detail::as_text(q.getColumn(0)));
        }
      }
      return out + "]";
    });
  }

  void add_validation(std::int64_t run_id, const ValidationRecord& v) override {
    guarded([&] {
      SQLite::Transaction t(db_, SQLite::TransactionBehavior::IMMEDIATE);
      const RunRecord r = run(run_id);
      if (v.generation < 0 || v.generation > r.generations)
        throw std::invalid_argument("generation = " + std::to_string(v.generation) + ": run " + std::to_string(run_id) +
                                    " has stored generations 0 to " + std::to_string(r.generations));
      detail::insert_validation(db_, run_id, v);
      t.commit();
      return 0;
    });
  }

  std::vector<ValidationRecord> validations(std::int64_t run_id) override {
    return guarded([&] {
      run(run_id);
      return detail::read_validations(db_, run_id);
    });
  }

  Configuration configuration(std::int64_t run_id, std::int64_t generation) override {
    const RunRecord r = run(run_id);
    if (generation < -1 || generation > r.generations)  // a bad argument, not a damaged file
      throw std::invalid_argument("generation = " + std::to_string(generation) + ": run " + std::to_string(run_id) +
                                  " has stored generations 0 to " + std::to_string(r.generations) +
                                  " (-1: the latest)");
    return guarded([&] {
      SQLite::Transaction t(db_, SQLite::TransactionBehavior::DEFERRED);
      SQLite::Statement q(db_,
                          "SELECT generation, accepted_candidate FROM generations WHERE run_id = ? AND "
                          "accepted_candidate IS NOT NULL AND generation <= ? "
                          "ORDER BY generation DESC LIMIT 1");
      q.bind(1, run_id);
      q.bind(2, static_cast<std::int64_t>(generation < 0 ? r.generations : generation));
      if (!q.executeStep())
        throw std::runtime_error("--generation " + std::to_string(generation) + ": run " + std::to_string(run_id) +
                                 " has no configuration there");
      Configuration c;
      c.generation = detail::as_int64(q.getColumn(0));
      const int candidate = detail::as_int(q.getColumn(1));
      c.medium.width = r.width;
      c.medium.height = r.height;
      c.medium.periodic = r.periodic;

      SQLite::Statement e(db_,
                          "SELECT outcome, reason, tortuosity, steps FROM candidates "
                          "WHERE run_id = ? AND generation = ? AND candidate = ?");
      e.bind(1, run_id);
      e.bind(2, c.generation);
      e.bind(3, candidate);
      const std::string where = "run " + std::to_string(run_id) + ", generation " + std::to_string(c.generation) + ": ";
      if (!e.executeStep()) throw std::runtime_error(where + "accepted candidate missing");
      if (detail::as_text(e.getColumn(0)) != "passed")
        throw std::runtime_error(where + "accepted candidate did not pass");
      c.eval.outcome = Outcome::passed;
      c.eval.reason = detail::as_text(e.getColumn(1));
      c.eval.tortuosity = detail::as_real(e.getColumn(2));
      if (!(c.eval.tortuosity > 0) || !std::isfinite(c.eval.tortuosity))
        throw std::runtime_error(where + "stored tortuosity " + std::to_string(c.eval.tortuosity) +
                                 " is not a tortuosity");
      c.eval.steps = detail::as_int64(e.getColumn(3));

      SQLite::Statement gq(db_,
                           "SELECT grain, x, y, r, touched FROM grains WHERE run_id = ? AND generation = ? "
                           "ORDER BY grain");
      gq.bind(1, run_id);
      gq.bind(2, c.generation);
      while (gq.executeStep()) {
        const int i = detail::as_int(gq.getColumn(0));
        if (i != static_cast<int>(c.medium.grains.size()))
          throw std::runtime_error(where + "grain numbering has a hole");
        c.medium.grains.push_back(
            {detail::as_real(gq.getColumn(1)), detail::as_real(gq.getColumn(2)), detail::as_real(gq.getColumn(3))});
        if (detail::as_int(gq.getColumn(4)) != 0) c.eval.touched.push_back(i);
      }
      if (static_cast<std::int64_t>(c.medium.grains.size()) != r.grains)
        throw std::runtime_error(where + "stores " + std::to_string(c.medium.grains.size()) + " grains, the run has " +
                                 std::to_string(r.grains));
      // What is read back must be a medium the simulator accepts (an edited file might not be).
      if (std::string why; !c.medium.IsValid(&why)) throw std::runtime_error(where + why);

      SQLite::Statement pq(db_, "SELECT x, y FROM paths WHERE run_id = ? AND generation = ? ORDER BY point");
      pq.bind(1, run_id);
      pq.bind(2, c.generation);
      while (pq.executeStep()) {
        c.eval.path_x.push_back(detail::as_real(pq.getColumn(0)));
        c.eval.path_y.push_back(detail::as_real(pq.getColumn(1)));
      }
      t.commit();
      return c;
    });
  }

 private:
  // A version-2 file opened for reading is read as it is (no state column).
  int schema_version() { return db_.execAndGet("PRAGMA user_version").getInt(); }

  // Inside a transaction: generation g of `run`, which must follow the stored one, and the run's
  // row. A migration's candidate was evaluated by another island: it counts no evaluation.
  void append_in_transaction(std::int64_t run, const Generation& g, const Configuration& best) {
    SQLite::Statement last(db_, "SELECT generations FROM runs WHERE id = ?");
    last.bind(1, run);
    if (!last.executeStep()) throw std::runtime_error("run " + std::to_string(run) + ": no such run");
    const std::int64_t stored = detail::as_int64(last.getColumn(0));
    // A statement left mid-result keeps a read snapshot open past COMMIT, and that snapshot
    // stops every automatic checkpoint: the WAL file would grow without bound.
    last.reset();
    if (g.number != stored + 1)
      throw std::runtime_error("run " + std::to_string(run) + ": generation " + std::to_string(g.number) +
                               " does not follow the stored generation " + std::to_string(stored) +
                               " (is another process writing this run?)");
    write_generation(run, g);
    SQLite::Statement u(db_, std::string("UPDATE runs SET generations = ?, evaluations = evaluations + ?, "
                                         "droplets = coalesce(droplets, evaluations) + ?, "
                                         "best_t = ?, best_generation = ?, status = 'running', updated = ") +
                                 kNow + " WHERE id = ?");
    const bool migration = g.kind == MoveKind::migrate;
    detail::insert_row(u, static_cast<std::int64_t>(g.number),
                       migration ? std::int64_t{0} : static_cast<std::int64_t>(g.candidates.size()),
                       migration ? std::int64_t{0} : droplets_of(g), best.eval.tortuosity,
                       static_cast<std::int64_t>(best.generation), run);
  }

  // The droplet runs of a generation: its candidates' and the parent's re-run.
  static std::int64_t droplets_of(const Generation& g) {
    std::int64_t n = g.parent.droplets;
    for (const Candidate& c : g.candidates) n += c.eval.droplets;
    return n;
  }

  // Inside a transaction: the generation, its candidates and, if it kept one, that candidate's
  // grains (with the touched flag) and path.
  void write_generation(std::int64_t run, const Generation& g) {
    const std::int64_t rid = run, gen = g.number;
    const bool rerun = g.parent.droplets > 0;
    SQLite::Statement q(db_, std::string("INSERT INTO generations (run_id, generation, kind, accepted_candidate, "
                                         "best_t, touched, seconds, state, parent_t, parent_passed, finished) "
                                         "VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ") +
                                 kNow + ")");
    detail::insert_row(q, rid, gen, to_string(g.kind), detail::value_if(g.accepted >= 0, g.accepted), g.best_t,
                       g.touched, g.seconds, detail::value_if(!g.state.empty(), g.state),
                       detail::value_if(rerun && g.parent.passed > 0, g.parent.tortuosity),
                       detail::value_if(rerun, g.parent.passed));
    SQLite::Statement c(db_,
                        "INSERT INTO candidates (run_id, generation, candidate, moved_grain, moved, outcome, "
                        "reason, tortuosity, steps, touched, seconds, droplets, passed, kind) "
                        "VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)");
    for (const Candidate& k : g.candidates)
      detail::insert_row(c, rid, gen, k.index, detail::value_if(k.moved_grain >= 0, k.moved_grain), k.moved,
                         to_string(k.eval.outcome), k.eval.reason,
                         detail::value_if(k.eval.outcome == Outcome::passed, k.eval.tortuosity),
                         static_cast<std::int64_t>(k.eval.steps), static_cast<int>(k.eval.touched.size()),
                         k.eval.seconds, k.eval.droplets, k.eval.passed, to_string(k.kind));
    if (g.accepted < 0) return;
    const Candidate& kept = g.candidates.at(static_cast<std::size_t>(g.accepted));
    if (kept.eval.outcome != Outcome::passed) throw std::logic_error("append: the kept candidate did not pass");

    std::vector<std::uint8_t> touched(kept.medium.grains.size(), 0);
    for (const std::int32_t i : kept.eval.touched) touched.at(static_cast<std::size_t>(i)) = 1;
    SQLite::Statement gq(db_,
                         "INSERT INTO grains (run_id, generation, grain, x, y, r, touched) "
                         "VALUES (?, ?, ?, ?, ?, ?, ?)");
    for (std::size_t i = 0; i < kept.medium.grains.size(); ++i) {
      const Grain& gr = kept.medium.grains[i];
      detail::insert_row(gq, rid, gen, static_cast<std::int64_t>(i), gr.x, gr.y, gr.r, static_cast<int>(touched[i]));
    }
    SQLite::Statement pq(db_, "INSERT INTO paths (run_id, generation, point, x, y) VALUES (?, ?, ?, ?, ?)");
    for (std::size_t i = 0; i < kept.eval.path_x.size(); ++i)
      detail::insert_row(pq, rid, gen, static_cast<std::int64_t>(i), kept.eval.path_x[i], kept.eval.path_y[i]);
  }
};

}  // namespace

std::unique_ptr<History> open_history(const std::string& path, OpenMode mode) {
  return std::make_unique<SqliteHistory>(path, mode);
}

}  // namespace softdrop
