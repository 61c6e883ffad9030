#include <charconv>

#include "corsa/engine/outputs.h"
#include "output/decimal_text.h"

namespace corsa::engine {
namespace {

// Decimals of the trajectory CSV's numbers (docs/engine.md, "Output files"): 1 um for lengths and
// 1 um/s for speeds, 1 nrad for angles (1 nrad of heading moves a point 5 m away by 5 nm).
// esmini writes 3 decimals; these keep every digit a test or a golden comparison could need at a
// fraction of the cost of the shortest round-trip text.
constexpr int kLengthDecimals = 6;
constexpr int kAngleDecimals = 9;

void put(std::string& out, double value, int decimals) {
  char buffer[detail::kDecimalTextMax + 1];
  char* end = detail::write_decimal(buffer, value, decimals);
  *end++ = ',';
  out.append(buffer, end);
}

}  // namespace

TrajectoryRecorder::TrajectoryRecorder(std::filesystem::path file, int64_t every)
    : file_(std::move(file)), every_(every < 1 ? 1 : every) {
  buffer_ = kTrajectoryHeader;
}

void TrajectoryRecorder::append_rows(const Simulation& simulation, std::string& out) {
  // The time is the same on every row of the step: its exact text (shortest round-trip, so that
  // rows can be matched to steps) is made once.
  char time[detail::kDecimalTextMax + 1];
  char* time_end = detail::write_exact(time, simulation.time());
  *time_end++ = ',';
  for (size_t i = 0; i < simulation.entity_count(); ++i) {
    const EntityState& state = simulation.state(i);
    if (!state.placed) {
      continue;  // not added yet or deleted (AddEntityAction, DeleteEntityAction, traffic)
    }
    out.append(time, time_end);
    out += simulation.entity(i).name;
    out.push_back(',');
    put(out, state.pose.x, kLengthDecimals);
    put(out, state.pose.y, kLengthDecimals);
    put(out, state.pose.z, kLengthDecimals);
    put(out, state.pose.h, kAngleDecimals);
    put(out, state.pose.p, kAngleDecimals);
    put(out, state.pose.r, kAngleDecimals);
    put(out, state.speed, kLengthDecimals);
    if (state.road) {
      out += simulation.road_id(state.road->road);
      char lane[16];
      lane[0] = ',';
      char* lane_end = std::to_chars(lane + 1, lane + sizeof lane - 1, state.road->lane).ptr;
      *lane_end++ = ',';
      out.append(lane, lane_end);
      put(out, state.road->s, kLengthDecimals);
      char buffer[detail::kDecimalTextMax];
      out.append(buffer, detail::write_decimal(buffer, state.road->t, kLengthDecimals));
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
