// `corsa run --rig -o DIR --force` replaces a previous dataset and nothing else: a folder that
// merely holds a file named run.json, or a dataset with a file of the user's added, is refused
// with nothing removed (a test thesis.tex was once deleted with the whole folder); a killed run's
// unindexed frames and temporaries are the previous dataset's and go. A folder another corsa
// writes into is refused.

#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "bounded_run.h"
#include "corsa/core/output_lock.h"

namespace corsa::test {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> rig_run(const fs::path& out, bool force) {
  std::vector<std::string> args{"run",        "scenarios/cut_in.xosc",
                                "--rig",      "scenarios/rigs/lidar64.xml",
                                "-o",         out.string(),
                                "--duration", "0.2",
                                "--quiet"};
  if (force) args.push_back("--force");
  return args;
}

/// Every file below `folder`, relative, with its content.
std::map<std::string, std::string> contents_below(const fs::path& folder) {
  std::map<std::string, std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(folder)) {
    if (!entry.is_directory()) {
      files[fs::relative(entry.path(), folder).string()] = slurp(entry.path());
    }
  }
  return files;
}

/// The files a finished dataset is made of: its index's files, the index, run.json, the class
/// table and each sensor's calibration.
std::set<std::string> dataset_files(const fs::path& dataset) {
  std::set<std::string> files{"run.json", "frames.csv", "classes.json", "hdl64/calibration.json"};
  std::istringstream index(slurp(dataset / "frames.csv"));
  std::string row;
  std::getline(index, row);
  // capture,tick,time,sensor,frame,file,overlap: the sixth field names the file.
  while (std::getline(index, row)) {
    size_t start = 0;
    for (int field = 0; field < 5; ++field) start = row.find(',', start) + 1;
    files.insert(row.substr(start, row.find(',', start) - start));
  }
  return files;
}

TEST_CASE("--force refuses a folder that merely holds a run.json, and removes nothing",
          "[robustness][dataset][output]") {
  TempDir dir;
  const fs::path out = dir.path() / "thesis";
  fs::create_directories(out / "figures");
  std::ofstream(out / "run.json") << "{\"status\": \"my own notes\"}\n";
  std::ofstream(out / "thesis.tex") << "\\documentclass{article}\n";
  std::ofstream(out / "figures" / "plot.png") << "png";
  const auto before = contents_below(out);
  const BoundedResult result = run_bounded(rig_run(out, true), 60);
  INFO(describe("run --rig --force onto a thesis folder", result));
  CHECK(result.exit_code == 2);
  CHECK(result.err.find((out / "run.json").string() +
                        ": error: is not the run.json of a Corsa dataset") != std::string::npos);
  CHECK(contents_below(out) == before);
}

TEST_CASE("--force replaces a previous dataset only when nothing else is in its folder",
          "[robustness][dataset][output]") {
  TempDir dir;
  const fs::path out = dir.path() / "dataset";
  REQUIRE(run_bounded(rig_run(out, false), 60).exit_code == 0);
  std::ofstream(out / "thesis.tex") << "\\documentclass{article}\n";
  const auto before = contents_below(out);
  const BoundedResult refused = run_bounded(rig_run(out, true), 60);
  INFO(describe("run --rig --force onto a dataset with a user's file", refused));
  CHECK(refused.exit_code == 2);
  CHECK(refused.err.find("--force replaces only a previous dataset, and this folder also holds 1 "
                         "file that its run.json and frames.csv do not name (thesis.tex); "
                         "nothing was removed") != std::string::npos);
  CHECK(contents_below(out) == before);

  // What a SIGKILLed run leaves besides its index: a frame not indexed yet, and a temporary.
  fs::remove(out / "thesis.tex");
  std::ofstream(out / "hdl64" / "000099.bin") << "unindexed capture";
  std::ofstream(out / "hdl64" / ".000100.bin.tmp.99999.0") << "half";
  const BoundedResult replaced = run_bounded(rig_run(out, true), 60);
  INFO(describe("run --rig --force onto a previous dataset", replaced));
  CHECK(replaced.exit_code == 0);
  std::set<std::string> names;
  for (const auto& [name, content] : contents_below(out)) names.insert(name);
  CHECK(names == dataset_files(out));
}

TEST_CASE("A dataset folder another corsa writes into is refused",
          "[robustness][dataset][output]") {
  TempDir dir;
  const fs::path out = dir.path() / "dataset";
  fs::create_directory(out);
  const OutputLock held(out);  // this process plays the other writer
  const BoundedResult result = run_bounded(rig_run(out, false), 60);
  INFO(describe("run --rig into a locked folder", result));
  CHECK(result.exit_code == 2);
  CHECK(result.err.find(out.string() + ": error: another corsa (pid ") != std::string::npos);
  CHECK(entry_names(out) == std::set<std::string>{".corsa.lock"});
}

}  // namespace
}  // namespace corsa::test
