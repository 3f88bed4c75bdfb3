// The scan grid of a calibration: axes parsed from "name=values", applied to DropletParams.

#include <cmath>
#include <cstdlib>
#include <sstream>
#include <stdexcept>
#include <type_traits>

#include "calibration.hpp"

namespace softdrop {
namespace {

// What a scan needs of a droplet field: whether it exists and is numeric, and whether it takes
// whole numbers. Every numeric field of visit_droplet_fields can be scanned, by its option name;
// the enums (constraint-order, viscosity-step) cannot.
struct FieldKind {
  bool numeric = false, whole = false;
};

FieldKind field_kind(const std::string& name) {
  FieldKind kind;
  DropletParams probe;
  visit_droplet_fields(
      [&](const DropletField& field, const auto& value) {
        using T = std::decay_t<decltype(value)>;
        if (name != field.key) return;
        kind.numeric = std::is_arithmetic_v<T>;
        kind.whole = std::is_integral_v<T>;
      },
      probe);
  return kind;
}

// A finite number taking the whole text, or an error naming the axis.
double number(const std::string& text, const std::string& axis) {
  const char* begin = text.c_str();
  char* end = nullptr;
  const double v = std::strtod(begin, &end);
  if (text.empty() || end != begin + text.size() || !std::isfinite(v))
    throw std::invalid_argument("scan '" + axis + "': '" + text + "' is not a finite number");
  return v;
}

std::vector<std::string> split(const std::string& text, char by) {
  std::vector<std::string> parts;
  std::size_t from = 0;
  for (std::size_t at; (at = text.find(by, from)) != std::string::npos; from = at + 1)
    parts.push_back(text.substr(from, at - from));
  parts.push_back(text.substr(from));
  return parts;
}

}  // namespace

std::vector<std::string> scan_parameter_names() {
  std::vector<std::string> names;
  DropletParams probe;
  visit_droplet_fields(
      [&](const DropletField& field, const auto& value) {
        if (std::is_arithmetic_v<std::decay_t<decltype(value)>>) names.emplace_back(field.key);
      },
      probe);
  return names;
}

std::string scan_parameter_list() {
  std::string list;
  for (const std::string& name : scan_parameter_names()) list += (list.empty() ? "" : ", ") + name;
  return list;
}

ScanAxis parse_scan_axis(const std::string& text) {
  const std::size_t eq = text.find('=');
  if (eq == std::string::npos) throw std::invalid_argument("scan '" + text + "': expected name=values");
  ScanAxis axis{text.substr(0, eq), {}};
  const FieldKind field = field_kind(axis.name);
  if (!field.numeric)
    throw std::invalid_argument("scan '" + text + "': unknown parameter '" + axis.name + "' (one of " +
                                scan_parameter_list() + ")");
  const std::string values = text.substr(eq + 1);
  if (values.empty()) throw std::invalid_argument("scan '" + text + "': no values");
  if (values.find(':') != std::string::npos) {
    const std::vector<std::string> p = split(values, ':');
    if (p.size() != 3 && !(p.size() == 4 && p[3] == "log"))
      throw std::invalid_argument("scan '" + text + "': a range is lo:hi:n or lo:hi:n:log");
    const double lo = number(p[0], text), hi = number(p[1], text), n = number(p[2], text);
    const bool log = p.size() == 4;
    if (lo > hi) throw std::invalid_argument("scan '" + text + "': inverted range (lo > hi)");
    if (n < 2 || n > 1000 || n != std::floor(n))
      throw std::invalid_argument("scan '" + text + "': n must be a whole number in [2, 1000]");
    if (log && !(lo > 0)) throw std::invalid_argument("scan '" + text + "': a log range needs lo > 0");
    const int count = static_cast<int>(n);
    for (int i = 0; i < count; ++i) {
      const double f = static_cast<double>(i) / (count - 1);
      axis.values.push_back(i == count - 1 ? hi : log ? lo * std::pow(hi / lo, f) : lo + (hi - lo) * f);
    }
  } else {
    for (const std::string& v : split(values, ',')) axis.values.push_back(number(v, text));
  }
  if (field.whole)
    for (double& v : axis.values) {
      if (v != std::round(v) || std::abs(v) > 1e9)
        throw std::invalid_argument("scan '" + text + "': " + axis.name + " takes whole numbers");
      v = std::round(v);
    }
  return axis;
}

void set_scan_parameter(DropletParams& params, const std::string& name, double value) {
  bool found = false;
  visit_droplet_fields(
      [&](const DropletField& field, auto& field_value) {
        using T = std::decay_t<decltype(field_value)>;
        if constexpr (std::is_arithmetic_v<T>)
          if (name == field.key) field_value = static_cast<T>(value), found = true;
      },
      params);
  if (!found) throw std::invalid_argument("scan: unknown parameter '" + name + "'");
}

DropletParams apply_setting(const DropletParams& base, const std::string& text) {
  DropletParams params = base;
  if (text == "defaults") return params;
  std::istringstream words(text);
  int count = 0;
  for (std::string word; words >> word; ++count) {
    if (word.find('=') == std::string::npos)
      throw std::invalid_argument("setting '" + text + "': '" + word +
                                  "' is not name=value (a label goes before the first ':' and has no '=')");
    const ScanAxis one = parse_scan_axis(word);
    if (one.values.size() != 1)
      throw std::invalid_argument("setting '" + text + "': '" + word + "' must give one value");
    set_scan_parameter(params, one.name, one.values[0]);
  }
  if (count == 0) throw std::invalid_argument("setting '" + text + "': no assignments");
  return params;
}

std::vector<DropletParams> scan_settings(const DropletParams& base, const std::vector<ScanAxis>& axes) {
  std::vector<DropletParams> settings{base};
  for (const ScanAxis& axis : axes) {
    std::vector<DropletParams> next;
    for (const DropletParams& s : settings)
      for (double v : axis.values) {
        next.push_back(s);
        set_scan_parameter(next.back(), axis.name, v);
      }
    settings = std::move(next);
  }
  return settings;
}

std::vector<std::string> scan_labels(const std::vector<ScanAxis>& axes) {
  std::vector<std::string> labels{""};
  for (const ScanAxis& axis : axes) {
    std::vector<std::string> next;
    for (const std::string& l : labels)
      for (double v : axis.values) {
        std::ostringstream text;
        text << l << (l.empty() ? "" : " ") << axis.name << '=' << v;  // 6 digits: a label, not data
        next.push_back(text.str());
      }
    labels = std::move(next);
  }
  if (axes.empty()) labels = {"defaults"};
  return labels;
}

}  // namespace softdrop
