// An interrupted `corsa run --rig` (SIGINT, as Ctrl-C sends) stops after the capture in progress
// and leaves a consistent dataset whose run.json says where it stopped.

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <chrono>
#include <filesystem>
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

}  // namespace

TEST_CASE("SIGINT leaves only complete captures and an index that says where it stopped",
          "[dataset][interrupt]") {
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
  REQUIRE(kill(child, SIGINT) == 0);
  int status = 0;
  REQUIRE(waitpid(child, &status, 0) == child);
  REQUIRE(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 128 + SIGINT);

  const std::string run_json = corsa::read_file(out / "run.json");
  CHECK(corsa::test::json_string(run_json, "status") == "interrupted");
  CHECK(corsa::test::json_string(run_json, "end_reason") == "interrupted by SIGINT");
  const size_t captures = captures_indexed(out);
  CHECK(captures >= 3);
  CHECK(captures < 201);  // the whole run has 201 captures at 10 Hz
  CHECK(corsa::test::json_number(run_json, "captures") == static_cast<double>(captures));
  CHECK(corsa::test::check_dataset(out, 192, 108).empty());
  // The run's own outputs are written for the part that ran: the trajectories up to the last
  // tick, the summary saying it was interrupted there.
  REQUIRE(fs::exists(record));
  REQUIRE(fs::exists(summary));
  const std::string summary_json = corsa::read_file(summary);
  CHECK(corsa::test::json_string(summary_json, "end_reason") == "interrupted");
  const double end_time = corsa::test::json_number(summary_json, "sim_time");
  CHECK(end_time >= 0.2);  // at least 3 captures at 10 Hz
  CHECK(end_time < 20.0);
  const std::string csv = corsa::read_file(record);
  const size_t last_row = csv.rfind('\n', csv.size() - 2) + 1;
  CHECK(std::stod(csv.substr(last_row)) == Approx(end_time));
  // Nothing half-written: no temporary files are left behind.
  for (const std::string& file : corsa::test::files_under(dir.path())) {
    CHECK(file.find(".tmp") == std::string::npos);
  }
}
