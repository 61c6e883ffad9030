// The command line's one exceptions-to-exit-codes ladder and its one reading of output paths.

#include "exit_codes.h"

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <new>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "args.h"
#include "corsa/core/diagnostic.h"
#include "output_paths.h"
#include "temp_dir.h"

namespace {

using corsa::cli::guarded;

// Runs guarded() and returns its exit code with what it printed on stderr.
std::pair<int, std::string> run(const std::string& command, const std::function<int()>& body) {
  std::ostringstream captured;
  std::streambuf* previous = std::cerr.rdbuf(captured.rdbuf());
  const int code = guarded(command, body);
  std::cerr.rdbuf(previous);
  return {code, captured.str()};
}

corsa::cli::ParsedArgs parse(const std::vector<std::string>& args) {
  corsa::cli::ArgParser parser("x [options]", "test");
  parser.option("-o", "FILE", "output").option("--log", "FILE", "log");
  return parser.parse(args);
}

}  // namespace

TEST_CASE("what a command throws becomes one message and one exit code", "[cli][exit]") {
  CHECK(run("run", [] { return 1; }) == std::pair<int, std::string>{1, ""});

  const auto usage = run("map render", []() -> int { throw corsa::cli::UsageError("bad --size"); });
  CHECK(usage.first == corsa::cli::kExitBadInput);
  CHECK(usage.second == "corsa map render: error: bad --size\n(see 'corsa map render --help')\n");

  const auto input = run("run", []() -> int {
    throw corsa::InputError(corsa::make_error("a.xosc", 3, "no storyboard"));
  });
  CHECK(input.first == corsa::cli::kExitBadInput);
  CHECK(input.second == "a.xosc:3: error: no storyboard\n");

  const auto disk = run("sweep", []() -> int {
    throw std::filesystem::filesystem_error("cannot create",
                                            std::make_error_code(std::errc::permission_denied));
  });
  CHECK(disk.first == corsa::cli::kExitBadInput);
  CHECK_THAT(disk.second, Catch::StartsWith("corsa sweep: error: "));

  const auto memory = run("run", []() -> int { throw std::bad_alloc(); });
  CHECK(memory.first == corsa::cli::kExitInternal);
  CHECK(memory.second == "corsa: error: out of memory\n");

  const auto bug = run("", []() -> int { throw std::logic_error("oops"); });
  CHECK(bug.first == corsa::cli::kExitInternal);
  CHECK_THAT(bug.second, Catch::Contains("internal error: oops") && Catch::Contains("a bug"));
}

TEST_CASE("output paths are checked when read, before any work", "[cli][outputs]") {
  corsa::test::TempDir dir;
  const std::string file = (dir.path() / "plain.txt").string();
  std::ofstream(file) << "x";

  CHECK_FALSE(corsa::cli::output_file(parse({}), "--log"));
  const std::string nested = (dir.path() / "new/deeper/out.csv").string();
  CHECK(corsa::cli::output_file(parse({"--log", nested}), "--log") ==
        std::filesystem::path(nested));
  CHECK_FALSE(std::filesystem::exists(dir.path() / "new"));  // made only when written

  CHECK_THROWS_AS(corsa::cli::output_file(parse({"--log", dir.path().string()}), "--log"),
                  corsa::InputError);  // a folder
  CHECK_THROWS_AS(corsa::cli::output_file(parse({"--log", file + "/x.csv"}), "--log"),
                  corsa::InputError);  // through a file
  CHECK_THROWS_WITH(corsa::cli::required_output_file(parse({}), "-o", "FILE.png (the picture)"),
                    "missing -o FILE.png (the picture)");
  CHECK_THROWS_WITH(corsa::cli::required_output_file(parse({"-o", "a.jpg"}), "-o", "FILE.png",
                                                     [](const std::filesystem::path&) {
                                                       throw corsa::cli::UsageError("name it .png");
                                                     }),
                    "name it .png");

  CHECK(corsa::cli::output_folder(parse({}), "-o", "sweep") == std::filesystem::path("sweep"));
  CHECK_THROWS_AS(corsa::cli::output_folder(parse({"-o", file}), "-o", "sweep"),
                  corsa::InputError);  // a file where a folder should be
  CHECK_THROWS_WITH(corsa::cli::required_output_folder(parse({}), "-o", "DIR (the dataset)"),
                    "missing -o DIR (the dataset)");
}
