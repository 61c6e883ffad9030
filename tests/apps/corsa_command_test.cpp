#include <catch2/catch.hpp>
#include <cstdio>
#include <string>

#include "run_corsa.h"

using corsa::test::run_corsa;

TEST_CASE("corsa --help lists every subcommand", "[cli][e2e]") {
  const auto result = run_corsa({"--help"});
  CHECK(result.exit_code == 0);
  for (const char* name : {"run", "validate", "map", "convert", "sweep", "test"}) {
    INFO(name);
    CHECK_THAT(result.out, Catch::Contains(std::string("  ") + name + " "));
  }
}

TEST_CASE("corsa --version prints the version", "[cli][e2e]") {
  const auto result = run_corsa({"--version"});
  CHECK(result.exit_code == 0);
  CHECK_THAT(result.out, Catch::Matches("corsa [0-9]+\\.[0-9]+\\.[0-9]+\n"));
}

TEST_CASE("every subcommand has its own --help", "[cli][e2e]") {
  for (const char* name : {"run", "validate", "map", "convert", "sweep", "test"}) {
    INFO(name);
    const auto result = run_corsa({name, "--help"});
    CHECK(result.exit_code == 0);
    CHECK_THAT(result.out, Catch::StartsWith(std::string("usage: corsa ") + name));
  }
}

TEST_CASE("bad usage exits 2 with a message", "[cli][e2e]") {
  SECTION("no command") {
    const auto result = run_corsa({});
    CHECK(result.exit_code == 2);
    CHECK_THAT(result.err, Catch::Contains("usage: corsa"));
  }
  SECTION("unknown command") {
    const auto result = run_corsa({"fly"});
    CHECK(result.exit_code == 2);
    CHECK_THAT(result.err, Catch::Contains("unknown command 'fly'"));
  }
  SECTION("unknown option") {
    const auto result = run_corsa({"run", "a.xosc", "--nope"});
    CHECK(result.exit_code == 2);
    CHECK_THAT(result.err, Catch::Contains("corsa run: error: unknown option '--nope'"));
  }
}

TEST_CASE("corsa run --help lists the dataset options without --rig", "[cli][e2e]") {
  const auto result = run_corsa({"run", "--help"});
  CHECK(result.exit_code == 0);
  CHECK_THAT(result.out, Catch::Contains("dataset options (with --rig"));
  for (const char* name : {"--rig", "-o DIR", "--format", "--weather", "--time-of-day", "--preview",
                           "--model", "--entity-model", "--force"}) {
    INFO(name);
    CHECK_THAT(result.out, Catch::Contains(std::string("  ") + name));
  }
}

TEST_CASE("a dataset option without --rig says what it needs", "[cli][e2e]") {
  const auto result = run_corsa({"run", "scenarios/cut_in.xosc", "--weather", "fog=50"});
  CHECK(result.exit_code == 2);
  CHECK_THAT(result.err, Catch::Contains("--weather is a dataset option: it needs --rig RIG.xml"));
}

TEST_CASE("a malformed --entity-model is refused before any run with exit 2", "[cli][e2e]") {
  const auto result = run_corsa({"run", "scenarios/demo/cut_in_city.xosc", "--rig",
                                 "tests/collect/fixtures/small_rig.xml", "-o", "out/never_written",
                                 "--entity-model", "car.glb"});
  CHECK(result.exit_code == 2);
  CHECK_THAT(result.err, Catch::Contains("--entity-model 'car.glb': expected WHO=FILE"));
  const auto who = run_corsa({"run", "scenarios/demo/cut_in_city.xosc", "--rig",
                              "tests/collect/fixtures/small_rig.xml", "-o", "out/never_written",
                              "--entity-model", "Eg0=car.glb"});
  CHECK(who.exit_code == 2);
  CHECK_THAT(who.err, Catch::Contains("--entity-model Eg0=car.glb: error: 'Eg0' is neither an "
                                      "entity of the scenario nor a category") &&
                          Catch::Contains("(did you mean 'Ego'?)"));
}

TEST_CASE("a misspelt option, key or name gets the nearest valid one", "[cli][e2e]") {
  const auto option = run_corsa({"run", "scenarios/cut_in.xosc", "--wether", "fog=50"});
  CHECK(option.exit_code == 2);
  CHECK_THAT(option.err, Catch::Contains("unknown option '--wether' (did you mean '--weather'?)"));
  const auto controller = run_corsa({"run", "scenarios/cut_in.xosc", "--controller", "ac"});
  CHECK(controller.exit_code == 2);
  CHECK_THAT(controller.err, Catch::Contains("(did you mean 'acc'?)"));
  const auto semantics = run_corsa({"run", "scenarios/cut_in.xosc", "--semantics", "esmin"});
  CHECK(semantics.exit_code == 2);
  CHECK_THAT(semantics.err, Catch::Contains("--semantics expects standard or esmini, got 'esmin' "
                                            "(did you mean 'esmini'?)"));
  const auto sweep = run_corsa({"sweep", "scenarios/cut_in.xosc", "--semantics", "esmin"});
  CHECK(sweep.exit_code == 2);
  CHECK_THAT(sweep.err, Catch::Contains("--semantics expects standard or esmini, got 'esmin'"));
  const auto test = run_corsa({"test", "scenarios/suites/alks", "--semantics", "esmin"});
  CHECK(test.exit_code == 2);
  CHECK_THAT(test.err, Catch::Contains("--semantics expects standard or esmini, got 'esmin'"));
  const auto npc = run_corsa({"run", "scenarios/cut_in.xosc", "--npc", "vehicle=3"});
  CHECK(npc.exit_code == 2);
  CHECK_THAT(npc.err, Catch::Contains("unknown key 'vehicle' (did you mean 'vehicles'?)"));
}

TEST_CASE("the plugin with the heavy libraries loads on demand", "[cli][e2e][plugin]") {
  const auto result = run_corsa({"--version", "--plugin"});
  CHECK(result.exit_code == 0);
  CHECK_THAT(result.out, Catch::Contains("corsa plugin "));
}

TEST_CASE("the corsa executable itself links none of the slow-to-load libraries", "[cli][plugin]") {
  // OpenCV and PROJ cost 100-300 ms to load; a scenario run must not pay for them (see
  // apps/corsa/plugin_api.h). ldd lists the shared libraries the executable needs.
  const std::string command = std::string("ldd ") + CORSA_BINARY;
  std::FILE* pipe = ::popen(command.c_str(), "r");
  REQUIRE(pipe != nullptr);
  std::string listing;
  char buffer[512];
  while (std::fgets(buffer, sizeof buffer, pipe) != nullptr) {
    listing += buffer;
  }
  REQUIRE(::pclose(pipe) == 0);
  CHECK_THAT(listing, Catch::Contains("libc.so"));
  for (const char* heavy : {"opencv", "libproj", "embree", "assimp", "gdal", "avcodec"}) {
    INFO(heavy);
    CHECK_THAT(listing, !Catch::Contains(heavy));
  }
}
