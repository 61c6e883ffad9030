// What `corsa` shows on a terminal: the progress bar reaches the scenario's own end, and the
// preview video's encoding has a bar of its own. The binary runs with its output on a
// pseudo-terminal (forkpty), as in an interactive shell.

#include <pty.h>
#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <string>
#include <vector>

#include "temp_dir.h"

namespace {

struct TerminalResult {
  int exit_code = -1;
  std::string screen;  ///< everything written to the terminal, stdout and stderr alike
};

TerminalResult run_on_terminal(const std::vector<std::string>& args) {
  int master = -1;
  const pid_t child = forkpty(&master, nullptr, nullptr, nullptr);
  REQUIRE(child >= 0);
  if (child == 0) {
    if (chdir(CORSA_SOURCE_DIR) != 0) {
      _exit(99);
    }
    std::vector<char*> argv{const_cast<char*>(CORSA_BINARY)};
    for (const std::string& arg : args) {
      argv.push_back(const_cast<char*>(arg.c_str()));
    }
    argv.push_back(nullptr);
    execv(CORSA_BINARY, argv.data());
    _exit(98);
  }
  TerminalResult result;
  char buffer[4096];
  for (;;) {
    const ssize_t n = read(master, buffer, sizeof buffer);
    if (n <= 0) {
      break;  // EIO once the child has closed the terminal
    }
    result.screen.append(buffer, static_cast<size_t>(n));
  }
  int status = 0;
  waitpid(child, &status, 0);
  close(master);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

}  // namespace

TEST_CASE("the run's progress bar ends at the scenario's own end, not the default cap",
          "[cli][e2e][progress]") {
  // cut_in_city stops at 20 s by its SimulationTime stop trigger; --duration is not given (3600).
  const TerminalResult run = run_on_terminal({"run", "scenarios/demo/cut_in_city.xosc"});
  INFO(run.screen);
  CHECK(run.exit_code == 0);
  CHECK_THAT(run.screen, Catch::Contains("100% done in"));
  CHECK_THAT(run.screen, !Catch::Contains("] 1%"));
}

TEST_CASE("a dataset run shows the preview encoding and counts all of its time",
          "[cli][e2e][progress][dataset]") {
  corsa::test::TempDir dir;
  const TerminalResult run = run_on_terminal(
      {"run", "scenarios/demo/cut_in_city.xosc", "--rig", "tests/collect/fixtures/small_rig.xml",
       "-o", (dir.path() / "d").string(), "--duration", "0.5", "--preview"});
  INFO(run.screen);
  CHECK(run.exit_code == 0);
  CHECK_THAT(run.screen, Catch::Contains("run [") && Catch::Contains("100% done in"));
  CHECK_THAT(run.screen, Catch::Contains("preview video ["));
  CHECK_THAT(run.screen, Catch::Contains("s wall in all"));
}
