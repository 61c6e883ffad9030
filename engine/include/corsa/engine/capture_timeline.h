#pragma once

// The capture timeline (DESIGN.md, "Data flow of one run", step 4): which sensors take a frame at
// which tick. Each sensor's rate becomes capture ticks on the integer tick grid with exact
// rational arithmetic, so there is no drift over long runs: with the step dt and the rate f both
// written as exact fractions, frame k of a window opened at tick s is due at
//   tick(k) = s + ceil(k / (f dt))
// computed in integers. A rate of 3 Hz with dt = 0.01 s gives ticks 0, 34, 67, 100, 134, ...
// The grid is anchored at tick 0 (s = 0) whenever a window opens: a window opened at tick t
// captures from the first grid tick at or after t, so sensors of the same rate always capture
// at the same ticks (synchronised frames), across windows and rate changes.
//
// Windows are opened and closed by the scenario with CustomCommandAction type="corsa:capture"
// (syntax in docs/datasets.md):
//   start [sensors=NAME,NAME...] [rate=HZ]
//   stop [sensors=NAME,NAME...]
// Without any corsa:capture action in the scenario the whole run is captured. A window opened by
// an action of the Init is open at tick 0; an action started while the triggers of tick t are
// evaluated (the state at t has already been seen) opens the window at tick t + 1, and a stop
// there means nothing after tick t is captured.

#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "corsa/core/diagnostic.h"
#include "corsa/engine/simulation.h"
#include "corsa/engine/world_snapshot.h"

namespace corsa::xosc {
struct Scenario;
struct UserDefinedAction;
}  // namespace corsa::xosc

namespace corsa::engine {

inline constexpr std::string_view kCaptureCommandType = "corsa:capture";

/// A sensor as the timeline sees it: a name and its default capture rate.
struct CaptureSensor {
  std::string name;
  double rate_hz = 10.0;
};

/// The content of a corsa:capture action.
struct CaptureCommand {
  bool start = true;
  bool every_sensor = true;          ///< no sensors= list
  std::vector<std::string> sensors;  ///< the rig's sensors the sensors= list names
  std::optional<double> rate_hz;     ///< start only: this rate instead of each sensor's own
};

/// Parses a corsa:capture action's content. Throws InputError located at the action for an
/// unknown word or a rate that is not a positive number. A sensor the rig does not have (a rig
/// made for another scenario) is left out with a warning located at the action (once per
/// action and name), suggesting the nearest name.
CaptureCommand parse_capture_command(const xosc::UserDefinedAction& action,
                                     std::span<const std::string> known_sensors,
                                     Diagnostics& diagnostics);

/// Every corsa:capture action of the scenario (Init and all Events), in document order.
std::vector<const xosc::UserDefinedAction*> find_capture_actions(const xosc::Scenario& scenario);

/// An exact fraction num / den (den > 0) from a decimal number: the shortest decimal (up to 9
/// places) that prints as the same double, so 0.01 is 1/100 and 3.3 is 33/10.
struct Fraction {
  int64_t num = 0;
  int64_t den = 1;
};
Fraction exact_fraction(double value);

/// Ticks per frame as a fraction: 1 / (rate dt). Frame k of a window opened at `start` is due at
/// start + ceil(k * period.num / period.den).
Fraction capture_period(double rate_hz, double dt);
int64_t capture_tick(int64_t start, Fraction period, int64_t k);
/// The first frame k whose tick capture_tick(0, period, k) is at or after `tick` (>= 0).
int64_t first_frame_at_or_after(int64_t tick, Fraction period);

/// One sensor's open window: from its opening tick at one rate.
struct CaptureWindow {
  std::string sensor;
  int64_t open_tick = 0;
  int64_t close_tick = -1;  ///< last tick that could be captured; -1 while open
  double rate_hz = 0.0;
};

/// Follows the simulation and calls the sink with the sensors due at each tick.
class CaptureTimeline final : public SimulationObserver {
 public:
  /// Validates every corsa:capture action of the scenario against `sensors` (InputError located
  /// at the first bad one). Throws InputError for a rate that is not positive or finite.
  CaptureTimeline(std::vector<CaptureSensor> sensors, const xosc::Scenario& scenario, double dt,
                  Diagnostics& diagnostics);

  /// Registers the observer and the corsa:capture handler. `sink` must outlive the simulation's
  /// run; `adjust` (optional) may change the snapshot before the sink sees it (environment
  /// overrides, extra objects).
  void attach(Simulation& simulation, CaptureSink& sink,
              std::function<void(WorldSnapshot&)> adjust = {});

  /// The sensors due at `tick`, in sensor order; advances their schedules. Ticks must be
  /// presented in increasing order (on_step does that).
  std::vector<std::string> take_due(int64_t tick);
  /// Applies a command issued while tick `tick` was evaluated (Init: tick -1, so windows open at
  /// tick 0).
  void apply(const CaptureCommand& command, int64_t tick);

  void on_step(const Simulation& simulation) override;

  /// Every window so far (closed and open), in the order they were opened.
  std::vector<CaptureWindow> windows() const;
  int64_t captures() const { return captures_; }

 private:
  struct Schedule {
    CaptureSensor sensor;
    bool open = false;
    int64_t start = 0;
    Fraction period;
    int64_t next_frame = 0;
    int64_t next_tick = 0;
    size_t window = 0;
  };
  void open(Schedule& schedule, int64_t tick, std::optional<double> rate);
  void close(Schedule& schedule, int64_t tick);

  std::vector<Schedule> schedules_;
  std::vector<std::string> names_;
  std::vector<CaptureWindow> windows_;
  double dt_;
  Diagnostics& diagnostics_;
  CaptureSink* sink_ = nullptr;
  std::function<void(WorldSnapshot&)> adjust_;
  WorldSnapshot snapshot_;
  int64_t captures_ = 0;
  int64_t last_tick_ = -1;
};

}  // namespace corsa::engine
