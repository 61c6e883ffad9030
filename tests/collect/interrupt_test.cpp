// An interrupted `corsa run --rig` (SIGINT, as Ctrl-C sends, or SIGTERM, as a job scheduler or
// `kill` sends) stops after the capture in progress and leaves a consistent dataset whose run.json
// says where it stopped, and the run's --record and --summary files for the part that ran.

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <chrono>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "corsa/core/atomic_file.h"
#include "dataset_check.h"
#include "temp_dir.h"

namespace {

namespace fs = std::filesystem;

size_t captures_indexed(const fs::path& dataset) {
  try {
    const auto rows = corsa::test::read_index(dataset);
    return rows.empty() ? 0 : static_cast<size_t>(rows.back().capture + 1);
  } catch (const std::exception&) {
    return 0;  // not written yet
  }
}

// Every line of a CSV ends in '\n' and has as many fields as the header: a file cut short while
// being written fails one of the two.
void check_complete_csv(const std::string& csv) {
  REQUIRE(!csv.empty());
  CHECK(csv.back() == '\n');
  std::istringstream lines(csv);
  std::string line;
  REQUIRE(std::getline(lines, line));
  const auto fields = std::count(line.begin(), line.end(), ',');
  size_t rows = 0;
  while (std::getline(lines, line)) {
    CHECK(std::count(line.begin(), line.end(), ',') == fields);
    ++rows;
  }
  CHECK(rows >= 3);
}

}  // namespace

TEST_CASE(
    "SIGINT or SIGTERM leaves only complete captures, an index that says where it stopped "
    "and complete --record and --summary files",
    "[dataset][interrupt]") {
  const int signal_number = GENERATE(SIGINT, SIGTERM);
  const std::string signal_name = signal_number == SIGINT ? "SIGINT" : "SIGTERM";
  INFO("signal " << signal_name);
  corsa::test::TempDir dir;
  const fs::path out = dir.path() / "interrupted";
  const fs::path record = dir.path() / "trajectories.csv";
  const fs::path summary = dir.path() / "summary.json";
  const pid_t child = fork();
  REQUIRE(child >= 0);
  if (child == 0) {
    if (chdir(CORSA_SOURCE_DIR) != 0) {
      _exit(99);
    }
    execl(CORSA_BINARY, CORSA_BINARY, "run", "scenarios/demo/cut_in_city.xosc", "--rig",
          "tests/collect/fixtures/small_rig.xml", "-o", out.c_str(), "--quiet", "--record",
          record.c_str(), "--summary", summary.c_str(), static_cast<char*>(nullptr));
    _exit(98);
  }
  // Wait for a few captures (at most 120 s on a busy machine), then interrupt.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (captures_indexed(out) < 3 && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  REQUIRE(kill(child, signal_number) == 0);
  int status = 0;
  REQUIRE(waitpid(child, &status, 0) == child);
  REQUIRE(WIFEXITED(status));  // handled: a SIGTERM left at its default would kill the process
  CHECK(WEXITSTATUS(status) == 128 + signal_number);

  const std::string run_json = corsa::read_file(out / "run.json");
  CHECK(corsa::test::json_string(run_json, "status") == "interrupted");
  CHECK(corsa::test::json_string(run_json, "end_reason") == "interrupted by " + signal_name);
  const size_t captures = captures_indexed(out);
  CHECK(captures >= 3);
  CHECK(captures < 201);  // the whole run has 201 captures at 10 Hz
  CHECK(corsa::test::json_number(run_json, "captures") == static_cast<double>(captures));
  CHECK(corsa::test::check_dataset(out, 192, 108).empty());
  // The run's own outputs are written for the part that ran: the trajectories up to the last
  // tick, the summary saying it was interrupted there. Both are whole files.
  REQUIRE(fs::exists(record));
  REQUIRE(fs::exists(summary));
  const std::string summary_json = corsa::read_file(summary);
  CHECK_NOTHROW(nlohmann::json::parse(summary_json));  // a cut-off JSON does not parse
  CHECK(corsa::test::json_string(summary_json, "end_reason") == "interrupted");
  const double end_time = corsa::test::json_number(summary_json, "sim_time");
  CHECK(end_time >= 0.2);  // at least 3 captures at 10 Hz
  CHECK(end_time < 20.0);
  const std::string csv = corsa::read_file(record);
  check_complete_csv(csv);
  const size_t last_row = csv.rfind('\n', csv.size() - 2) + 1;
  CHECK(std::stod(csv.substr(last_row)) == Approx(end_time));
  // Nothing half-written: no temporary files are left behind.
  for (const std::string& file : corsa::test::files_under(dir.path())) {
    CHECK(file.find(".tmp") == std::string::npos);
  }
}
