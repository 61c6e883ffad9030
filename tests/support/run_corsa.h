#pragma once

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "temp_dir.h"

namespace corsa::test {

/// What one `corsa` process printed and returned.
struct ProcessResult {
  int exit_code = -1;
  std::string out;
  std::string err;
};

inline std::string shell_quote(const std::string& text) {
  std::string quoted = "'";
  for (char c : text) {
    quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  }
  return quoted + "'";
}

inline std::string slurp(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream content;
  content << in.rdbuf();
  return content.str();
}

/// Runs the built `corsa` binary (CORSA_BINARY) with `args`, stdin from `input` (empty: /dev/null),
/// from the source tree, and captures its outputs and exit code.
inline ProcessResult run_corsa(const std::vector<std::string>& args,
                               const std::string& input = {}) {
  TempDir dir;
  std::string command = shell_quote(CORSA_BINARY);
  for (const auto& arg : args) {
    command += ' ' + shell_quote(arg);
  }
  if (input.empty()) {
    command += " </dev/null";
  } else {
    std::ofstream(dir.path() / "stdin") << input;
    command += " <" + shell_quote((dir.path() / "stdin").string());
  }
  command += " >" + shell_quote((dir.path() / "stdout").string());
  command += " 2>" + shell_quote((dir.path() / "stderr").string());
  command = "cd " + shell_quote(CORSA_SOURCE_DIR) + " && " + command;
  const int status = std::system(command.c_str());
  ProcessResult result;
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  result.out = slurp(dir.path() / "stdout");
  result.err = slurp(dir.path() / "stderr");
  return result;
}

}  // namespace corsa::test
