// The one list of DropletParams's fields: which fields decide which droplets step together, and
// that the lane block and the stored parameters follow it.
#include <gtest/gtest.h>

#include <map>
#include <set>
#include <string>
#include <type_traits>

#include "cli_run.hpp"
#include "sim/lane_block_step.hpp"
#include "softdrop/droplet.hpp"
#include "softdrop/params_json.hpp"
#include "softdrop/search.hpp"

namespace softdrop {
namespace {

// Every field once, with its use.
std::map<std::string, FieldUse> uses() {
  std::map<std::string, FieldUse> out;
  DropletParams p;
  visit_droplet_fields(
      [&](const DropletField& field, const auto&) {
        EXPECT_TRUE(out.emplace(field.key, field.use).second) << field.key;
      },
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
          v = v == ConstraintOrder::sequential ? ConstraintOrder::red_black
                                               : ConstraintOrder::sequential;
        else if constexpr (std::is_floating_point_v<T>)
          v = v * 1.5;
        else
          v = v + 1;
      },
      q);
  return q;
}

TEST(DropletFields, TheContactFieldsAloneMayDifferWithinALaneBlock) {
  const auto all = uses();
  ASSERT_EQ(all.size(), 15u);
  std::set<std::string> constraint, contacts;
  for (const auto& [key, use] : all) {
    if (use == FieldUse::constraint) constraint.insert(key);
    if (use == FieldUse::contacts) contacts.insert(key);
  }
  EXPECT_EQ(constraint,
            (std::set<std::string>{"masses", "radius", "max-strain", "constraint-iterations"}));
  EXPECT_EQ(contacts, (std::set<std::string>{"kc", "cc", "max-depth"}));
  const DropletParams p;
  for (const auto& [key, use] : all) {
    SCOPED_TRACE(key);
    const DropletParams q = changed(p, key);
    EXPECT_FALSE(same_fields(p, q, FieldUse::contacts)) << "every field counts";
    EXPECT_EQ(same_fields(p, q, FieldUse::lanes), use == FieldUse::contacts);
    EXPECT_EQ(same_fields(p, q, FieldUse::constraint), use != FieldUse::constraint);
    EXPECT_EQ(LaneBlockStep::compatible(p, q), use == FieldUse::contacts);
  }
  EXPECT_TRUE(same_fields(p, DropletParams{}, FieldUse::contacts));
}

TEST(DropletFields, EqualMeansEqualToTheBit) {
  DropletParams a, b;
  a.viscosity = 0.0;
  b.viscosity = -0.0;
  EXPECT_FALSE(same_fields(a, b, FieldUse::lanes));
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
