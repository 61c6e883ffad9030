#pragma once

// Runs the `corsa` binary under a time limit and checks the project's promise for bad input:
// exit code 2 with a located `file:line: error:` message, never a crash, a hang or an output file
// left behind.

#include <fcntl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <chrono>
#include <filesystem>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include "run_corsa.h"

namespace corsa::test {

/// The bundled map and scenario the reader cases start from (paths from the source folder).
inline const std::string kMap = "scenarios/maps/motorway_2km.xodr";
inline const std::string kScenario = "scenarios/cut_in.xosc";

/// The command line `corsa args...` as text, for messages.
inline std::string joined(const std::vector<std::string>& args) {
  std::string text = "corsa";
  for (const auto& arg : args) {
    text += ' ' + arg;
  }
  return text;
}

/// What one time-limited `corsa` process did.
struct BoundedResult {
  int exit_code = -1;  ///< -1 when killed by a signal (a crash)
  bool timed_out = false;
  double seconds = 0.0;      ///< wall clock: for messages only (the machine is shared)
  double cpu_seconds = 0.0;  ///< user + system time of the process and its children
  std::string err;
};

/// Seconds a single case may take before it counts as a hang. Generous: the machine running the
/// tests is shared, and every case here finishes in well under a second when it works.
inline constexpr int kCaseTimeLimit = 20;

/// User + system seconds of the children waited for so far (RUSAGE_CHILDREN).
inline double children_cpu_seconds() {
  rusage usage{};
  getrusage(RUSAGE_CHILDREN, &usage);
  const auto seconds = [](const timeval& t) { return t.tv_sec + 1e-6 * t.tv_usec; };
  return seconds(usage.ru_utime) + seconds(usage.ru_stime);
}

/// Runs `corsa args...` from the source tree with stdin from /dev/null, stdout discarded, under
/// `timeout` (exit 124 = the limit was hit; the process is killed 2 s later if it ignores TERM).
inline BoundedResult run_bounded(const std::vector<std::string>& args,
                                 int limit_seconds = kCaseTimeLimit) {
  TempDir dir;
  std::string command =
      "timeout -k 2 " + std::to_string(limit_seconds) + " " + shell_quote(CORSA_BINARY);
  for (const auto& arg : args) {
    command += ' ' + shell_quote(arg);
  }
  command += " </dev/null >/dev/null 2>" + shell_quote((dir.path() / "stderr").string());
  command = "cd " + shell_quote(CORSA_SOURCE_DIR) + " && " + command;
  const auto start = std::chrono::steady_clock::now();
  const double cpu_start = children_cpu_seconds();
  const int status = std::system(command.c_str());
  BoundedResult result;
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  // The shell, timeout(1) and corsa have all been waited for: their times are in the children's.
  result.cpu_seconds = children_cpu_seconds() - cpu_start;
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  // timeout(1) exits 124 on TERM, 137 when it had to KILL.
  result.timed_out = result.exit_code == 124 || result.exit_code == 137;
  result.err = slurp(dir.path() / "stderr");
  return result;
}

/// A `corsa` process started in the background (from the source tree, stdin /dev/null, stdout
/// discarded, stderr to `err_file`), for tests that signal or race it.
inline pid_t spawn_corsa(const std::vector<std::string>& args,
                         const std::filesystem::path& err_file) {
  std::vector<std::string> argv{CORSA_BINARY};
  argv.insert(argv.end(), args.begin(), args.end());
  std::vector<char*> pointers;
  for (auto& arg : argv) pointers.push_back(arg.data());
  pointers.push_back(nullptr);
  const pid_t child = fork();
  if (child == 0) {
    const int null = ::open("/dev/null", O_RDWR);
    const int err = ::open(err_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (chdir(CORSA_SOURCE_DIR) != 0 || null < 0 || err < 0) _exit(99);
    dup2(null, 0);
    dup2(null, 1);
    dup2(err, 2);
    execv(CORSA_BINARY, pointers.data());
    _exit(98);
  }
  return child;
}

/// Waits for a spawned process: its exit code, -1 when a signal ended it.
inline int wait_corsa(pid_t child) {
  int status = 0;
  if (waitpid(child, &status, 0) != child) return -2;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

/// True when stderr holds a located error: `file:LINE: error: ` with LINE >= 1, or
/// `file: record N: error: ` for record-based inputs (DBF/Shapefile).
inline bool has_located_error(const std::string& err) {
  static const std::regex kLocated(R"((^|\n)[^\n]+:[1-9][0-9]*: error: [^\n]+)");
  static const std::regex kRecord(R"((^|\n)[^\n]+: record [0-9]+: error: [^\n]+)");
  return std::regex_search(err, kLocated) || std::regex_search(err, kRecord);
}

/// True when stderr names `file` in an error about the file as a whole (`file: error: ...`), the
/// form used when there is no line to point at (missing file, a folder, an unwritable output).
inline bool has_file_error(const std::string& err, const std::string& file) {
  return err.find(file + ": error: ") != std::string::npos;
}

/// Names of the entries directly inside `dir`.
inline std::set<std::string> entry_names(const std::filesystem::path& dir) {
  std::set<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    names.insert(entry.path().filename().string());
  }
  return names;
}

/// scenarios/cut_in.xosc with its map and catalog folder named by absolute path, so that a copy
/// anywhere still finds them.
inline std::string cut_in_text() {
  const std::string scenarios = std::string(CORSA_SOURCE_DIR) + "/scenarios/";
  std::string text = slurp(scenarios + "cut_in.xosc");
  const auto replace = [&](const std::string& from, const std::string& to) {
    const size_t at = text.find(from);
    REQUIRE(at != std::string::npos);
    text.replace(at, from.size(), to);
  };
  replace("filepath=\"maps/", "filepath=\"" + scenarios + "maps/");
  replace("path=\"catalogs\"", "path=\"" + scenarios + "catalogs\"");
  return text;
}

/// One case of the corpus: what ran and what it did, for the failure message.
inline std::string describe(const std::string& name, const BoundedResult& result) {
  return name + ": exit " + std::to_string(result.exit_code) +
         (result.timed_out ? " (timed out)" : "") + " after " + std::to_string(result.seconds) +
         " s (" + std::to_string(result.cpu_seconds) +
         " s CPU), stderr: " + result.err.substr(0, 600);
}

/// Checks that a case either succeeded (when `may_succeed`) or was rejected the way bad input must
/// be: exit 2 and a located message. Never a signal, exit 3 (internal error) or a timeout.
inline void check_rejected_or_ok(const std::string& name, const BoundedResult& result,
                                 bool may_succeed) {
  INFO(describe(name, result));
  CHECK_FALSE(result.timed_out);
  if (may_succeed && result.exit_code == 0) {
    SUCCEED();
    return;
  }
  CHECK(result.exit_code == 2);
  CHECK(has_located_error(result.err));
}

}  // namespace corsa::test
