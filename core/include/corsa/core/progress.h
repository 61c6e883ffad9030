#pragma once

#include <chrono>
#include <cstdio>
#include <mutex>
#include <string>

namespace corsa {

/// True when `stream` (stderr by default) is an interactive terminal.
bool is_terminal(std::FILE* stream = stderr);

/// A one-line progress bar with rate and ETA, redrawn at most ~10 times a second on stderr.
///
/// Shown only when enabled and stderr is a terminal, so CI logs and pipes stay quiet; `--quiet`
/// passes enabled = false. update() is thread-safe (sweeps report from worker threads).
class ProgressBar {
 public:
  ProgressBar(std::string label, double total, bool enabled = true, std::FILE* stream = stderr);
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;
  ~ProgressBar();

  /// Sets the amount done (same unit as total) and redraws when due.
  void update(double done);
  /// Adds to the amount done.
  void advance(double amount = 1.0);
  /// Changes the total (e.g. once a scenario is loaded and its own end is known).
  void set_total(double total);
  /// Starts over with another label and total (the next phase of a command, e.g. encoding a
  /// video after a run); the elapsed time restarts too.
  void restart(std::string label, double total);
  /// Draws the final state and ends the line. Called by the destructor if not before.
  void finish();
  /// All done: the bar is full, drawn and ended (e.g. a run that reached its end between two
  /// updates).
  void complete();

  bool visible() const { return visible_; }
  /// The bar as text for a given state (exposed for tests): label, bar, percent, ETA.
  static std::string render(const std::string& label, double done, double total,
                            double elapsed_seconds, int width);

 private:
  void draw_locked(bool force);

  std::string label_;
  double total_;
  double done_ = 0.0;
  bool visible_;
  bool finished_ = false;
  std::FILE* stream_;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_draw_;
  std::mutex mutex_;
};

}  // namespace corsa
