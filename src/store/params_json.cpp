#include "params_json.hpp"

#include <nlohmann/json.hpp>
#include <stdexcept>
#include <type_traits>

namespace softdrop {

namespace {

// Keys added after files already existed. A missing one reads as what older builds did: the
// default for the constraint order, the explicit viscosity step, the viscosity's share on dilation
// (1), the strategy (paper) and its options, no rest test (0) for the rest test's keys, a sweep's
// media from the calibration stream (the only one there was), and no shaking (the defaults of the
// vibration's keys).
bool optional_key(const std::string& key) {
  return key == "constraint-order" || key == "rest-window" || key == "rest-distance" || key == "strategy" ||
         key == "target-success" || key == "history-length" || key == "temperature" || key == "half-life" ||
         key == "sigma" || key == "relocate-every" || key == "viscosity-dilation" || key == "viscosity-step" ||
         key == "objective" || key == "starts" || key == "quantile" || key == "se-factor" || key == "margin" ||
         key == "media-stream" || key.rfind("vibration-", 0) == 0;
}
// The stored enums go through the same names as the command line (their to_string and parse), so
// an unknown stored name is refused in the parse's words instead of read as the first value.
template <class DropletEnum>  // the droplet's enums (constraint order, viscosity step)
void parse_stored(const std::string& name, DropletEnum* value) {
  parse_name(name, value);
}
void parse_stored(const std::string& name, StrategyKind* kind) { *kind = parse_strategy(name); }
void parse_stored(const std::string& name, ObjectiveKind* kind) { *kind = parse_objective(name); }
void parse_stored(const std::string& name, MediaStream* stream) { *stream = parse_media_stream(name); }

template <class T>
void set_legacy(const std::string& key, T& value) {
  if constexpr (std::is_arithmetic_v<T>) {
    if (key == "rest-window" || key == "rest-distance") value = 0;
    if (key == "viscosity-dilation") value = 1;  // (the default is 0 now)
  }
  if constexpr (std::is_same_v<T, ViscosityStep>) value = ViscosityStep::explicit_euler;
  if constexpr (std::is_same_v<T, MediaStream>) value = MediaStream::calibration;
}

// The lists of stored options: key (= CLI long option name) and field. They are alike in shape
// because each is a list; a key is written once, here, and every read and write of it goes through
// the list.
template <class Droplet, class F>
void visit_droplet(Droplet& d, F&& f) {
  visit_droplet_fields([&](const DropletField& field, auto& value) { f(field.key, value); }, d);
}
template <class Run, class F>
void visit_exit(Run& r, F&& f) {
  f("max-steps", r.max_steps);
  f("stuck-window", r.stuck_window);
  f("stuck-distance", r.stuck_distance);
  f("rest-window", r.rest_window);
  f("rest-distance", r.rest_distance);
  f("check-interval", r.check_interval);
}

template <class Options, class F>
void visit_search(Options& o, F&& f) {
  f("seed", o.seed);
  f("lambda", o.lambda);
  f("single-every", o.single_every);
  f("step", o.step);
  f("single-step", o.single_step);
  f("relocate-every", o.relocate_every);
  f("max-redraws", o.max_redraws);
  f("gap", o.gap);
  f("strategy", o.strategy.kind);
  f("target-success", o.strategy.target_success);
  f("history-length", o.strategy.history_length);
  f("temperature", o.strategy.temperature);
  f("half-life", o.strategy.half_life);
  f("sigma", o.strategy.sigma);
  f("objective", o.objective.kind);
  f("starts", o.objective.starts);
  f("quantile", o.objective.quantile);
  f("se-factor", o.objective.se_factor);
  f("margin", o.objective.margin);
  visit_droplet(o.droplet, f);
  visit_exit(o.run, f);
  f("path-interval", o.run.path_interval);
}

// Sweep options; the medium kind, radius distribution and walls go through their CLI spelling.
struct SweepFields {
  SweepOptions o;
  std::string kind, radii;
  bool walls = false;
};

template <class F>
void visit_sweep(SweepFields& s, F&& f) {
  f("porosities", s.o.porosities);
  f("media", s.o.media);
  f("droplets", s.o.droplets);
  f("seed", s.o.seed);
  f("media-stream", s.o.stream);
  f("kind", s.kind);
  f("width", s.o.medium.width);
  f("height", s.o.medium.height);
  f("walls", s.walls);
  f("r-min", s.o.medium.r_min);
  f("r-max", s.o.medium.r_max);
  f("radius-distribution", s.radii);
  f("r-median", s.o.medium.r_median);
  f("r-sigma", s.o.medium.r_sigma);
  f("gap", s.o.medium.gap);
  f("max-failed-attempts", s.o.medium.max_failed_attempts);
  visit_droplet(s.o.droplet, f);
  visit_exit(s.o.run, f);
}

nlohmann::json parse_object(const std::string& text) {
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(std::string("stored parameters: not JSON (") + e.what() + ")");
  }
  if (!j.is_object()) throw std::runtime_error("stored parameters: not a JSON object");
  return j;
}

// Reads `key` of `j` into `value`, refusing a missing key or a value of the wrong JSON type.
struct Reader {
  const nlohmann::json& j;
  template <class T>
  void operator()(const char* key, T& value) const {
    if (!j.contains(key)) {
      if (optional_key(key)) return set_legacy(key, value);
      throw std::runtime_error(std::string("stored parameters: '") + key + "' missing");
    }
    const auto& v = j.at(key);
    bool ok;
    if constexpr (std::is_same_v<T, bool>)
      ok = v.is_boolean();
    else if constexpr (std::is_same_v<T, std::string> || std::is_enum_v<T>)
      ok = v.is_string();
    else if constexpr (std::is_same_v<T, std::vector<double>>)
      ok = v.is_array();
    else if constexpr (std::is_integral_v<T>)
      ok = v.is_number_integer() || v.is_number_unsigned();
    else
      ok = v.is_number();
    if (ok) {
      try {
        if constexpr (std::is_enum_v<T>)
          parse_stored(v.template get<std::string>(), &value);
        else
          value = v.template get<T>();
        return;
      } catch (const nlohmann::json::exception&) {
      } catch (const std::invalid_argument& e) {
        throw std::runtime_error(std::string("stored parameters: ") + e.what());
      }
    }
    throw std::runtime_error(std::string("stored parameters: '") + key + "' has the wrong type");
  }
};

// Fields as flat JSON and back, keyed as visit(fields, f) names them.
template <class Fields, class Visit>
std::string fields_to_json(Fields& fields, Visit visit) {
  nlohmann::json j = nlohmann::json::object();
  visit(fields, [&](const char* key, const auto& value) {
    if constexpr (std::is_enum_v<std::decay_t<decltype(value)>>)
      j[key] = to_string(value);
    else
      j[key] = value;
  });
  return j.dump();
}
template <class Fields, class Visit>
Fields fields_from_json(const std::string& text, Visit visit) {
  const nlohmann::json j = parse_object(text);
  Fields fields;
  visit(fields, Reader{j});
  return fields;
}

}  // namespace

std::string search_params_to_json(const SearchOptions& options) {
  return fields_to_json(options, [](auto& o, auto&& f) { visit_search(o, f); });
}

SearchOptions search_params_from_json(const std::string& text) {
  return fields_from_json<SearchOptions>(text, [](auto& o, auto&& f) { visit_search(o, f); });
}

std::vector<std::string> search_param_keys() {
  std::vector<std::string> keys;
  SearchOptions o;
  visit_search(o, [&](const char* key, const auto&) { keys.emplace_back(key); });
  return keys;
}

std::vector<std::string> simulation_param_keys() {
  std::vector<std::string> keys;
  DropletParams d;
  visit_droplet(d, [&](const char* key, const auto&) { keys.emplace_back(key); });
  RunOptions r;
  visit_exit(r, [&](const char* key, const auto&) {
    if (std::string(key) != "check-interval") keys.emplace_back(key);  // not an option of simulate
  });
  return keys;
}

// A sweep of pairs adds the second droplet's keys; a sweep of one droplet has none, so its stored
// text (by which a sweep is found again) is what it was before pairs existed.
std::string sweep_params_to_json(const SweepOptions& options) {
  SweepFields s{options, to_string(options.medium.kind), to_string(options.medium.radii), !options.medium.periodic};
  const std::string flat = fields_to_json(s, [](auto& f, auto&& g) { visit_sweep(f, g); });
  if (!options.second) return flat;
  nlohmann::json j = nlohmann::json::parse(flat);
  j["second-droplet"] = to_string(options.second->release);
  j["second-after"] = options.second->after;
  j["second-offset-x"] = options.second->offset_x;
  return j.dump();
}

SweepOptions sweep_params_from_json(const std::string& text) {
  SweepFields s = fields_from_json<SweepFields>(text, [](auto& f, auto&& g) { visit_sweep(f, g); });
  s.o.medium.kind = parse_medium_kind(s.kind);
  s.o.medium.radii = parse_radius_distribution(s.radii);
  s.o.medium.periodic = !s.walls;
  const nlohmann::json j = parse_object(text);
  if (j.contains("second-droplet")) {
    SecondDroplet second;
    std::string release;
    const Reader read{j};
    read("second-droplet", release);
    read("second-after", second.after);
    read("second-offset-x", second.offset_x);
    try {
      second.release = parse_second_release(release);
    } catch (const std::invalid_argument& e) {
      throw std::runtime_error(std::string("stored parameters: ") + e.what());
    }
    s.o.second = second;
  }
  return s.o;
}

}  // namespace softdrop
