#include "softdrop/search_params.hpp"

#include <nlohmann/json.hpp>
#include <stdexcept>
#include <type_traits>

namespace softdrop {
namespace {

// The one list of stored options: key (= CLI long option name) and field.
template <class Options, class F>
void visit(Options& o, F&& f) {
  f("seed", o.seed);
  f("lambda", o.lambda);
  f("single-every", o.single_every);
  f("step", o.step);
  f("single-step", o.single_step);
  f("max-redraws", o.max_redraws);
  f("gap", o.gap);
  f("masses", o.droplet.masses);
  f("mass", o.droplet.mass);
  f("radius", o.droplet.radius);
  f("nrt", o.droplet.nrt);
  f("ks", o.droplet.ks);
  f("kd", o.droplet.kd);
  f("kc", o.droplet.kc);
  f("cc", o.droplet.cc);
  f("gravity", o.droplet.gravity);
  f("dt", o.droplet.dt);
  f("max-strain", o.droplet.max_strain);
  f("constraint-iterations", o.droplet.constraint_iterations);
  f("max-depth", o.droplet.max_depth);
  f("viscosity", o.droplet.viscosity);
  f("max-steps", o.run.max_steps);
  f("stuck-window", o.run.stuck_window);
  f("stuck-distance", o.run.stuck_distance);
  f("check-interval", o.run.check_interval);
  f("path-interval", o.run.path_interval);
}

}  // namespace

std::string search_params_to_json(const SearchOptions& options) {
  nlohmann::json j = nlohmann::json::object();
  visit(options, [&](const char* key, const auto& value) { j[key] = value; });
  return j.dump();
}

SearchOptions search_params_from_json(const std::string& text) {
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(std::string("stored parameters: not JSON (") + e.what() + ")");
  }
  if (!j.is_object()) throw std::runtime_error("stored parameters: not a JSON object");
  SearchOptions o;
  visit(o, [&](const char* key, auto& value) {
    using T = std::decay_t<decltype(value)>;
    if (!j.contains(key)) throw std::runtime_error(std::string("stored parameters: '") + key + "' missing");
    const auto& v = j.at(key);
    const bool ok = std::is_integral_v<T> ? (v.is_number_integer() || v.is_number_unsigned()) : v.is_number();
    if (!ok) throw std::runtime_error(std::string("stored parameters: '") + key + "' has the wrong type");
    value = v.template get<T>();
  });
  return o;
}

std::vector<std::string> search_param_keys() {
  std::vector<std::string> keys;
  SearchOptions o;
  visit(o, [&](const char* key, const auto&) { keys.emplace_back(key); });
  return keys;
}

}  // namespace softdrop
