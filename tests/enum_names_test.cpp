// The names of enum values: every to_string and its parse read one table, so each value's name
// reads back as that value, and a name no table has is refused in one line that names the option
// and offers every name.
#include "util/enum_names.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "optimizer/islands.hpp"
#include "softdrop/droplet.hpp"
#include "softdrop/medium.hpp"
#include "softdrop/search.hpp"
#include "softdrop/simulation.hpp"

namespace softdrop {
namespace {

template <class E, class Parse>
void expect_round_trips(std::initializer_list<E> values, Parse parse) {
  for (const E v : values) {
    const std::string name = to_string(v);
    EXPECT_NE(name, "?");
    EXPECT_EQ(parse(name), v) << name;
  }
}

TEST(EnumNames, EveryValueReadsBackFromItsName) {
  expect_round_trips({MoveKind::initial, MoveKind::all, MoveKind::single, MoveKind::relocate, MoveKind::migrate},
                     parse_move_kind);
  expect_round_trips({StrategyKind::paper, StrategyKind::es, StrategyKind::lahc, StrategyKind::anneal}, parse_strategy);
  expect_round_trips({Migration::ring, Migration::broadcast}, parse_migration);
  expect_round_trips({MediumKind::overlapping, MediumKind::non_overlapping}, parse_medium_kind);
  expect_round_trips({RadiusDistribution::uniform, RadiusDistribution::lognormal}, parse_radius_distribution);
  expect_round_trips({ConstraintOrder::sequential, ConstraintOrder::red_black}, parse_constraint_order);
  expect_round_trips({Outcome::passed, Outcome::stuck, Outcome::timeout, Outcome::diverged}, parse_outcome);
  EXPECT_STREQ(to_string(Termination::time_limit), "time-limit");
  EXPECT_EQ(parse_medium_kind("nonoverlapping"), MediumKind::non_overlapping);  // the old spelling
}

TEST(EnumNames, AnUnknownNameIsRefusedWithTheOptionAndEveryName) {
  const auto message = [](auto parse, const std::string& name) -> std::string {
    try {
      parse(name);
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "accepted";
  };
  EXPECT_EQ(message(parse_strategy, "tabu"), "strategy = 'tabu': must be paper, es, lahc, anneal or cmaes");
  EXPECT_EQ(message(parse_constraint_order, "zigzag"), "constraint-order = 'zigzag': must be sequential or red-black");
  EXPECT_EQ(message(parse_medium_kind, "Overlapping"),
            "kind = 'Overlapping': must be overlapping, non-overlapping or relaxed");
  EXPECT_EQ(message(parse_outcome, ""), "outcome = '': must be passed, stuck, timeout or diverged");
  EXPECT_EQ(message(parse_move_kind, "all "),
            "move kind = 'all ': must be initial, all, single, relocate, migrate or mixed");
}

TEST(EnumNames, TheTableHelpersNameOneValueAndListAll) {
  enum class Colour { red, green, blue, grey };
  constexpr detail::EnumName<Colour> kOne[] = {{Colour::red, "red"}};
  constexpr detail::EnumName<Colour> kThree[] = {
      {Colour::red, "red"}, {Colour::green, "green"}, {Colour::blue, "blue"}};
  EXPECT_EQ(detail::names_of(kOne), "red");
  EXPECT_EQ(detail::names_of(kThree), "red, green or blue");
  static_assert(std::string_view(detail::name_of(kThree, Colour::blue)) == "blue");
  EXPECT_STREQ(detail::name_of(kThree, Colour::grey), "?");  // a value the table lacks
  Colour c = Colour::grey;
  EXPECT_FALSE(detail::value_of(kThree, "Green", &c));  // names are matched exactly
  EXPECT_EQ(c, Colour::grey);
  EXPECT_TRUE(detail::value_of(kThree, "green", &c));
  EXPECT_EQ(c, Colour::green);
  EXPECT_EQ(detail::name_list(kThree), (std::vector<std::string>{"red", "green", "blue"}));
}

TEST(EnumNames, TheCommandLineOffersEveryNameAParseTakes) {
  EXPECT_EQ(strategy_names(), (std::vector<std::string>{"paper", "es", "lahc", "anneal", "cmaes"}));
  EXPECT_EQ(constraint_order_names(), (std::vector<std::string>{"sequential", "red-black"}));
  EXPECT_EQ(medium_kind_names(), (std::vector<std::string>{"overlapping", "non-overlapping", "relaxed"}));
  EXPECT_EQ(radius_distribution_names(), (std::vector<std::string>{"uniform", "lognormal"}));
  for (const std::string& name : strategy_names()) EXPECT_STREQ(to_string(parse_strategy(name)), name.c_str());
  for (const std::string& name : medium_kind_names()) EXPECT_STREQ(to_string(parse_medium_kind(name)), name.c_str());
}

}  // namespace
}  // namespace softdrop
