#include "corsa/sweep/variant_plan.h"

#include <catch2/catch.hpp>

#include "corsa/xosc/distributions.h"
#include "sweep_fixtures.h"

using corsa::InputError;
using corsa::sweep::GridAxis;
using corsa::sweep::ParameterValues;
using corsa::sweep::parse_grid_axis;
using corsa::sweep::VariantPlan;
using corsa::sweep::test::distribution_plan;
using corsa::sweep::test::fixture;
using corsa::sweep::test::follow_scenario;

namespace {

// Checks strictly: a distribution parameter the scenario lacks is an error then.
std::string check_error(const VariantPlan& plan) {
  corsa::Diagnostics diagnostics;
  try {
    plan.check(follow_scenario(), true, diagnostics);
  } catch (const InputError& error) {
    return error.diagnostic().format();
  }
  return "no error";
}

}  // namespace

TEST_CASE("deterministic distributions combine as nested loops, the first slowest",
          "[sweep][plan]") {
  const VariantPlan plan = distribution_plan("grid.xosc");
  REQUIRE(plan.size() == 12);
  CHECK(plan.scenario() == fixture("follow.xosc").lexically_normal());
  CHECK(plan.parameter_names() ==
        std::vector<std::string>{"Ego_Speed", "Lane", "Gap", "Lead_Speed"});
  CHECK(plan.variant(0) ==
        ParameterValues{{"Ego_Speed", "20"}, {"Lane", "-2"}, {"Gap", "30"}, {"Lead_Speed", "10"}});
  CHECK(plan.variant(1) ==
        ParameterValues{{"Ego_Speed", "20"}, {"Lane", "-2"}, {"Gap", "60"}, {"Lead_Speed", "20"}});
  CHECK(plan.variant(2)[1].second == "-3");
  CHECK(plan.variant(11) ==
        ParameterValues{{"Ego_Speed", "30"}, {"Lane", "-3"}, {"Gap", "60"}, {"Lead_Speed", "20"}});
  CHECK(check_error(plan) == "no error");
}

TEST_CASE("a command-line grid varies fastest inside a distribution", "[sweep][plan]") {
  const VariantPlan plan = distribution_plan("grid.xosc", {parse_grid_axis("Headway=1,2,3")});
  REQUIRE(plan.size() == 36);
  CHECK(plan.parameter_names().back() == "Headway");
  CHECK(plan.variant(0).back().second == "1");
  CHECK(plan.variant(2).back().second == "3");
  CHECK(plan.variant(3).back().second == "1");
  CHECK(plan.variant(3)[2].second == "60");  // the distribution moved on by one
}

TEST_CASE("a grid over a scenario is row-major over its axes", "[sweep][plan]") {
  const VariantPlan plan = VariantPlan::from_scenario(
      fixture("follow.xosc"),
      {parse_grid_axis("Ego_Speed=20:40:5"), parse_grid_axis("Lane=-2,-3")});
  REQUIRE(plan.size() == 10);
  CHECK(plan.variant(0) == ParameterValues{{"Ego_Speed", "20"}, {"Lane", "-2"}});
  CHECK(plan.variant(1) == ParameterValues{{"Ego_Speed", "20"}, {"Lane", "-3"}});
  CHECK(plan.variant(9) == ParameterValues{{"Ego_Speed", "40"}, {"Lane", "-3"}});
  CHECK(VariantPlan::from_scenario(fixture("follow.xosc"), {}).size() == 1);
  CHECK(VariantPlan::from_scenario(fixture("follow.xosc"), {}).variant(0).empty());
}

TEST_CASE("stochastic variants are reproducible and independent of each other", "[sweep][plan]") {
  const VariantPlan plan = distribution_plan("stochastic.xosc");
  const VariantPlan again = distribution_plan("stochastic.xosc");
  REQUIRE(plan.size() == 16);
  CHECK(plan.parameter_names().size() == 6);
  for (size_t i = 0; i < plan.size(); ++i) {
    CHECK(plan.variant(i) == again.variant(i));
    // The same draws as the distribution model's own enumeration.
    CHECK(plan.variant(i) ==
          corsa::xosc::variant_at(*plan.distribution(), i, corsa::xosc::VariantOptions{}).values);
  }
  CHECK(plan.variant(3) != plan.variant(4));
  CHECK(check_error(plan) == "no error");
}

TEST_CASE("a parameter varied twice is refused", "[sweep][plan]") {
  CHECK_THROWS_WITH(distribution_plan("grid.xosc", {parse_grid_axis("Lane=-1")}),
                    Catch::Contains("--param Lane=-1: error: parameter 'Lane' is varied twice"));
  CHECK_THROWS_WITH(VariantPlan::from_scenario(fixture("follow.xosc"), {parse_grid_axis("Gap=1"),
                                                                        parse_grid_axis("Gap=2")}),
                    Catch::Contains("varied twice"));
}

TEST_CASE("a distribution over an undeclared parameter is located in the distribution",
          "[sweep][plan]") {
  const VariantPlan plan = distribution_plan("undeclared.xosc");
  const std::string error = check_error(plan);
  CHECK(error.find("undeclared.xosc:10: error: parameter 'Wind_Speed' is not declared in "
                   "scenario") != std::string::npos);
  // Leniently, that parameter is not varied: a located warning, and its name to leave out.
  corsa::Diagnostics diagnostics;
  CHECK(plan.check(follow_scenario(), false, diagnostics) ==
        std::vector<std::string>{"Wind_Speed"});
  REQUIRE(diagnostics.size() == 1);
  CHECK_THAT(
      diagnostics.all()[0].format(),
      Catch::Contains("undeclared.xosc:10: warning: parameter 'Wind_Speed' is not declared") &&
          Catch::Contains("(read as not varied: its values are left out)"));
  const VariantPlan grid =
      VariantPlan::from_scenario(fixture("follow.xosc"), {parse_grid_axis("speed=1,2")});
  CHECK(check_error(grid).find("--param speed=1,2: error: parameter 'speed' is not declared") == 0);
}

TEST_CASE("values that do not suit a parameter's type are located", "[sweep][plan]") {
  const VariantPlan fractional =
      VariantPlan::from_scenario(fixture("follow.xosc"), {parse_grid_axis("Lane=-2:-1:0.5")});
  CHECK(check_error(fractional) ==
        "--param Lane=-2:-1:0.5: error: value '-1.5' is not a valid int for parameter 'Lane'");
  const VariantPlan too_big =
      VariantPlan::from_scenario(fixture("follow.xosc"), {parse_grid_axis("Count=1,70000")});
  CHECK(check_error(too_big).find("'70000' is not a valid unsignedShort") != std::string::npos);
  const VariantPlan boolean =
      VariantPlan::from_scenario(fixture("follow.xosc"), {parse_grid_axis("Flag=true,maybe")});
  CHECK(check_error(boolean).find("'maybe' is not a valid boolean") != std::string::npos);
  CHECK(check_error(distribution_plan("wrong_type.xosc"))
            .find("wrong_type.xosc:7: error: this distribution draws real numbers, which do not "
                  "suit parameter 'Lane' of type int") != std::string::npos);
}

TEST_CASE("an empty range in a distribution is located by the loader", "[sweep][plan]") {
  CHECK_THROWS_WITH(distribution_plan("empty_range.xosc"),
                    Catch::Contains("empty_range.xosc:8: error: range lowerLimit is above "
                                    "upperLimit"));
}
