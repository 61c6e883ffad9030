#include <charconv>
#include <cstring>
#include <string_view>

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

template <int Decimals>
char* put(char* out, double value) {
  out = detail::write_fixed<Decimals>(out, value);
  *out++ = ',';
  return out;
}

char* put(char* out, std::string_view text) {
  std::memcpy(out, text.data(), text.size());
  return out + text.size();
}

}  // namespace

TrajectoryRecorder::TrajectoryRecorder(std::filesystem::path file, int64_t every)
    : file_(std::move(file)), every_(every < 1 ? 1 : every) {
  buffer_ = kTrajectoryHeader;
}

void TrajectoryRecorder::append_rows(const Simulation& simulation, std::string& out) {
  // The time is the same on every row of the step: its exact text (shortest round-trip, so that
  // rows can be matched to steps) is made once.
  char time_text[detail::kDecimalTextMax + 1];
  char* time_end = detail::write_exact(time_text, simulation.time());
  *time_end++ = ',';
  const std::string_view time(time_text, static_cast<size_t>(time_end - time_text));
  for (size_t i = 0; i < simulation.entity_count(); ++i) {
    const EntityState& state = simulation.state(i);
    if (!state.placed) {
      continue;  // not added yet or deleted (AddEntityAction, DeleteEntityAction, traffic)
    }
    const std::string& name = simulation.entity(i).name;
    const std::string* road = state.road ? &simulation.road_id(state.road->road) : nullptr;
    // The row is written in place (one resize instead of an append per field, which was a
    // third of the row's cost): room for the strings, ten numbers, the lane and separators.
    const size_t room = time.size() + name.size() + (road ? road->size() : 0) +
                        10 * (detail::kDecimalTextMax + 1) + 16;
    const size_t start = out.size();
    out.resize(start + room);
    char* p = out.data() + start;
    p = put(p, time);
    p = put(p, name);
    *p++ = ',';
    p = put<kLengthDecimals>(p, state.pose.x);
    p = put<kLengthDecimals>(p, state.pose.y);
    p = put<kLengthDecimals>(p, state.pose.z);
    p = put<kAngleDecimals>(p, state.pose.h);
    p = put<kAngleDecimals>(p, state.pose.p);
    p = put<kAngleDecimals>(p, state.pose.r);
    p = put<kLengthDecimals>(p, state.speed);
    if (road) {
      p = put(p, *road);
      *p++ = ',';
      p = std::to_chars(p, p + 12, state.road->lane).ptr;
      *p++ = ',';
      p = put<kLengthDecimals>(p, state.road->s);
      p = detail::write_fixed<kLengthDecimals>(p, state.road->t);
    } else {
      p = put(p, ",,,");
    }
    *p++ = '\n';
    out.resize(static_cast<size_t>(p - out.data()));
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
