// A search's and a sweep's options as named values (run_values.hpp).
#include "service/run_values.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>

#include "store/params_json.hpp"

namespace softdrop {

SearchRun default_search_run() {
  SearchRun run;
  // The default search scene: the default 500 x 500 periodic box with 20 non-overlapping grains of
  // the default radii (phi ~ 0.72).
  run.start.medium.kind = MediumKind::non_overlapping;
  run.start.medium.grains = 20;
  // The measured best of the strategies (results/search/README.md): the evolution strategy with a
  // relocation every third generation and a generation of 8, enough candidates for every thread
  // and lane. SearchOptions{} itself stays the paper's algorithm, and a stored run without these
  // keys reads as that.
  run.search.strategy.kind = StrategyKind::es;
  run.search.relocate_every = 3;
  run.search.lambda = 8;
  // The paper's objective, one droplet from the middle of the top, tunes that one chaotic path
  // (results/search/README.md): the default scores a medium by the mean T of droplets from fresh
  // starts, compared on common starts.
  run.search.objective.kind = ObjectiveKind::mean;
  return run;
}

namespace {
// The reader of stored parameters (params_json.hpp) names its source "stored parameters"; these
// values are the caller's own, not yet stored, so the refusal names only the value.
std::invalid_argument given_values_error(const std::runtime_error& e) {
  constexpr std::string_view stored = "stored parameters: ";
  std::string what = e.what();
  if (what.starts_with(stored)) what.erase(0, stored.size());
  return std::invalid_argument(what);
}

// The start's stored keys that are plain fields of MediumOptions, in one list for the writer
// (search_run_params) and the reader (set_search_run_values): f(key, field) for each.
template <class Medium, class F>
void each_medium_field(Medium& m, const F& f) {
  f("grains", m.grains);
  f("width", m.width);
  f("height", m.height);
  f("r-min", m.r_min);
  f("r-max", m.r_max);
  f("r-median", m.r_median);
  f("r-sigma", m.r_sigma);
  f("medium-seed", m.seed);
}
// The islands' stored keys that are plain fields of SearchRun, the same way.
template <class Run, class F>
void each_island_field(Run& run, const F& f) {
  f("islands", run.islands);
  f("migrate-every", run.migrate_every);
  f("migration", run.migration);
}
// The writer's f and the reader's: the field's value as the key's, and the key's as the field's.
auto write_to(nlohmann::json& j) {
  return [&j](const char* key, const auto& field) { j[key] = field; };
}
auto read_from(const nlohmann::json& j) {
  return [&j](const char* key, auto& field) { field = j.at(key).get<std::remove_reference_t<decltype(field)>>(); };
}
}  // namespace

nlohmann::json search_run_params(const SearchOptions& search, const SearchStart& start) {
  nlohmann::json j = nlohmann::json::parse(search_params_to_json(search));
  j["medium"] = start.file;
  each_medium_field(start.medium, write_to(j));
  j["radius-distribution"] = to_string(start.medium.radii);
  j["walls"] = !start.medium.periodic;
  return j;
}

const char* island_starts_name(bool own) { return own ? "own" : "shared"; }

void set_island_params(const SearchRun& run, nlohmann::json* params) {
  each_island_field(run, write_to(*params));
  (*params)["island-starts"] = island_starts_name(run.own_island_starts);
}

nlohmann::json search_run_values(const SearchRun& run) {
  nlohmann::json j = search_run_params(run.search, run.start);
  set_island_params(run, &j);
  return j;
}

const std::vector<std::string>& search_medium_keys() {
  static const std::vector<std::string> keys = [] {
    const std::vector<std::string> search = search_param_keys();
    const nlohmann::json all = search_run_params(SearchOptions{}, SearchStart{});
    std::vector<std::string> medium;
    for (const auto& [key, value] : all.items())
      if (key != "medium" && std::find(search.begin(), search.end(), key) == search.end()) medium.push_back(key);
    return medium;
  }();
  return keys;
}

void set_search_run_values(const nlohmann::json& values, SearchRun* run) {
  try {
    run->search = search_params_from_json(values.dump());
    MediumOptions& m = run->start.medium;
    run->start.file = values.at("medium").get<std::string>();
    each_medium_field(m, read_from(values));
    m.radii = parse_radius_distribution(values.at("radius-distribution").get<std::string>());
    m.periodic = !values.at("walls").get<bool>();
    m.gap = run->search.gap;  // the generator's spacing rule is the moves'
    each_island_field(*run, read_from(values));
    const std::string starts = values.at("island-starts").get<std::string>();
    if (starts != island_starts_name(false) && starts != island_starts_name(true))
      throw std::invalid_argument("island-starts = '" + starts + "': must be " + island_starts_name(false) + " or " +
                                  island_starts_name(true));
    run->own_island_starts = starts == island_starts_name(true);
  } catch (const nlohmann::json::exception& e) {
    throw std::invalid_argument(std::string("a search's values: ") + e.what());
  } catch (const std::runtime_error& e) {  // search_params_from_json naming a mistyped key
    throw given_values_error(e);
  }
}

std::vector<std::string> apply_search_preset(const std::string& name, const std::vector<std::string>& given,
                                             SearchOptions* search) {
  if (name.empty()) return {};
  if (name != "paper") throw std::invalid_argument("preset = '" + name + "': must be paper");
  std::vector<std::string> set;
  const auto fill = [&](const char* key, auto apply) {
    if (std::find(given.begin(), given.end(), key) != given.end()) return;
    apply();
    set.emplace_back(key);
  };
  fill("strategy", [&] { search->strategy.kind = StrategyKind::paper; });
  fill("lambda", [&] { search->lambda = 1; });
  fill("relocate-every", [&] { search->relocate_every = 0; });
  fill("objective", [&] { search->objective.kind = ObjectiveKind::single; });
  return set;
}

bool given_options_used(const SearchOptions& search, const std::vector<std::string>& given, std::string* why) {
  const auto named = [&](const char* key) { return std::find(given.begin(), given.end(), key) != given.end(); };
  static const std::pair<const char*, StrategyKind> of_strategy[] = {{"target-success", StrategyKind::es},
                                                                     {"history-length", StrategyKind::lahc},
                                                                     {"temperature", StrategyKind::anneal},
                                                                     {"half-life", StrategyKind::anneal},
                                                                     {"sigma", StrategyKind::cmaes}};
  for (const auto& [key, kind] : of_strategy)
    if (named(key) && kind != search.strategy.kind) {
      if (why)
        *why = std::string(key) + ": an option of --strategy " + to_string(kind) + ", not used by --strategy " +
               to_string(search.strategy.kind);
      return false;
    }
  using K = ObjectiveKind;
  static const std::pair<const char*, std::vector<K>> of_objective[] = {
      {"starts", {K::mean, K::quantile, K::lower_bound}},
      {"quantile", {K::quantile}},
      {"se-factor", {K::lower_bound}},
      {"margin", {K::mean, K::quantile, K::lower_bound}}};
  for (const auto& [key, kinds] : of_objective)
    if (named(key) && std::find(kinds.begin(), kinds.end(), search.objective.kind) == kinds.end()) {
      if (why) *why = std::string(key) + ": not an option of --objective " + to_string(search.objective.kind);
      return false;
    }
  return true;
}

SweepOptions default_sweep() {
  SweepOptions sweep;
  sweep.medium.kind = MediumKind::overlapping;
  return sweep;
}

nlohmann::json sweep_values(const SweepOptions& sweep) {
  nlohmann::json j = nlohmann::json::parse(sweep_params_to_json(sweep));
  if (!sweep.second) {
    const SecondDroplet none;
    j["second-droplet"] = "";
    j["second-after"] = none.after;
    j["second-offset-x"] = none.offset_x;
  }
  return j;
}

SweepOptions sweep_of_values(const nlohmann::json& values, const std::vector<std::string>& given) {
  nlohmann::json j = values;
  if (j.at("second-droplet") == "") {
    for (const char* key : {"second-after", "second-offset-x"})
      if (std::find(given.begin(), given.end(), key) != given.end())
        throw std::invalid_argument(std::string(key) + ": has no effect without --second-droplet");
    j.erase("second-droplet"), j.erase("second-after"), j.erase("second-offset-x");
  }
  try {
    return sweep_params_from_json(j.dump());
  } catch (const std::runtime_error& e) {  // naming a mistyped key
    throw given_values_error(e);
  }
}

void apply_sweep_preset(const std::string& name, const std::vector<std::string>& given, SweepOptions* sweep) {
  if (name.empty()) return;
  if (name != "quick" && name != "paper")
    throw std::invalid_argument("preset = '" + name + "': must be quick or paper");
  const auto unset = [&](const char* key) { return std::find(given.begin(), given.end(), key) == given.end(); };
  const bool quick = name == "quick";
  if (unset("porosities"))
    sweep->porosities = quick ? std::vector<double>{0.7, 0.8, 0.9}
                              : std::vector<double>{0.45, 0.5, 0.55, 0.6, 0.65, 0.7, 0.75, 0.8, 0.85, 0.9};
  if (unset("media")) sweep->media = quick ? 2 : 200;
  if (unset("droplets")) sweep->droplets = quick ? 8 : 200;
}

}  // namespace softdrop
