#pragma once

#include <span>
#include <string>
#include <string_view>

#include "exit_codes.h"

namespace corsa::cli {

/// One `corsa` subcommand. `run` receives the arguments after the subcommand name; it reports bad
/// input by throwing (InputError, UsageError; see guarded()) and returns an ExitCode otherwise.
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
int command_record(std::span<const std::string> args);

/// The subcommands in the order `corsa --help` lists them.
std::span<const Command> commands();

}  // namespace corsa::cli
