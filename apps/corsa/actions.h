#pragma once

// Subcommands made of actions (`corsa map info`, `corsa record export`): one dispatch and one
// --help layout for all of them.

#include <span>
#include <string>
#include <string_view>

namespace corsa::cli {

/// One action of a subcommand. `run` receives the arguments after the action name and behaves as
/// a Command's run (commands.h).
struct Action {
  std::string_view name;
  std::string_view summary;
  int (*run)(std::span<const std::string> args);
};

/// A subcommand made of actions, and the text its --help prints around the list of them.
struct ActionMenu {
  std::string_view command;      ///< e.g. "map"
  std::string_view synopsis;     ///< after "corsa <command> ", e.g. "ACTION MAP.xodr [options]"
  std::string_view description;  ///< one paragraph under the usage line
  std::span<const Action> actions;
};

/// Runs the action that args[0] names with the arguments after it. No arguments: the help on
/// standard error and kExitBadInput; --help or -h: the help on standard output and kExitOk; an
/// unknown action: UsageError naming the actions there are.
int run_action(const ActionMenu& menu, std::span<const std::string> args);

}  // namespace corsa::cli
