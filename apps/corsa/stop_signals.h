#pragma once

// SIGINT and SIGTERM as a request to stop cleanly: while a StopSignals object lives, the signals
// only set a flag (nothing else is safe in a handler), and long runs ask for it between units of
// work (a dataset run between steps, a sweep before each variant), finish what is in progress
// and end with 128 + the signal's number. Used by `corsa run --rig` and `corsa sweep`.

#include <optional>
#include <string>

namespace corsa::cli {

class StopSignals {
 public:
  /// Installs the handlers (and clears an earlier request); the destructor restores the
  /// previous ones.
  StopSignals();
  StopSignals(const StopSignals&) = delete;
  StopSignals& operator=(const StopSignals&) = delete;
  ~StopSignals();

  /// Why to stop ("interrupted by SIGINT" or "... SIGTERM"), once a signal came.
  static std::optional<std::string> reason();
  /// The exit code for a stopped run: 128 + the signal's number (130 for SIGINT).
  static int exit_code();
};

}  // namespace corsa::cli
