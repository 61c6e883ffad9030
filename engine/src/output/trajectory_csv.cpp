#include <charconv>

#include "corsa/core/strings.h"
#include "corsa/engine/outputs.h"

namespace corsa::engine {
namespace {

// Shortest round-trip text, as format_double, appended without temporaries: this is the hot
// path of a recorded run.
void put(std::string& out, double value) {
  value += 0.0;  // -0 prints as 0
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  out.append(buffer, result.ptr);
  out.push_back(',');
}

}  // namespace

TrajectoryRecorder::TrajectoryRecorder(std::filesystem::path file, int64_t every)
    : file_(std::move(file)), every_(every < 1 ? 1 : every) {
  buffer_ = kTrajectoryHeader;
}

void TrajectoryRecorder::append_rows(const Simulation& simulation, std::string& out) {
  const double time = simulation.time();
  for (size_t i = 0; i < simulation.entity_count(); ++i) {
    const EntityState& state = simulation.state(i);
    if (!state.placed) {
      continue;  // not added yet or deleted (AddEntityAction, DeleteEntityAction, traffic)
    }
    put(out, time);
    out += simulation.entity(i).name;
    out.push_back(',');
    put(out, state.pose.x);
    put(out, state.pose.y);
    put(out, state.pose.z);
    put(out, state.pose.h);
    put(out, state.pose.p);
    put(out, state.pose.r);
    put(out, state.speed);
    if (state.road) {
      out += simulation.road_id(state.road->road);
      out.push_back(',');
      out += std::to_string(state.road->lane);
      out.push_back(',');
      put(out, state.road->s);
      char buffer[32];
      const auto result = std::to_chars(buffer, buffer + sizeof buffer, state.road->t + 0.0);
      out.append(buffer, result.ptr);
    } else {
      out += ",,,";
    }
    out.push_back('\n');
  }
}

void TrajectoryRecorder::on_step(const Simulation& simulation) {
  if (simulation.tick() % every_ != 0) {
    return;
  }
  append_rows(simulation, buffer_);
  last_recorded_ = simulation.tick();
  if (buffer_.size() > (1u << 20)) {
    flush();
  }
}

void TrajectoryRecorder::flush() {
  file_.stream().write(buffer_.data(), static_cast<std::streamsize>(buffer_.size()));
  buffer_.clear();
}

void TrajectoryRecorder::finish(const Simulation& simulation) {
  if (last_recorded_ != simulation.tick()) {
    append_rows(simulation, buffer_);
    last_recorded_ = simulation.tick();
  }
  flush();
  file_.commit();
}

}  // namespace corsa::engine
