#include "args.h"

#include <catch2/catch.hpp>
#include <sstream>
#include <string>
#include <vector>

using corsa::cli::ArgParser;
using corsa::cli::UsageError;

namespace {

ArgParser run_parser() {
  ArgParser parser("run SCENARIO.xosc [options]", "Runs a scenario.");
  parser.positional("SCENARIO.xosc", "the scenario")
      .flag("--quiet", "no progress bar")
      .option("--dt", "SECONDS", "fixed step")
      .repeated("--param", "NAME=VALUE", "override a parameter");
  return parser;
}

}  // namespace

TEST_CASE("options, flags, repeated options and positionals parse", "[cli][args]") {
  const std::vector<std::string> args{"cut_in.xosc", "--dt",        "0.02",   "--param",
                                      "a=1",         "--param=b=2", "--quiet"};
  const auto parsed = run_parser().parse(args);
  CHECK(parsed.positionals() == std::vector<std::string>{"cut_in.xosc"});
  CHECK(parsed.number("--dt") == 0.02);
  CHECK(parsed.values("--param") == std::vector<std::string>{"a=1", "b=2"});
  CHECK(parsed.flag("--quiet"));
  CHECK_FALSE(parsed.help());
}

TEST_CASE("NAME=VALUE options split at their first equals sign", "[cli][args]") {
  const std::vector<std::string> args{"a.xosc",   "--param", "speed=30", "--param",
                                      "expr=a=b", "--param", "empty="};
  const auto parsed = run_parser().parse(args);
  using Assignments = std::vector<std::pair<std::string, std::string>>;
  CHECK(parsed.assignments("--param") ==
        Assignments{{"speed", "30"}, {"expr", "a=b"}, {"empty", ""}});
  CHECK(parsed.assignments("--dt").empty());
  SECTION("a value without a name is refused with the option named") {
    for (const std::string bad : {"speed", "=30"}) {
      const std::vector<std::string> one{"a.xosc", "--param", bad};
      CHECK_THROWS_WITH(run_parser().parse(one).assignments("--param"),
                        "--param expects NAME=VALUE, got '" + bad + "'");
    }
  }
}

TEST_CASE("a choice option takes one of its names and refuses any other", "[cli][args]") {
  ArgParser parser("run", "Runs.");
  parser.option("--mode", "a|b|c", "a mode");
  const auto mode = [&parser](std::vector<std::string> args, std::vector<std::string> names) {
    return parser.parse(args).choice("--mode", names);
  };
  const std::vector<std::string> names{"auto", "caller", "writer"};
  CHECK_FALSE(mode({}, names));
  CHECK(mode({"--mode", "caller"}, names) == "caller");
  CHECK_THROWS_WITH(
      mode({"--mode", "writers"}, names),
      "--mode expects auto, caller or writer, got 'writers' (did you mean 'writer'?)");
  CHECK_THROWS_WITH(mode({"--mode", ""}, {"x", "y"}), "--mode expects x or y, got ''");
  CHECK_THROWS_WITH(mode({"--mode", "zzz"}, {"one"}), "--mode expects one, got 'zzz'");
}

TEST_CASE("bad usage is reported with the option named", "[cli][args]") {
  const auto parser = run_parser();
  SECTION("unknown option") {
    const std::vector<std::string> args{"a.xosc", "--frobnicate"};
    CHECK_THROWS_WITH(parser.parse(args), "unknown option '--frobnicate'");
  }
  SECTION("missing value") {
    const std::vector<std::string> args{"a.xosc", "--dt"};
    CHECK_THROWS_WITH(parser.parse(args), Catch::StartsWith("option '--dt' needs a value"));
  }
  SECTION("not a number") {
    const std::vector<std::string> args{"a.xosc", "--dt", "fast"};
    const auto parsed = parser.parse(args);
    CHECK_THROWS_AS(parsed.number("--dt"), UsageError);
  }
  SECTION("missing positional") {
    const std::vector<std::string> args{"--quiet"};
    CHECK_THROWS_WITH(parser.parse(args), "missing SCENARIO.xosc");
  }
  SECTION("too many positionals") {
    const std::vector<std::string> args{"a.xosc", "b.xosc"};
    CHECK_THROWS_WITH(parser.parse(args), "unexpected argument 'b.xosc'");
  }
  SECTION("a single-valued option given twice") {
    const std::vector<std::string> args{"a.xosc", "--dt", "1", "--dt", "2"};
    CHECK_THROWS_WITH(parser.parse(args), "option '--dt' given twice");
  }
}

TEST_CASE("--help is recognised anywhere and lists every option", "[cli][args]") {
  const std::vector<std::string> args{"--help"};
  const auto parser = run_parser();
  CHECK(parser.parse(args).help());
  std::ostringstream help;
  parser.print_help(help);
  CHECK_THAT(help.str(), Catch::Contains("usage: corsa run SCENARIO.xosc [options]"));
  CHECK_THAT(help.str(), Catch::Contains("--param NAME=VALUE ..."));
  CHECK_THAT(help.str(), Catch::Contains("--dt SECONDS"));
}

TEST_CASE("negative numbers are values, not options", "[cli][args]") {
  const std::vector<std::string> args{"a.xosc", "--dt", "-1"};
  CHECK(run_parser().parse(args).number("--dt") == -1.0);
}
