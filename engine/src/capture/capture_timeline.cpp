// The capture timeline: exact rational capture ticks per sensor and corsa:capture windows
// (see corsa/engine/capture_timeline.h and docs/datasets.md).

#include "corsa/engine/capture_timeline.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "corsa/core/strings.h"
#include "corsa/xosc/scenario.h"

namespace corsa::engine {
namespace {

// 128-bit intermediates: products of two 1e9-denominators would overflow int64.
__extension__ typedef __int128 Wide;

Wide wide_gcd(Wide a, Wide b) {
  a = a < 0 ? -a : a;
  b = b < 0 ? -b : b;
  while (b != 0) {
    const Wide r = a % b;
    a = b;
    b = r;
  }
  return a;
}

bool fits(Wide value) {
  return value <= std::numeric_limits<int64_t>::max() &&
         value >= std::numeric_limits<int64_t>::min();
}

void collect_event_actions(const xosc::Scenario& scenario,
                           std::vector<const xosc::UserDefinedAction*>& out) {
  for (const xosc::Action* action : xosc::event_actions(scenario.storyboard)) {
    const auto* user = std::get_if<xosc::UserDefinedAction>(&action->action);
    if (user != nullptr && user->type == kCaptureCommandType) {
      out.push_back(user);
    }
  }
}

std::vector<std::string> parse_sensor_list(std::string_view list,
                                           std::span<const std::string> known,
                                           const xosc::UserDefinedAction& action,
                                           Diagnostics& diagnostics) {
  std::vector<std::string> sensors;
  for (const std::string_view item : split(list, ',')) {
    const std::string name(trim(item));
    if (name.empty()) {
      throw InputError(action.source.error(
          "corsa:capture: empty sensor name in 'sensors=" + std::string(list) + "'"));
    }
    if (std::find(known.begin(), known.end(), name) == known.end()) {
      std::string names;
      for (const std::string& k : known) {
        names += (names.empty() ? "" : ", ") + k;
      }
      diagnostics.add_once(
          "capture-unknown-sensor:" + std::to_string(action.source.line) + ":" + name,
          action.source.warning("corsa:capture: the rig has no sensor '" + clip(name) + "'" +
                                did_you_mean(name, known) + " (sensors: " + names +
                                "); the action leaves it out"));
      continue;
    }
    if (std::find(sensors.begin(), sensors.end(), name) == sensors.end()) {
      sensors.push_back(name);
    }
  }
  return sensors;
}

std::vector<std::string_view> words_of(std::string_view text) {
  std::vector<std::string_view> words;
  size_t i = 0;
  while (i < text.size()) {
    while (i < text.size() && std::isspace(static_cast<unsigned char>(text[i])) != 0) {
      ++i;
    }
    size_t j = i;
    while (j < text.size() && std::isspace(static_cast<unsigned char>(text[j])) == 0) {
      ++j;
    }
    if (j > i) {
      words.push_back(text.substr(i, j - i));
    }
    i = j;
  }
  return words;
}

}  // namespace

CaptureCommand parse_capture_command(const xosc::UserDefinedAction& action,
                                     std::span<const std::string> known_sensors,
                                     Diagnostics& diagnostics) {
  const std::vector<std::string_view> words = words_of(action.content);
  const std::string usage =
      " (expected 'start [sensors=NAME,...] [rate=HZ]' or 'stop [sensors=NAME,...]')";
  if (words.empty() || (words[0] != "start" && words[0] != "stop")) {
    throw InputError(action.source.error("corsa:capture: content '" + action.content +
                                         "' does not begin with start or stop" + usage));
  }
  CaptureCommand command;
  command.start = words[0] == "start";
  bool have_sensors = false;
  for (size_t i = 1; i < words.size(); ++i) {
    const std::string_view word = words[i];
    const size_t eq = word.find('=');
    const std::string_view key = word.substr(0, eq);
    const std::string_view value = eq == std::string_view::npos ? "" : word.substr(eq + 1);
    if (key == "sensors" && eq != std::string_view::npos && !have_sensors) {
      command.sensors = parse_sensor_list(value, known_sensors, action, diagnostics);
      command.every_sensor = false;
      have_sensors = true;
    } else if (key == "rate" && eq != std::string_view::npos && command.start && !command.rate_hz) {
      const std::optional<double> rate = parse_double(value);
      if (!rate || !(*rate > 0.0) || !std::isfinite(*rate) || *rate > 1e6) {
        throw InputError(action.source.error("corsa:capture: rate '" + std::string(value) +
                                             "' is not a positive number of Hz (at most 1e6)"));
      }
      command.rate_hz = *rate;
    } else {
      throw InputError(action.source.error("corsa:capture: unexpected '" + std::string(word) +
                                           "' in '" + action.content + "'" + usage));
    }
  }
  return command;
}

std::vector<const xosc::UserDefinedAction*> find_capture_actions(const xosc::Scenario& scenario) {
  std::vector<const xosc::UserDefinedAction*> out;
  for (const xosc::UserDefinedAction& action : scenario.storyboard.init.user_defined_actions) {
    if (action.type == kCaptureCommandType) {
      out.push_back(&action);
    }
  }
  collect_event_actions(scenario, out);
  return out;
}

Fraction exact_fraction(double value) {
  int64_t scale = 1;
  for (int places = 0; places <= 9; ++places, scale *= 10) {
    const double scaled = std::round(value * static_cast<double>(scale));
    if (scaled / static_cast<double>(scale) == value || places == 9) {
      const auto num = static_cast<int64_t>(scaled);
      const int64_t g = std::gcd(num, scale);
      return {num / std::max<int64_t>(g, 1), scale / std::max<int64_t>(g, 1)};
    }
  }
  return {0, 1};  // not reached: the loop returns at places == 9
}

Fraction capture_period(double rate_hz, double dt) {
  const Fraction rate = exact_fraction(rate_hz);
  const Fraction step = exact_fraction(dt);
  // period = 1 / (rate * dt) ticks = (rate.den * step.den) / (rate.num * step.num)
  Wide num = static_cast<Wide>(rate.den) * step.den;
  Wide den = static_cast<Wide>(rate.num) * step.num;
  if (den <= 0) {
    throw std::invalid_argument("capture_period: rate and step must be positive");
  }
  const Wide g = wide_gcd(num, den);
  num /= g;
  den /= g;
  if (!fits(num) || !fits(den)) {
    throw std::invalid_argument("capture_period: rate and step too finely divided");
  }
  return {static_cast<int64_t>(num), static_cast<int64_t>(den)};
}

int64_t first_frame_at_or_after(int64_t tick, Fraction period) {
  if (tick <= 0) {
    return 0;
  }
  // ceil(k num / den) >= tick  <=>  k num / den > tick - 1  <=>  k > (tick - 1) den / num.
  const Wide before = static_cast<Wide>(tick - 1) * period.den / period.num;
  return static_cast<int64_t>(before) + 1;
}

int64_t capture_tick(int64_t start, Fraction period, int64_t k) {
  const Wide product = static_cast<Wide>(k) * period.num;
  const Wide ceil = (product + period.den - 1) / period.den;  // k, num >= 0
  return start + static_cast<int64_t>(ceil);
}

CaptureTimeline::CaptureTimeline(std::vector<CaptureSensor> sensors, const xosc::Scenario& scenario,
                                 double dt, Diagnostics& diagnostics)
    : dt_(dt), diagnostics_(diagnostics) {
  for (CaptureSensor& sensor : sensors) {
    if (!(sensor.rate_hz > 0.0) || !std::isfinite(sensor.rate_hz)) {
      throw InputError(make_error("", 0,
                                  "sensor '" + sensor.name + "': capture rate " +
                                      format_double(sensor.rate_hz) + " Hz is not positive"));
    }
    names_.push_back(sensor.name);
    Schedule schedule;
    schedule.sensor = std::move(sensor);
    schedules_.push_back(std::move(schedule));
  }
  const auto actions = find_capture_actions(scenario);
  for (const xosc::UserDefinedAction* action : actions) {
    parse_capture_command(*action, names_, diagnostics_);  // located errors before the run
  }
  if (actions.empty()) {
    for (Schedule& schedule : schedules_) {
      open(schedule, 0, std::nullopt);
    }
  }
}

void CaptureTimeline::attach(Simulation& simulation, CaptureSink& sink,
                             std::function<void(WorldSnapshot&)> adjust) {
  sink_ = &sink;
  adjust_ = std::move(adjust);
  simulation.add_observer(*this);
  simulation.set_custom_command_handler(
      std::string(kCaptureCommandType),
      [this](const xosc::UserDefinedAction& action, const Simulation& sim) {
        // Init actions run before the tick-0 state is observed: they open windows at tick 0.
        const int64_t tick = last_tick_ < 0 ? -1 : sim.tick();
        apply(parse_capture_command(action, names_, diagnostics_), tick);
      });
}

void CaptureTimeline::open(Schedule& schedule, int64_t tick, std::optional<double> rate) {
  const double hz = rate.value_or(schedule.sensor.rate_hz);
  Fraction period = capture_period(hz, dt_);
  if (period.num < period.den) {
    diagnostics_.add_once(
        "capture-rate-above-step:" + schedule.sensor.name,
        make_warning("", 0,
                     "sensor '" + schedule.sensor.name + "': rate " + format_double(hz) +
                         " Hz is above the step rate; captured every step"));
    period = {1, 1};
  }
  if (schedule.open) {
    close(schedule, tick - 1);
  }
  schedule.open = true;
  // Frames stay on the rate's grid anchored at tick 0, so sensors of one rate capture at the same
  // ticks whenever their windows open: the first frame is the first grid tick at or after `tick`.
  schedule.start = 0;
  schedule.period = period;
  schedule.next_frame = first_frame_at_or_after(tick, period);
  schedule.next_tick = capture_tick(0, period, schedule.next_frame);
  schedule.window = windows_.size();
  windows_.push_back({schedule.sensor.name, tick, -1, hz});
}

void CaptureTimeline::close(Schedule& schedule, int64_t tick) {
  if (schedule.open) {
    schedule.open = false;
    windows_[schedule.window].close_tick = tick;
  }
}

void CaptureTimeline::apply(const CaptureCommand& command, int64_t tick) {
  for (Schedule& schedule : schedules_) {
    const bool named =
        command.every_sensor || std::find(command.sensors.begin(), command.sensors.end(),
                                          schedule.sensor.name) != command.sensors.end();
    if (!named) {
      continue;
    }
    if (command.start) {
      open(schedule, tick + 1, command.rate_hz);
    } else {
      close(schedule, tick);
    }
  }
}

std::vector<std::string> CaptureTimeline::take_due(int64_t tick) {
  std::vector<std::string> due;
  for (Schedule& schedule : schedules_) {
    if (!schedule.open) {
      continue;
    }
    // A tick the caller skipped (it never does in a run) must not leave the schedule behind.
    while (schedule.next_tick < tick) {
      schedule.next_tick = capture_tick(schedule.start, schedule.period, ++schedule.next_frame);
    }
    if (schedule.next_tick == tick) {
      due.push_back(schedule.sensor.name);
      schedule.next_tick = capture_tick(schedule.start, schedule.period, ++schedule.next_frame);
    }
  }
  return due;
}

void CaptureTimeline::on_step(const Simulation& simulation) {
  const int64_t tick = simulation.tick();
  last_tick_ = tick;
  const std::vector<std::string> due = take_due(tick);
  if (due.empty() || sink_ == nullptr) {
    return;
  }
  simulation.fill_snapshot(snapshot_);
  if (adjust_) {
    adjust_(snapshot_);
  }
  sink_->capture(snapshot_, due);
  ++captures_;
}

std::vector<CaptureWindow> CaptureTimeline::windows() const { return windows_; }

}  // namespace corsa::engine
