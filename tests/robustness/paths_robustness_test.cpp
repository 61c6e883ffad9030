// Paths that are not what a command expects: folders instead of files, missing files, a path
// through a regular file, outputs onto a folder or through a file, and files that are empty, all
// NUL bytes or binary garbage. Each is rejected with exit 2 and a message naming the path, and no
// output is left behind. Outputs into missing folders create them (every command the same way).

#include <random>
#include <string>
#include <vector>

#include "bounded_run.h"

namespace corsa::test {
namespace {

/// The commands that read one input file, with `input` in the input's place.
std::vector<std::vector<std::string>> readers(const std::string& input, const std::string& out) {
  return {{"validate", input},
          {"map", "info", input},
          {"map", "mesh", input, "-o", out + "/mesh.obj"},
          {"run", input, "--quiet", "--record", out + "/out.csv"},
          {"sweep", input, "-o", out + "/sweep", "--quiet"}};
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

TEST_CASE("Outputs onto a folder or through a regular file fail with exit 2 and write nothing",
          "[robustness][paths]") {
  TempDir dir;
  const std::string folder = (dir.path() / "folder.csv").string();
  std::filesystem::create_directory(folder);
  const std::string mesh_folder = (dir.path() / "folder.obj").string();
  std::filesystem::create_directory(mesh_folder);
  const std::string plain = (dir.path() / "plain.txt").string();
  std::ofstream(plain) << "a file, not a folder\n";
  const std::string through = plain + "/deeper";
  const std::string suite = std::string(CORSA_SOURCE_DIR) + "/scenarios/suites/regression";
  const std::vector<std::pair<std::string, std::vector<std::string>>> cases = {
      {through + "/mesh.obj", {"map", "mesh", kMap, "-o", through + "/mesh.obj"}},
      {mesh_folder, {"map", "mesh", kMap, "-o", mesh_folder}},
      {through + "/out.csv",
       {"run", kScenario, "--quiet", "--duration", "1", "--record", through + "/out.csv"}},
      {folder, {"run", kScenario, "--quiet", "--duration", "1", "--record", folder}},
      {through + "/s.json",
       {"run", kScenario, "--quiet", "--duration", "1", "--summary", through + "/s.json"}},
      {folder, {"run", kScenario, "--quiet", "--duration", "1", "--log", folder}},
      {through + "/r.xml", {"test", suite, "--quiet", "--junit", through + "/r.xml"}},
      {folder, {"test", suite, "--quiet", "--junit", folder}},
      {through, {"test", suite, "--quiet", "-o", through}},
      {through, {"sweep", "scenarios/suites/sweeps/cut_in_grid.xosc", "--quiet", "-o", through}},
      {through + "/map.png", {"map", "render", kMap, "-o", through + "/map.png"}},
      {through + "/k.xodr",
       {"convert", "ngii", std::string(CORSA_SHARED_DIR) + "/data/ngii/kcity", "-o",
        through + "/k.xodr"}},
      {through + "/fixes.csv",
       {"convert", "ngii", std::string(CORSA_SHARED_DIR) + "/data/ngii/kcity", "-o",
        (dir.path() / "folder.csv" / "k.xodr").string(), "--report", through + "/fixes.csv"}},
      {through, {"run", kScenario, "--quiet", "--rig", "scenarios/rigs/demo.xml", "-o", through}},
  };
  for (const auto& [target, args] : cases) {
    const BoundedResult result = run_bounded(args, 10);
    INFO(describe(joined(args), result));
    CHECK_FALSE(result.timed_out);
    CHECK(result.exit_code == 2);
    // Refused before any work: a message naming the target, and nothing written anywhere.
    CHECK(result.err.find(": error: ") != std::string::npos);
    CHECK(result.err.find(target) != std::string::npos);
    CHECK(entry_names(dir.path()) ==
          std::set<std::string>{"folder.csv", "folder.obj", "plain.txt"});
    CHECK(std::filesystem::is_empty(folder));
    CHECK(std::filesystem::is_empty(mesh_folder));
    CHECK(slurp(plain) == "a file, not a folder\n");
  }
}

TEST_CASE("Every output into missing folders creates them, as sweep -o always did",
          "[robustness][paths]") {
  TempDir dir;
  const auto in = [&](const std::string& path) { return (dir.path() / path).string(); };
  const std::vector<std::vector<std::string>> cases = {
      {"map", "mesh", kMap, "-o", in("a/b/mesh.obj")},
      {"run", kScenario, "--quiet", "--duration", "1", "--record", in("c/d/out.csv"), "--summary",
       in("e/s.json"), "--log", in("f/g/h/log.csv")},
  };
  for (const auto& args : cases) {
    const BoundedResult result = run_bounded(args);
    INFO(describe(joined(args), result));
    CHECK(result.exit_code == 0);
  }
  for (const char* file :
       {"a/b/mesh.obj", "a/b/mesh.mtl", "c/d/out.csv", "e/s.json", "f/g/h/log.csv"}) {
    INFO(file);
    CHECK(std::filesystem::is_regular_file(dir.path() / file));
  }
  // A JUnit report of a one-test folder suite.
  TempDir suite;
  std::ofstream(suite.path() / "cut_in.xosc") << cut_in_text();
  const BoundedResult result =
      run_bounded({"test", suite.path().string(), "--quiet", "--junit", in("i/j/report.xml")});
  INFO(describe("test --junit", result));
  CHECK(result.exit_code == 0);
  CHECK(std::filesystem::is_regular_file(dir.path() / "i/j/report.xml"));
}

TEST_CASE("A run refused for bad input leaves no output folder behind", "[robustness][paths]") {
  TempDir dir;
  std::ofstream(dir.path() / "broken.xosc") << cut_in_text().substr(0, 2000);
  const BoundedResult result = run_bounded({"run", (dir.path() / "broken.xosc").string(), "--quiet",
                                            "--record", (dir.path() / "new/out.csv").string(),
                                            "--summary", (dir.path() / "other/s.json").string()});
  INFO(describe("broken scenario with outputs in new folders", result));
  CHECK(result.exit_code == 2);
  CHECK(has_located_error(result.err));
  CHECK(entry_names(dir.path()) == std::set<std::string>{"broken.xosc"});
}

}  // namespace
}  // namespace corsa::test
