// The runs, generations and candidates tables' rows read back (generation_rows.hpp).
#include "generation_rows.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "sqlite_file.hpp"

namespace softdrop::detail {

std::string select_runs(int version) {
  return std::string(
             "SELECT id, created, updated, version, status, params, seed, lambda, grains, width, height, "
             "periodic, generations, evaluations, best_t, best_generation, ") +
         (version >= 5 ? "island, archipelago" : "NULL, NULL") +
         (version >= 7 ? ", coalesce(droplets, evaluations)" : ", evaluations") + " FROM runs";
}

RunRecord read_run(SQLite::Statement& q) {
  RunRecord r;
  read_row_head(q, &r);
  r.seed = static_cast<std::uint64_t>(as_int64(q.getColumn(6)));
  r.lambda = as_int(q.getColumn(7));
  r.grains = as_int64(q.getColumn(8));
  r.width = as_real(q.getColumn(9));
  r.height = as_real(q.getColumn(10));
  r.periodic = as_int(q.getColumn(11)) != 0;
  r.generations = as_int64(q.getColumn(12));
  r.evaluations = as_int64(q.getColumn(13));
  r.best_t = as_real(q.getColumn(14));
  r.best_generation = as_int64(q.getColumn(15));
  if (!q.getColumn(16).isNull()) r.island = as_int(q.getColumn(16));
  if (!q.getColumn(17).isNull()) r.archipelago = as_int64(q.getColumn(17));
  r.droplets = as_int64(q.getColumn(18));
  const auto bad = [&](const char* column, const std::string& value) {
    throw std::runtime_error("run " + std::to_string(r.id) + ": column " + column + " holds " + value +
                             " (damaged or edited file?)");
  };
  if (r.generations < 0) bad("generations", std::to_string(r.generations));
  if (r.evaluations < 0) bad("evaluations", std::to_string(r.evaluations));
  if (r.droplets < r.evaluations) bad("droplets", std::to_string(r.droplets) + ", fewer than its evaluations");
  if (r.best_generation < 0 || r.best_generation > r.generations)
    bad("best_generation",
        std::to_string(r.best_generation) + ", outside the run's generations 0 to " + std::to_string(r.generations));
  if (r.lambda < 1) bad("lambda", std::to_string(r.lambda));
  if (r.grains < 0) bad("grains", std::to_string(r.grains));
  if (!(r.width > 0) || !(r.height > 0) || !std::isfinite(r.width) || !std::isfinite(r.height))
    bad("width or height", std::to_string(r.width) + " x " + std::to_string(r.height));
  if (!std::isfinite(r.best_t) || r.best_t < 0) bad("best_t", std::to_string(r.best_t));
  return r;
}

std::vector<GenerationRecord> read_generations(SQLite::Database& db, std::int64_t run_id, int version) {
  std::vector<GenerationRecord> out;
  SQLite::Statement q(db, std::string("SELECT generation, kind, accepted_candidate, best_t, touched, seconds, "
                                      "finished, ") +
                              (version >= 3 ? "state" : "NULL") +
                              (version >= 7 ? ", parent_t, parent_passed" : ", NULL, NULL") +
                              " FROM generations WHERE run_id = ? ORDER BY generation");
  q.bind(1, run_id);
  while (q.executeStep()) {
    GenerationRecord g;
    g.generation = as_int64(q.getColumn(0));
    g.kind = as_text(q.getColumn(1));
    g.accepted = q.getColumn(2).isNull() ? -1 : as_int(q.getColumn(2));
    g.best_t = as_real(q.getColumn(3));
    g.touched = as_int(q.getColumn(4));
    g.seconds = as_real(q.getColumn(5));
    g.finished = as_text(q.getColumn(6));
    g.state = q.getColumn(7).isNull() ? "" : as_text(q.getColumn(7));
    if (!q.getColumn(8).isNull()) g.parent_t = as_real(q.getColumn(8));
    if (!q.getColumn(9).isNull()) g.parent_passed = as_int(q.getColumn(9));
    if (g.generation != static_cast<std::int64_t>(out.size()))
      throw std::runtime_error("run " + std::to_string(run_id) + ": generation " + std::to_string(out.size()) +
                               " is missing (damaged or edited file?)");
    out.push_back(std::move(g));
  }
  SQLite::Statement c(db, std::string("SELECT generation, candidate, moved_grain, moved, outcome, reason, "
                                      "tortuosity, steps, touched, seconds, ") +
                              (version >= 7 ? "droplets, passed" : "NULL, NULL") +
                              (version >= 8 ? ", kind" : ", NULL") +
                              " FROM candidates WHERE run_id = ? ORDER BY generation, candidate");
  c.bind(1, run_id);
  std::size_t k = 0;
  while (c.executeStep()) {
    const std::int64_t gen = as_int64(c.getColumn(0));
    while (k < out.size() && out[k].generation < gen) ++k;
    if (k == out.size() || out[k].generation != gen)
      throw std::runtime_error("candidate of missing generation " + std::to_string(gen));
    CandidateRecord r;
    r.index = as_int(c.getColumn(1));
    r.moved_grain = c.getColumn(2).isNull() ? -1 : as_int(c.getColumn(2));
    r.moved = as_int(c.getColumn(3));
    r.outcome = as_text(c.getColumn(4));
    r.reason = as_text(c.getColumn(5));
    r.tortuosity = c.getColumn(6).isNull() ? 0.0 : as_real(c.getColumn(6));
    r.steps = as_int64(c.getColumn(7));
    r.touched = as_int(c.getColumn(8));
    r.seconds = as_real(c.getColumn(9));
    r.droplets = c.getColumn(10).isNull() ? 1 : as_int(c.getColumn(10));
    r.passed = c.getColumn(11).isNull() ? (r.outcome == "passed" ? 1 : 0) : as_int(c.getColumn(11));
    // Before version 8 the generation's kind tells a candidate's move, except in an 'all'
    // generation of es, whose candidates with a moved grain moved one grain (single or relocate).
    const std::string& gk = out[k].kind;
    r.kind = !c.getColumn(12).isNull()      ? as_text(c.getColumn(12))
             : gk != "all" && gk != "mixed" ? gk
             : r.moved_grain < 0            ? std::string("all")
                                            : std::string();
    out[k].candidates.push_back(std::move(r));
  }
  for (const GenerationRecord& g : out)
    if (g.candidates.empty())
      throw std::runtime_error("run " + std::to_string(run_id) + ": generation " + std::to_string(g.generation) +
                               " has no candidates (damaged or edited file?)");
  return out;
}

}  // namespace softdrop::detail
