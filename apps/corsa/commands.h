#pragma once

#include <span>
#include <string>
#include <string_view>

namespace corsa::cli {

/// Process exit codes of `corsa`.
enum ExitCode : int {
  kExitOk = 0,        ///< success
  kExitFailed = 1,    ///< a scenario or test ran and failed its expectations
  kExitBadInput = 2,  ///< bad input file or bad usage: nothing was run
  kExitInternal = 3,  ///< a bug in Corsa (an unexpected exception); please report
};

/// One `corsa` subcommand. `run` receives the arguments after the subcommand name; it reports bad
/// input by throwing (InputError, UsageError) and returns an ExitCode otherwise.
struct Command {
  std::string_view name;
  std::string_view summary;
  int (*run)(std::span<const std::string> args);
};

int command_run(std::span<const std::string> args);
int command_validate(std::span<const std::string> args);
int command_map(std::span<const std::string> args);
int command_convert(std::span<const std::string> args);
int command_sweep(std::span<const std::string> args);
int command_test(std::span<const std::string> args);

/// The subcommands in the order `corsa --help` lists them.
std::span<const Command> commands();

}  // namespace corsa::cli
