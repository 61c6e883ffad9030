#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <map>
#include <string>

#include "corsa/core/strings.h"
#include "corsa/xosc/distributions.h"
#include "scenario_text.h"
#include "shared_data.h"
#include "temp_dir.h"

namespace fs = std::filesystem;
using namespace corsa::xosc;

using corsa::test::kAsamExamples;

namespace {

ParameterValueDistribution load_text(const corsa::test::TempDir& dir, const std::string& body) {
  corsa::test::write_text(dir.path() / "s.xosc", "<OpenSCENARIO/>\n");
  corsa::test::write_text(
      dir.path() / "d.xosc",
      "<?xml version=\"1.0\"?>\n<OpenSCENARIO>\n<FileHeader revMajor=\"1\" revMinor=\"3\" "
      "date=\"2024-01-01T00:00:00\" description=\"d\" author=\"a\"/>\n"
      "<ParameterValueDistribution>\n<ScenarioFile filepath=\"s.xosc\"/>\n" +
          body + "</ParameterValueDistribution>\n</OpenSCENARIO>\n");
  corsa::Diagnostics diagnostics;
  return load_distribution(dir.path() / "d.xosc", diagnostics);
}

}  // namespace

TEST_CASE("the ASAM deterministic parameter set enumerates its value sets in order",
          "[xosc][distribution]") {
  corsa::Diagnostics diagnostics;
  const auto distribution = load_distribution(
      kAsamExamples / "SlowPrecedingVehicleDeterministicParameterSet.xosc", diagnostics);
  CHECK(distribution.scenario_path ==
        (kAsamExamples / "SlowPrecedingVehicle.xosc").lexically_normal());
  const auto variants = enumerate_variants(distribution);
  REQUIRE(variants.size() == 2);
  using Values = std::vector<std::pair<std::string, std::string>>;
  CHECK(variants[0].values == Values{{"Time_Of_Day", "2024-03-21T12:00:00"},
                                     {"Sun_Azimuth", "3.1415"},
                                     {"Sun_Elevation", "0.8"}});
  CHECK(variants[1].values[0].second == "2024-03-21T17:00:00");
}

TEST_CASE("deterministic entries combine row-major, the first varying slowest",
          "[xosc][distribution]") {
  corsa::test::TempDir dir;
  const auto distribution = load_text(dir, R"(<Deterministic>
<DeterministicSingleParameterDistribution parameterName="A">
<DistributionSet><Element value="x"/><Element value="y"/></DistributionSet>
</DeterministicSingleParameterDistribution>
<DeterministicSingleParameterDistribution parameterName="B">
<DistributionRange stepWidth="0.1"><Range lowerLimit="0.1" upperLimit="0.3"/></DistributionRange>
</DeterministicSingleParameterDistribution>
</Deterministic>
)");
  REQUIRE(variant_count(distribution) == 6);
  const auto variants = enumerate_variants(distribution);
  const char* expected[][2] = {{"x", "0.1"}, {"x", "0.2"}, {"x", "0.30000000000000004"},
                               {"y", "0.1"}, {"y", "0.2"}, {"y", "0.30000000000000004"}};
  for (size_t i = 0; i < 6; ++i) {
    INFO(i);
    CHECK(variants[i].values[0] == std::pair<std::string, std::string>{"A", expected[i][0]});
    CHECK(variants[i].values[1].first == "B");
    CHECK(variants[i].values[1].second == expected[i][1]);
    CHECK(variant_at(distribution, i).values == variants[i].values);
  }
}

TEST_CASE("stochastic variants are reproducible and independent of each other",
          "[xosc][distribution]") {
  corsa::Diagnostics diagnostics;
  const auto distribution = load_distribution(
      kAsamExamples / "SlowPrecedingVehicleStochasticParameterSet.xosc", diagnostics);
  REQUIRE(variant_count(distribution) == 100);
  const auto first = enumerate_variants(distribution);
  const auto second = enumerate_variants(distribution);
  REQUIRE(first.size() == 100);
  std::map<std::string, int> ego_counts;
  for (size_t i = 0; i < first.size(); ++i) {
    CHECK(first[i].values == second[i].values);
    CHECK(variant_at(distribution, i).values == first[i].values);
    REQUIRE(first[i].values.size() == 2);
    CHECK(first[i].values[0].first == "Ego_Speed");
    ++ego_counts[first[i].values[0].second];
    const auto a1 = corsa::parse_double(first[i].values[1].second);
    REQUIRE(a1);
    CHECK(*a1 >= 15.0);  // the Range truncates the normal distribution
    CHECK(*a1 <= 30.0);
  }
  // Only the set's values occur, and the heaviest ones (weight 10 of 35) most often.
  for (const auto& [value, count] : ego_counts) {
    INFO(value);
    CHECK((value == "10.0" || value == "22.0" || value == "25.0" || value == "27.0" ||
           value == "28.0" || value == "40.0" || value == "60.0"));
    CHECK(count < 60);
  }
  CHECK(ego_counts["27.0"] + ego_counts["28.0"] > ego_counts["10.0"] + ego_counts["60.0"]);
  // A different seed gives different draws.
  auto reseeded = distribution;
  std::get<Stochastic>(reseeded.definition).random_seed = 2.0;
  CHECK(variant_at(reseeded, 0).values != first[0].values);
}

TEST_CASE("every stochastic distribution kind draws inside its support", "[xosc][distribution]") {
  corsa::test::TempDir dir;
  const auto distribution = load_text(dir, R"(<Stochastic numberOfTestRuns="200" randomSeed="7">
<StochasticDistribution parameterName="U"><UniformDistribution><Range lowerLimit="2" upperLimit="3"/></UniformDistribution></StochasticDistribution>
<StochasticDistribution parameterName="P"><PoissonDistribution expectedValue="4"><Range lowerLimit="1" upperLimit="9"/></PoissonDistribution></StochasticDistribution>
<StochasticDistribution parameterName="L"><LogNormalDistribution expectedValue="10" variance="4"/></StochasticDistribution>
<StochasticDistribution parameterName="H"><Histogram><Bin weight="1"><Range lowerLimit="0" upperLimit="1"/></Bin><Bin weight="0"><Range lowerLimit="5" upperLimit="6"/></Bin></Histogram></StochasticDistribution>
<StochasticDistribution parameterName="N"><NormalDistribution expectedValue="0" variance="1"/></StochasticDistribution>
</Stochastic>
)");
  double log_normal_sum = 0.0;
  for (const auto& variant : enumerate_variants(distribution)) {
    REQUIRE(variant.values.size() == 5);
    const double u = *corsa::parse_double(variant.values[0].second);
    CHECK((u >= 2.0 && u < 3.0));
    const auto p = corsa::parse_int(variant.values[1].second);
    REQUIRE(p);
    CHECK((*p >= 1 && *p <= 9));
    const double l = *corsa::parse_double(variant.values[2].second);
    CHECK(l > 0.0);
    log_normal_sum += l;
    const double h = *corsa::parse_double(variant.values[3].second);
    CHECK((h >= 0.0 && h < 1.0));
    CHECK(std::isfinite(*corsa::parse_double(variant.values[4].second)));
  }
  // The log-normal's own mean is expectedValue (10): 200 draws with sd 2 land near it.
  CHECK(log_normal_sum / 200.0 == Approx(10.0).margin(0.6));
}

TEST_CASE("user-defined distributions load but cannot be enumerated", "[xosc][distribution]") {
  corsa::test::TempDir dir;
  const auto distribution = load_text(dir, R"(<Deterministic>
<DeterministicSingleParameterDistribution parameterName="A">
<UserDefinedDistribution type="myTool">anything</UserDefinedDistribution>
</DeterministicSingleParameterDistribution>
</Deterministic>
)");
  CHECK_THROWS_WITH(
      variant_count(distribution),
      Catch::Contains("UserDefinedDistribution of type 'myTool' cannot be enumerated"));
}

TEST_CASE("a distribution must name an existing scenario file", "[xosc][distribution]") {
  corsa::test::TempDir dir;
  corsa::test::write_text(dir.path() / "d.xosc", R"(<?xml version="1.0"?>
<OpenSCENARIO>
<FileHeader revMajor="1" revMinor="3" date="2024-01-01T00:00:00" description="d" author="a"/>
<ParameterValueDistribution>
<ScenarioFile filepath="missing.xosc"/>
<Stochastic numberOfTestRuns="3"><StochasticDistribution parameterName="X"><UniformDistribution><Range lowerLimit="0" upperLimit="1"/></UniformDistribution></StochasticDistribution></Stochastic>
</ParameterValueDistribution>
</OpenSCENARIO>
)");
  corsa::Diagnostics diagnostics;
  try {
    load_distribution(dir.path() / "d.xosc", diagnostics);
    FAIL("loaded");
  } catch (const corsa::InputError& error) {
    CHECK_THAT(error.diagnostic().message,
               Catch::StartsWith("scenario file 'missing.xosc' not found"));
    CHECK(error.diagnostic().line == 5);
  }
}
