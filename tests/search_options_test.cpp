// A search's options: IsValid names the bad parameter; stored options read back bit for bit, a
// missing key is named, and runs stored before a key existed read as they ran.
#include <gtest/gtest.h>

#include <cmath>

#include "search_fixtures.hpp"
#include "softdrop/search.hpp"
#include "store/params_json.hpp"

namespace softdrop {
namespace {

TEST(SearchOptions, IsValidNamesTheBadParameter) {
  std::string why;
  auto bad = [&](auto change, const char* name) {
    SearchOptions o;
    change(o);
    EXPECT_FALSE(o.IsValid(&why)) << name;
    EXPECT_NE(why.find(name), std::string::npos) << why;
  };
  bad([](SearchOptions& o) { o.lambda = 0; }, "lambda");
  bad([](SearchOptions& o) { o.step = -1; }, "step");
  bad([](SearchOptions& o) { o.single_step = NAN; }, "single-step");
  bad([](SearchOptions& o) { o.single_every = -2; }, "single-every");
  bad([](SearchOptions& o) { o.gap = -0.1; }, "gap");
  bad([](SearchOptions& o) { o.droplet.dt = 0; }, "dt");
  EXPECT_TRUE(SearchOptions().IsValid(&why)) << why;
}

TEST(SearchParams, RoundTripBitForBitAndNameMissingKeys) {
  SearchOptions o;
  o.seed = 0xFFFFFFFFFFFFFFF1ULL;
  o.lambda = 3;
  o.step = 0.1 + 0.2;
  o.droplet.dt = 1.2345678901234567e-5;
  o.droplet.nrt = 6.02214076e8;
  o.run.max_steps = 123456789;
  const SearchOptions back = search_params_from_json(search_params_to_json(o));
  EXPECT_EQ(back.seed, o.seed);
  EXPECT_EQ(back.lambda, 3);
  EXPECT_EQ(back.step, o.step);
  EXPECT_EQ(back.droplet.dt, o.droplet.dt);
  EXPECT_EQ(back.droplet.nrt, o.droplet.nrt);
  EXPECT_EQ(back.run.max_steps, o.run.max_steps);
  EXPECT_EQ(search_params_to_json(back), search_params_to_json(o));
  try {
    search_params_from_json(R"({"seed": 1})");
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("'lambda' missing"), std::string::npos) << e.what();
  }
  std::string j = search_params_to_json(o);
  j.replace(j.find("\"lambda\":3"), 10, "\"lambda\":3.5");
  EXPECT_THROW(search_params_from_json(j), std::runtime_error);
  // The constraint order travels as its name; files written before it existed mean sequential.
  o.droplet.constraint_order = ConstraintOrder::red_black;
  std::string k = search_params_to_json(o);
  EXPECT_NE(k.find("\"constraint-order\":\"red-black\""), std::string::npos);
  EXPECT_EQ(search_params_from_json(k).droplet.constraint_order, ConstraintOrder::red_black);
  std::string old = k;
  old.erase(old.find("\"constraint-order\":\"red-black\","), std::string("\"constraint-order\":\"red-black\",").size());
  EXPECT_EQ(search_params_from_json(old).droplet.constraint_order, ConstraintOrder::sequential);
  k.replace(k.find("red-black"), 9, "shuffled!");
  EXPECT_THROW(search_params_from_json(k), std::runtime_error);
}

TEST(SearchParams, RunsStoredBeforeTheRestTestReadAsRunsWithoutIt) {
  SearchOptions o;
  o.run.rest_window = 0.05;
  o.run.rest_distance = 0.25;
  const std::string j = search_params_to_json(o);
  EXPECT_EQ(search_params_from_json(j).run.rest_window, 0.05);
  EXPECT_EQ(search_params_from_json(j).run.rest_distance, 0.25);
  auto without = [](std::string text, const std::string& key) {
    const auto at = text.find("\"" + key + "\":");
    const auto end = text.find(',', at);
    return text.erase(at, end - at + 1);
  };
  const SearchOptions old = search_params_from_json(without(without(j, "rest-window"), "rest-distance"));
  EXPECT_EQ(old.run.rest_window, 0.0);  // whatever today's default, a stored run keeps its own test
  EXPECT_EQ(old.run.rest_distance, 0.0);
}

}  // namespace
}  // namespace softdrop
