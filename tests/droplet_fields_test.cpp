// The one list of DropletParams's fields: which fields decide which droplets step together, and
// that the lane block and the stored parameters follow it.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <type_traits>
#include <vector>

#include "cli_run.hpp"
#include "sim/lane_block_step.hpp"
#include "softdrop/droplet.hpp"
#include "softdrop/search.hpp"
#include "store/params_json.hpp"

namespace softdrop {
namespace {

// Every field once, with its use.
std::map<std::string, FieldUse> uses() {
  std::map<std::string, FieldUse> out;
  DropletParams p;
  visit_droplet_fields([&](const DropletField& field,
                           const auto&) { EXPECT_TRUE(out.emplace(field.key, field.use).second) << field.key; },
                       p);
  return out;
}

// A copy of p with the field `key` changed (and still a different value to the bit).
DropletParams changed(const DropletParams& p, const std::string& key) {
  DropletParams q = p;
  visit_droplet_fields(
      [&](const DropletField& field, auto& v) {
        if (key != field.key) return;
        using T = std::decay_t<decltype(v)>;
        if constexpr (std::is_enum_v<T>)
          v = static_cast<T>(static_cast<int>(v) == 0 ? 1 : 0);  // (every enum has two values or more)
        else if constexpr (std::is_floating_point_v<T>)
          v = v != 0 ? v * 1.5 : 0.5;  // (0.5: in every field's range)
        else
          v = v + 1;
      },
      q);
  return q;
}

TEST(DropletFields, TheContactFieldsAloneMayDifferWithinALaneBlock) {
  const auto all = uses();
  ASSERT_EQ(all.size(), 21u);
  std::set<std::string> constraint, contacts;
  for (const auto& [key, use] : all) {
    if (use == FieldUse::constraint) constraint.insert(key);
    if (use == FieldUse::contacts) contacts.insert(key);
  }
  EXPECT_EQ(constraint, (std::set<std::string>{"masses", "radius", "max-strain", "constraint-iterations"}));
  // The shaking is each droplet's own force, added lane by lane.
  EXPECT_EQ(contacts, (std::set<std::string>{"kc", "cc", "max-depth", "vibration-amplitude", "vibration-frequency",
                                             "vibration-axis", "vibration-start"}));
  const DropletParams p;
  for (const auto& [key, use] : all) {
    SCOPED_TRACE(key);
    const DropletParams q = changed(p, key);
    EXPECT_FALSE(same_fields(p, q, FieldUse::contacts)) << "every field counts";
    EXPECT_EQ(same_fields(p, q, FieldUse::forces), use == FieldUse::contacts);
    EXPECT_EQ(same_fields(p, q, FieldUse::constraint), use != FieldUse::constraint);
    EXPECT_EQ(LaneBlockStep::compatible(p, q), use == FieldUse::contacts);
  }
  EXPECT_TRUE(same_fields(p, DropletParams{}, FieldUse::contacts));
}

TEST(DropletFields, EqualMeansEqualToTheBit) {
  DropletParams a, b;
  a.viscosity = 0.0;
  b.viscosity = -0.0;
  EXPECT_FALSE(same_fields(a, b, FieldUse::forces));
  EXPECT_FALSE(LaneBlockStep::compatible(a, b));
}

TEST(DropletFields, StoredParametersHoldEveryFieldAndReadItBack) {
  SearchOptions o;
  for (const auto& [key, use] : uses()) {
    SCOPED_TRACE(key);
    o.droplet = changed(DropletParams{}, key);
    const SearchOptions back = search_params_from_json(search_params_to_json(o));
    EXPECT_TRUE(same_fields(back.droplet, o.droplet, FieldUse::contacts));
    EXPECT_FALSE(same_fields(back.droplet, DropletParams{}, FieldUse::contacts));
  }
}

// Parameters stored by a build older than a key read as that build ran: the viscosity's share on
// dilation as 1 (the default now is 0), no rest test, the sequential constraint order, the
// explicit viscosity step, the paper's strategy, no shaking. So a history stored with the balloon
// resumes as the balloon.
TEST(DropletFields, StoredParametersWithoutTheNewerKeysReadAsOlderBuildsRanThem) {
  SearchOptions o;
  o.run.rest_window = 0.05, o.run.rest_distance = 0.1;
  o.strategy.kind = StrategyKind::es;
  o.droplet.viscosity_step = ViscosityStep::exponential;
  o.droplet.vibration_amplitude = 2, o.droplet.vibration_frequency = 300;
  o.droplet.vibration_axis = VibrationAxis::xy, o.droplet.vibration_start = VibrationStart::start;
  nlohmann::json j = nlohmann::json::parse(search_params_to_json(o));
  EXPECT_EQ(j.at("viscosity-step"), "exponential");
  EXPECT_EQ(j.at("vibration-axis"), "xy");
  for (const char* key :
       {"viscosity-dilation", "rest-window", "rest-distance", "constraint-order", "viscosity-step", "strategy",
        "vibration-amplitude", "vibration-frequency", "vibration-axis", "vibration-start"}) {
    ASSERT_TRUE(j.contains(key)) << key;
    j.erase(key);
  }
  const SearchOptions back = search_params_from_json(j.dump());
  EXPECT_EQ(back.droplet.viscosity_dilation, 1.0);
  EXPECT_EQ(DropletParams{}.viscosity_dilation, 0.0);
  EXPECT_EQ(back.run.rest_window, 0.0);
  EXPECT_EQ(back.run.rest_distance, 0.0);
  EXPECT_EQ(back.droplet.constraint_order, ConstraintOrder::sequential);
  EXPECT_EQ(back.droplet.viscosity_step, ViscosityStep::explicit_euler);
  EXPECT_EQ(back.strategy.kind, StrategyKind::paper);
  EXPECT_FALSE(back.droplet.vibrates());
  EXPECT_EQ(back.droplet.vibration_axis, VibrationAxis::x);
  EXPECT_EQ(back.droplet.vibration_start, VibrationStart::rest);
  EXPECT_EQ(back.droplet.ks, o.droplet.ks);  // the keys that are there are read as they are
}

TEST(DropletFields, EveryFieldIsACommandLineOptionWithItsHelp) {
  for (const char* command : {"simulate", "sweep", "optimize"}) {
    const test::Result r = test::run(std::string(command) + " --help");
    ASSERT_EQ(r.code, 0) << command;
    DropletParams p;
    visit_droplet_fields(
        [&](const DropletField& field, const auto&) {
          EXPECT_NE(r.out.find(std::string("--") + field.key), std::string::npos) << command << " --" << field.key;
          EXPECT_NE(r.out.find(field.help), std::string::npos) << command << " --" << field.key;
        },
        p);
  }
  // A value given on the command line reaches the droplet's checks, which name the option.
  const test::Result bad = test::run("simulate --x0 250 --max-strain -1");
  EXPECT_NE(bad.code, 0);
  EXPECT_NE(bad.err.find("max-strain = -1"), std::string::npos) << bad.err;
}

}  // namespace
}  // namespace softdrop

namespace softdrop {
namespace {

// Sets the field `key` of a copy of the defaults to v.
DropletParams with_value(const std::string& key, double v) {
  DropletParams q;
  visit_droplet_fields(
      [&](const DropletField& field, auto& x) {
        using T = std::decay_t<decltype(x)>;
        if constexpr (std::is_arithmetic_v<T>)
          if (key == field.key) x = static_cast<T>(v);
      },
      q);
  return q;
}

TEST(DropletFields, EveryFieldsRangeIsCheckedAndNamedInItsOwnWords) {
  // Just outside each finite end of a field's range, and NaN and infinity for the doubles: refused
  // with a message that names the field, its value and the range. Every field but the constraint
  // order has a range, and the defaults are inside every one.
  std::string why;
  ASSERT_TRUE(DropletParams{}.IsValid(&why)) << why;
  int checked = 0;
  DropletParams defaults;
  visit_droplet_fields(
      [&](const DropletField& field, const auto& value) {
        using T = std::decay_t<decltype(value)>;
        if constexpr (std::is_arithmetic_v<T>) {
          const FieldRange& r = field.range;
          std::vector<double> bad;
          const double step = std::is_integral_v<T> ? 1.0 : 0.0;
          if (std::isfinite(r.lo))
            bad.push_back(r.lo_included ? (step > 0 ? r.lo - step : std::nextafter(r.lo, -1e300)) : r.lo);
          if (std::isfinite(r.hi))
            bad.push_back(r.hi_included ? (step > 0 ? r.hi + step : std::nextafter(r.hi, 1e300)) : r.hi);
          if (std::is_floating_point_v<T>) {
            bad.push_back(std::nan(""));
            bad.push_back(std::numeric_limits<double>::infinity());
          }
          for (double v : bad) {
            std::string message;
            EXPECT_FALSE(with_value(field.key, v).IsValid(&message)) << field.key << " = " << v;
            EXPECT_EQ(message.rfind(std::string(field.key) + " = ", 0), 0u) << message;
            EXPECT_NE(message.find(": must be "), std::string::npos) << message;
          }
          ++checked;
        }
      },
      defaults);
  EXPECT_EQ(checked, static_cast<int>(uses().size()) - 4);  // all but the four enums
  // The words of the three kinds of range, as users see them.
  std::string message;
  EXPECT_FALSE(with_value("dt", 0).IsValid(&message));
  EXPECT_EQ(message, "dt = 0: must be in (0, 0.01]");
  EXPECT_FALSE(with_value("masses", 7).IsValid(&message));
  EXPECT_EQ(message, "masses = 7: must be in [8, 100000]");
  EXPECT_FALSE(with_value("ks", -1).IsValid(&message));
  EXPECT_EQ(message, "ks = -1: must be >= 0");
  EXPECT_FALSE(with_value("mass", 0).IsValid(&message));
  EXPECT_EQ(message, "mass = 0: must be > 0");
  EXPECT_FALSE(with_value("gravity", std::nan("")).IsValid(&message));
  EXPECT_EQ(message, "gravity = nan: must be finite");
}

}  // namespace
}  // namespace softdrop
