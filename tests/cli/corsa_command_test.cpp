#include <catch2/catch.hpp>

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
