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

std::optional<ValidationRecord> held_out_of(const std::vector<ValidationRecord>& validations, std::int64_t generation) {
  std::optional<ValidationRecord> last;
  // ISO 8601 times order as strings; a tie keeps the later row.
  for (const ValidationRecord& v : validations)
    if (v.generation == generation &&
        (!last || v.starts > last->starts || (v.starts == last->starts && v.created >= last->created)))
      last = v;
  return last;
}

ArrangementValues arrangement_values(History& history, std::int64_t run, const Configuration& kept) {
  const auto params = nlohmann::json::parse(history.run(run).params, nullptr, false);
  if (!params.is_object())
    throw std::runtime_error("run " + std::to_string(run) + ": its stored parameters are not a JSON object");
  ArrangementValues v;
  v.objective = params.value("objective", "single");  // runs from before the objectives are single
  v.held_out = held_out_of(history.validations(run), kept.generation);
  if (!v.robust()) {
    v.in_search = kept.eval.tortuosity;
    return v;
  }
  v.starts = params.value("starts", 1);
  const KeptValue k = kept_value(history.generations(run), kept.generation);
  v.in_search = k.value, v.re_runs = k.re_runs;
  return v;
}

}  // namespace softdrop
