#include "corsa/suite/golden.h"

#include <catch2/catch.hpp>

using corsa::suite::compare_trajectories;
using corsa::suite::Tolerances;

namespace {

const std::string kHeader = "time,entity,x,y,z,h,p,r,speed,road,lane,s,t\n";

std::string row(const std::string& time, const std::string& entity, double x, double h = 0.0,
                const std::string& lane = "-2") {
  return time + "," + entity + "," + std::to_string(x) + ",-5.625,0," + std::to_string(h) +
         ",0,0,25,1," + lane + "," + std::to_string(x) + ",-5.625\n";
}

std::string golden() {
  return kHeader + row("0", "Ego", 10) + row("0", "Lead", 50) + row("0.1", "Ego", 12.5) +
         row("0.1", "Lead", 51.5) + row("0.2", "Ego", 15) + row("0.2", "Lead", 53);
}

}  // namespace

TEST_CASE("an identical trajectory matches its golden with zero deviation", "[suite][golden]") {
  const auto result = compare_trajectories(golden(), golden(), Tolerances{});
  CHECK(result.ok());
  REQUIRE(result.deviations.size() == 9);
  for (const auto& d : result.deviations) CHECK(d.worst == 0.0);
}

TEST_CASE("the worst deviation of a column is reported with when and where", "[suite][golden]") {
  const std::string run = kHeader + row("0", "Ego", 10) + row("0", "Lead", 50.005) +
                          row("0.1", "Ego", 12.5) + row("0.1", "Lead", 51.7) +
                          row("0.2", "Ego", 15) + row("0.2", "Lead", 53.1);
  const auto result = compare_trajectories(golden(), run, Tolerances{});
  REQUIRE_FALSE(result.ok());
  // x and s both deviate by 0.2 m at 0.1 s on Lead.
  REQUIRE(result.failures.size() == 2);
  CHECK(result.failures[0].find("x deviates by 0.2") == 0);
  CHECK(result.failures[0].find("at t=0.1 s (Lead), tolerance 0.01") != std::string::npos);
  CHECK(result.failures[1].find("s deviates by 0.2") == 0);
  CHECK(result.deviations[0].entity == "Lead");
  CHECK(result.deviations[0].time == 0.1);
  Tolerances loose;
  loose.value[0] = 0.5;
  loose.value[*Tolerances::column("s")] = 0.5;
  CHECK(compare_trajectories(golden(), run, loose).ok());
}

TEST_CASE("headings are compared the short way round", "[suite][golden]") {
  const std::string a = kHeader + row("0", "Ego", 10, 3.1415);
  const std::string b = kHeader + row("0", "Ego", 10, -3.1415);
  const auto result = compare_trajectories(a, b, Tolerances{});
  CHECK(result.ok());
  CHECK(result.deviations[*Tolerances::column("h")].worst < 0.001);
}

TEST_CASE("missing rows, other entities and other lanes fail the golden", "[suite][golden]") {
  const std::string shorter = kHeader + row("0", "Ego", 10) + row("0", "Lead", 50);
  const auto missing = compare_trajectories(golden(), shorter, Tolerances{});
  REQUIRE(missing.failures.size() == 1);
  CHECK(missing.failures[0] ==
        "the run has 2 rows up to t=0 s, the golden file 6 rows up to t=0.2 s");

  const std::string swapped = kHeader + row("0", "Lead", 50) + row("0", "Ego", 10);
  const auto order = compare_trajectories(golden(), swapped, Tolerances{});
  REQUIRE_FALSE(order.ok());
  CHECK(order.failures[0].find("row 2 is Ego at t=0 s in the golden file but Lead") == 0);

  const std::string lane = kHeader + row("0", "Ego", 10) + row("0", "Lead", 50) +
                           row("0.1", "Ego", 12.5, 0, "-3") + row("0.1", "Lead", 51.5) +
                           row("0.2", "Ego", 15, 0, "-3") + row("0.2", "Lead", 53);
  const auto changed = compare_trajectories(golden(), lane, Tolerances{});
  REQUIRE(changed.failures.size() == 1);
  CHECK(changed.failures[0] == "road/lane 1/-3 at t=0.1 s (Ego) differs from the golden 1/-2");
}

TEST_CASE("a golden that is not a trajectory is a failure, not a crash", "[suite][golden]") {
  const auto result = compare_trajectories("garbage", golden(), Tolerances{});
  REQUIRE(result.failures.size() == 1);
  CHECK(result.failures[0] == "the golden file is not a trajectory CSV");
  const auto bad_row = compare_trajectories(kHeader + "x,Ego\n", golden(), Tolerances{});
  CHECK(bad_row.failures.at(0) == "the golden file has a malformed row 2");
}
