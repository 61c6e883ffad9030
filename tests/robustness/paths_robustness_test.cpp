// Paths that are not what a command expects: folders instead of files, missing files, a path
// through a regular file, outputs into a missing folder or onto a folder, and files that are
// empty, all NUL bytes or binary garbage. Each is rejected with exit 2 and a message naming the
// path, and no output is left behind.

#include <random>
#include <string>
#include <vector>

#include "bounded_run.h"

namespace corsa::test {
namespace {

const std::string kMap = "scenarios/maps/motorway_2km.xodr";
const std::string kScenario = "scenarios/cut_in.xosc";

/// The commands that read one input file, with `input` in the input's place.
std::vector<std::vector<std::string>> readers(const std::string& input, const std::string& out) {
  return {{"validate", input},
          {"map", "info", input},
          {"map", "mesh", input, "-o", out + "/mesh.obj"},
          {"run", input, "--quiet", "--record", out + "/out.csv"},
          {"sweep", input, "-o", out + "/sweep", "--quiet"}};
}

std::string joined(const std::vector<std::string>& args) {
  std::string text = "corsa";
  for (const auto& arg : args) {
    text += ' ' + arg;
  }
  return text;
}

/// Runs every reader on `input` and checks exit 2, a message naming `input` and an empty `out`.
void check_readers_reject(const std::string& input, const std::string& what) {
  TempDir out;
  for (const auto& args : readers(input, out.path().string())) {
    const BoundedResult result = run_bounded(args);
    INFO(what << ": " << describe(joined(args), result));
    CHECK_FALSE(result.timed_out);
    CHECK(result.exit_code == 2);
    CHECK(result.err.find(input + ":") != std::string::npos);
    CHECK(result.err.find("error: ") != std::string::npos);
    CHECK(out.entries() == 0);
  }
}

TEST_CASE("A folder given as an input file is rejected as a folder", "[robustness][paths]") {
  TempDir dir;
  for (const char* name : {"map.xodr", "scenario.xosc", "no_extension"}) {
    const auto folder = dir.path() / name;
    std::filesystem::create_directory(folder);
    check_readers_reject(folder.string(), "folder");
    // Not an XML message about an empty document: the path itself is the problem.
    const BoundedResult result = run_bounded({"validate", folder.string()});
    CHECK(has_file_error(result.err, folder.string()));
    CHECK(result.err.find("folder") != std::string::npos);
  }
}

TEST_CASE("Missing input files and paths through a regular file are rejected",
          "[robustness][paths]") {
  TempDir dir;
  std::ofstream(dir.path() / "plain.txt") << "not a folder\n";
  for (const auto& input : {dir.path() / "missing.xodr", dir.path() / "missing.xosc",
                            dir.path() / "plain.txt" / "map.xodr"}) {
    check_readers_reject(input.string(), "missing");
    CHECK(has_file_error(run_bounded({"validate", input.string()}).err, input.string()));
  }
}

TEST_CASE("Empty, NUL-filled and binary garbage inputs are rejected at line 1 or later",
          "[robustness][paths]") {
  TempDir dir;
  std::mt19937 engine(11);
  std::string garbage(8192, '\0');
  for (char& c : garbage) {
    c = static_cast<char>(engine() % 256);
  }
  const std::pair<const char*, std::string> contents[] = {
      {"empty", ""},          {"nul", std::string(64, '\0')}, {"bom", "\xEF\xBB\xBF"},
      {"blank", "\n\n   \n"}, {"garbage", garbage},           {"text", "hello, world\n"}};
  for (const auto& [name, content] : contents) {
    for (const char* extension : {".xodr", ".xosc"}) {
      const auto input = dir.path() / (std::string(name) + extension);
      std::ofstream(input, std::ios::binary) << content;
      TempDir out;
      for (const auto& args : readers(input.string(), out.path().string())) {
        const BoundedResult result = run_bounded(args);
        INFO(describe(joined(args), result));
        CHECK_FALSE(result.timed_out);
        CHECK(result.exit_code == 2);
        CHECK(has_located_error(result.err));
        CHECK(result.err.find(input.string() + ":") != std::string::npos);
        CHECK(out.entries() == 0);
      }
    }
  }
}

TEST_CASE("Outputs into a missing folder or onto a folder fail with exit 2 and write nothing",
          "[robustness][paths]") {
  TempDir dir;
  const std::string missing = (dir.path() / "missing" / "deeper").string();
  const std::string folder = (dir.path() / "folder.csv").string();
  std::filesystem::create_directory(folder);
  const std::vector<std::vector<std::string>> cases = {
      {"map", "mesh", kMap, "-o", missing + "/mesh.obj"},
      {"map", "mesh", kMap, "-o", missing + "/mesh.ply"},
      {"run", kScenario, "--quiet", "--duration", "1", "--record", missing + "/out.csv"},
      {"run", kScenario, "--quiet", "--duration", "1", "--record", folder},
      {"run", kScenario, "--quiet", "--duration", "1", "--summary", missing + "/s.json"},
      {"run", kScenario, "--quiet", "--duration", "1", "--log", folder},
  };
  for (const auto& args : cases) {
    const BoundedResult result = run_bounded(args);
    INFO(describe(joined(args), result));
    CHECK_FALSE(result.timed_out);
    CHECK(result.exit_code == 2);
    CHECK(result.err.find(": error: ") != std::string::npos);
    // Nothing written next to the bad target, and the folder target is still an empty folder.
    CHECK(entry_names(dir.path()) == std::set<std::string>{"folder.csv"});
    CHECK(std::filesystem::is_empty(folder));
  }
}

}  // namespace
}  // namespace corsa::test
