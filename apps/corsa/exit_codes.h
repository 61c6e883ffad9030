#pragma once

// Exit codes of `corsa` and the one place where what a command throws becomes a message and an
// exit code: the executable's commands and the plugin's alike (so that nothing is thrown across
// the plugin boundary, plugin_api.h).

#include <functional>
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

/// Runs `body` (command `command`, e.g. "map render"; empty outside any command) and returns its
/// exit code, or prints what it threw to stderr and returns:
///   UsageError                "corsa CMD: error: ... (see 'corsa CMD --help')"     2
///   InputError                its located diagnostic, "file:line: error: ..."      2
///   filesystem_error          "corsa CMD: error: ..." (an output that cannot be
///                             written: permissions, disk full; the user's to fix)  2
///   std::bad_alloc            "corsa: error: out of memory"                        3
///   any other std::exception  "corsa: internal error: ... (this is a bug)"         3
int guarded(std::string_view command, const std::function<int()>& body);

/// The same for a command function and its arguments.
int guarded(std::string_view command, int (*body)(std::span<const std::string>),
            std::span<const std::string> args);

}  // namespace corsa::cli
