// What one search and islands share (search_start.hpp).
#include "service/search_start.hpp"

#include <algorithm>
#include <stdexcept>

#include "optimizer/strategy.hpp"
#include "softdrop/batch.hpp"
#include "softdrop/medium.hpp"
#include "store/params_json.hpp"
#include "util/random.hpp"
#include "util/validation.hpp"

namespace softdrop {

using detail::num;

Generation starting_generation(const SearchStart& start, const SearchOptions& search, Configuration* best,
                               const std::function<void(int, const std::string&)>& refused) {
  if (!start.file.empty()) {
    if (is_image_file(start.file))
      throw std::invalid_argument("medium: " + start.file +
                                  " is an image; a search moves grains, so it starts from a grain file (.json, .csv)");
    return initial_generation(load_medium(start.file), search, best);
  }
  std::string last_reason;
  for (int attempt = 0; attempt < start.attempts; ++attempt) {
    MediumOptions m = start.medium;
    if (attempt > 0) m.seed = derive_seed(start.medium.seed, static_cast<std::uint64_t>(attempt));
    const Medium medium = generate_medium(m);
    try {
      return initial_generation(medium, search, best);
    } catch (const std::runtime_error& e) {  // the droplet did not pass: try another medium
      last_reason = e.what();
      if (refused) refused(attempt + 1, last_reason);
    }
  }
  throw std::runtime_error("start-attempts = " + std::to_string(start.attempts) +
                           ": no starting medium let the droplet pass (" + last_reason + ")");
}

Search resumed_search(History& history, const RunRecord& rec, const SearchOptions& options) {
  // The strategy moves on from the last kept arrangement; the best may be an earlier one (with a
  // robust objective it is that arrangement, with the mean of its re-runs stored as the run's best).
  Configuration current = history.configuration(rec.id, -1);
  const bool robust = options.objective.robust();
  // Both must come out the same with this build (on the starts they were kept on), or the history
  // would fork. The best is checked apart only when it is another arrangement.
  const auto check = [&](Configuration& c) {
    const Evaluation again = evaluate(c.medium, options, c.generation);
    if (again.outcome != Outcome::passed || again.tortuosity != c.eval.tortuosity || again.touched != c.eval.touched)
      throw std::runtime_error("resume " + std::to_string(rec.id) + ": this build gives T = " + num(again.tortuosity) +
                               " for the stored arrangement of generation " + std::to_string(c.generation) +
                               ", the run stored " + num(c.eval.tortuosity) +
                               " (built with other numerics? resuming would not continue the same history)");
    c.eval = again;
  };
  check(current);
  Configuration best = current;
  if (!robust && rec.best_generation != current.generation) {
    best = history.configuration(rec.id, rec.best_generation);
    check(best);
  }
  if (robust) {
    if (rec.best_generation != current.generation)
      throw std::runtime_error("resume " + std::to_string(rec.id) + ": the stored best (generation " +
                               std::to_string(rec.best_generation) + ") is not the last kept arrangement (generation " +
                               std::to_string(current.generation) + "), as the " + to_string(options.objective.kind) +
                               " objective keeps it");
    best.eval.tortuosity = rec.best_t;
  }
  return Search(options, std::move(best), std::move(current),
                resumes_by_replay(options.strategy.kind) ? history.strategy_states(rec.id, rec.generations)
                                                         : history.strategy_state(rec.id, rec.generations),
                rec.generations);
}

nlohmann::json stored_params(const RunRecord& run, const SearchOptions& options) {
  nlohmann::json stored = nlohmann::json::parse(run.params);
  const nlohmann::json read_back = nlohmann::json::parse(search_params_to_json(options));
  for (const auto& [key, value] : read_back.items())
    if (!stored.contains(key)) stored[key] = value;
  return stored;
}

std::optional<std::int64_t> stored_target(const nlohmann::json& stored, const std::string& db, std::int64_t run) {
  if (!stored.contains("target-generations")) return std::nullopt;
  const nlohmann::json& t = stored.at("target-generations");
  if (!t.is_number_integer() || t.get<std::int64_t>() < 0 || t.get<std::int64_t>() > 1'000'000'000)
    throw std::runtime_error("--db '" + db + "': run " + std::to_string(run) + ": its stored target-generations " +
                             t.dump() + " is not a whole number in [0, 1e9]");
  return t.get<std::int64_t>();
}

std::string contradictions(const nlohmann::json& wanted, const nlohmann::json& stored,
                           const std::vector<std::string>& given) {
  std::string out;
  for (const auto& [key, value] : wanted.items()) {
    if (std::find(given.begin(), given.end(), key) == given.end()) continue;
    if (stored.contains(key) && stored.at(key) == value) continue;
    out += (out.empty() ? "" : ", ") + std::string("--") + key + " " + value.dump() + " (stored " +
           (stored.contains(key) ? stored.at(key).dump() : std::string("nothing")) + ")";
  }
  return out;
}

ValidationRecord validate_kept(History& history, std::int64_t run, const SearchOptions& search,
                               const Configuration& best, int starts, int threads,
                               const std::function<void(int, int)>& progress, double* objective) {
  HeldOutOptions o;
  o.starts = starts;
  o.threads = threads;
  RunOptions runs = search.run;
  runs.path_interval = 0;
  const HeldOutValue v = held_out_value(search.droplet, best.medium, runs, o, progress);
  const ValidationRecord r = validation_record(best.generation, o, v);
  history.add_validation(run, r);
  // A robust objective over the held-out starts: the counterpart of the best's in-search value.
  if (objective && search.objective.robust()) *objective = objective_value(search.objective, v.at_dt.runs);
  return r;
}

}  // namespace softdrop
