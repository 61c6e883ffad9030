#include "stop_signals.h"

#include <csignal>

namespace corsa::cli {
namespace {

// The one piece of process-wide state: a signal can only reach the run through a flag.
volatile std::sig_atomic_t& stop_signal() {
  static volatile std::sig_atomic_t signal_number = 0;
  return signal_number;
}

extern "C" void on_stop_signal(int number) { stop_signal() = number; }

struct sigaction& previous(int number) {
  static struct sigaction previous_int {};
  static struct sigaction previous_term {};
  return number == SIGINT ? previous_int : previous_term;
}

}  // namespace

StopSignals::StopSignals() {
  stop_signal() = 0;
  struct sigaction action {};
  action.sa_handler = on_stop_signal;
  sigemptyset(&action.sa_mask);
  for (const int number : {SIGINT, SIGTERM}) {
    sigaction(number, &action, &previous(number));
  }
}

StopSignals::~StopSignals() {
  for (const int number : {SIGINT, SIGTERM}) {
    sigaction(number, &previous(number), nullptr);
  }
}

std::optional<std::string> StopSignals::reason() {
  const int number = stop_signal();
  if (number == 0) {
    return std::nullopt;
  }
  return std::string("interrupted by ") + (number == SIGTERM ? "SIGTERM" : "SIGINT");
}

int StopSignals::exit_code() { return 128 + static_cast<int>(stop_signal()); }

}  // namespace corsa::cli
