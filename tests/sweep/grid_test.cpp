#include "corsa/sweep/grid.h"

#include <catch2/catch.hpp>

#include "corsa/core/diagnostic.h"

using corsa::InputError;
using corsa::sweep::parse_grid_axis;

namespace {

std::string error_of(const std::string& text) {
  try {
    parse_grid_axis(text);
  } catch (const InputError& error) {
    return error.diagnostic().format();
  }
  return "no error";
}

}  // namespace

TEST_CASE("a grid range includes both ends in DistributionRange's number format", "[sweep][grid]") {
  const auto axis = parse_grid_axis("speed=20:40:5");
  CHECK(axis.name == "speed");
  CHECK(axis.values == std::vector<std::string>{"20", "25", "30", "35", "40"});
  CHECK(axis.spec == "speed=20:40:5");
  // lower + k * step, not a running sum: 0.1 steps stay exact to the shortest text.
  const auto fine = parse_grid_axis("t=0:0.3:0.1");
  CHECK(fine.values == std::vector<std::string>{"0", "0.1", "0.2", "0.30000000000000004"});
  CHECK(parse_grid_axis("x=1:2.5:1").values == std::vector<std::string>{"1", "2"});
}

TEST_CASE("grid lists and single values are taken as written", "[sweep][grid]") {
  CHECK(parse_grid_axis("lane=-1,-2").values == std::vector<std::string>{"-1", "-2"});
  CHECK(parse_grid_axis("$owner=A2").name == "owner");
  CHECK(parse_grid_axis("label= car , truck").values == std::vector<std::string>{"car", "truck"});
  // A dateTime has colons but is one value.
  const auto time = parse_grid_axis("Time_Of_Day=2024-03-21T12:00:00");
  CHECK(time.values == std::vector<std::string>{"2024-03-21T12:00:00"});
}

TEST_CASE("bad grid axes are located at the option", "[sweep][grid]") {
  CHECK(error_of("speed=40:20:5") ==
        "--param speed=40:20:5: error: empty range: HIGH (20) is below LOW (40)");
  CHECK(error_of("speed=20:40:0").find("step of a range LOW:HIGH:STEP must be positive") !=
        std::string::npos);
  CHECK(error_of("speed").find("expected NAME=VALUES") != std::string::npos);
  CHECK(error_of("=3").find("parameter name is empty") != std::string::npos);
  CHECK(error_of("lane=-1,,-2").find("empty value") != std::string::npos);
  CHECK(error_of("lane=").find("no value") != std::string::npos);
  CHECK(error_of("x=0:1e9:1").find("more than 10 million") != std::string::npos);
}
