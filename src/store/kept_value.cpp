// What a search says of an arrangement it kept: its in-search value read off the stored
// generations, and the held-out value stored for it.
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

#include "softdrop/store.hpp"

namespace softdrop {

KeptValue kept_value(const std::vector<GenerationRecord>& generations, std::int64_t kept) {
  // Generations are numbered 0, 1, 2, ... (History::generations checks it), so g is at index g.
  if (kept < 0 || kept >= static_cast<std::int64_t>(generations.size()))
    throw std::invalid_argument("generation " + std::to_string(kept) + ": not stored");
  auto end = static_cast<std::size_t>(kept);
  while (end + 1 < generations.size() && generations[end + 1].accepted < 0) ++end;
  return {generations[end].best_t, static_cast<std::int64_t>(end) - kept};
}

std::vector<BestPoint> best_curve(const std::vector<GenerationRecord>& generations, bool robust) {
  std::vector<BestPoint> curve;
  double best = 0;
  for (const GenerationRecord& g : generations)
    if (robust && (g.generation == 0 || g.accepted >= 0)) {
      const KeptValue kept = kept_value(generations, g.generation);
      curve.push_back({g.generation, kept.value, kept.re_runs});
    } else if (!robust && (g.generation == 0 || g.best_t > best)) {  // the generations that raised the best
      best = g.best_t;
      curve.push_back({g.generation, g.best_t, 0});
    }
  return curve;
}

std::optional<ValidationRecord> held_out_of(const std::vector<ValidationRecord>& validations, std::int64_t generation) {
  std::optional<ValidationRecord> last;
  // ISO 8601 times order as strings; a tie keeps the later row.
  for (const ValidationRecord& v : validations)
    if (v.generation == generation &&
        (!last || v.starts > last->starts || (v.starts == last->starts && v.created >= last->created)))
      last = v;
  return last;
}

namespace {

// The stored run's objective (runs from before the objectives are single) and its parameters.
nlohmann::json params_of(const RunRecord& run) {
  auto params = nlohmann::json::parse(run.params, nullptr, false);
  if (!params.is_object())
    throw std::runtime_error("run " + std::to_string(run.id) + ": its stored parameters are not a JSON object");
  return params;
}

}  // namespace

ArrangementValues arrangement_values(const RunRecord& run, const std::vector<GenerationRecord>& generations,
                                     const std::vector<ValidationRecord>& validations, const Configuration& kept) {
  const nlohmann::json params = params_of(run);
  ArrangementValues v;
  v.objective = params.value("objective", "single");
  v.held_out = held_out_of(validations, kept.generation);
  if (!v.robust()) {
    v.in_search = kept.eval.tortuosity;
    return v;
  }
  v.starts = params.value("starts", 1);
  const KeptValue k = kept_value(generations, kept.generation);
  v.in_search = k.value, v.re_runs = k.re_runs;
  return v;
}

ArrangementValues arrangement_values(History& history, std::int64_t run, const Configuration& kept) {
  const RunRecord r = history.run(run);
  const bool robust = params_of(r).value("objective", "single") != "single";
  return arrangement_values(r, robust ? history.generations(run) : std::vector<GenerationRecord>{},
                            history.validations(run), kept);
}

BestCurve best_rows(History& history, std::int64_t run) {
  return best_rows(history.run(run), history.generations(run), history.validations(run));
}

BestCurve best_rows(const RunRecord& run, const std::vector<GenerationRecord>& generations,
                    const std::vector<ValidationRecord>& validations) {
  BestCurve curve;
  curve.robust = params_of(run).value("objective", "single") != "single";
  for (const BestPoint& p : best_curve(generations, curve.robust)) {
    const GenerationRecord& g = generations[static_cast<std::size_t>(p.generation)];
    curve.rows.push_back({p, g.kind, g.touched, held_out_of(validations, p.generation)});
  }
  return curve;
}

}  // namespace softdrop
