// The binary trajectory's writer (docs/trajectory-format.md): at each recorded tick, each entity
// whose row differs from what its previous rows predict gets a record of the differences.

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "corsa/engine/trajectory_file.h"
#include "output/trajectory_codec.h"
#include "output/trajectory_rows.h"

namespace corsa::engine {

namespace codec = detail::trajectory_codec;

struct BinaryTrajectoryRecorder::State {
  State(std::filesystem::path path, int64_t every_in)
      : file(std::move(path), true), every(every_in < 1 ? 1 : every_in) {}

  AtomicFile file;
  int64_t every;
  std::string buffer;  ///< bytes not yet written to the file
  uint32_t crc = 0;    ///< of the bytes written so far
  bool started = false;
  int64_t per_second = 0;  ///< N when the time of tick k is k / N
  double dt = 0.0;
  int64_t last_recorded = -1;
  int64_t last_frame = 0;
  std::vector<codec::EntityHistory> entities;
  /// Per entity: the inputs of its last row, when that row repeats its prediction (valid):
  /// then equal inputs mean no record, without making the row.
  struct Steady {
    bool valid = false;
    detail::RowInputs inputs;
  };
  std::vector<Steady> steady;
  std::vector<bool> road_named;
  std::string roads;  ///< road records of roads first met at this tick
  /// The entity records of this tick: the first frame_size bytes of `frame` (which only grows,
  /// so that a record is written in place without clearing its room first).
  std::vector<char> frame;
  size_t frame_size = 0;

  void start(const Simulation& simulation);
  void record(const Simulation& simulation);
  /// Appends the record of entity `index` to `frame` when its row differs from the prediction
  /// (`previous`: the index of the frame's last record, -1 before the first). An entity whose
  /// row inputs are bit for bit those of its last row, when that row repeated its prediction,
  /// is as predicted again: it is skipped without making its row.
  void encode(const Simulation& simulation, uint32_t index, int64_t& previous);
  void flush();
};

namespace {

// The N of a step dt = 1 / N (the engine then counts time as tick / N), or 0.
int64_t steps_per_second(double dt) {
  const double n = std::round(1.0 / dt);
  return n >= 1.0 && n < 1e9 && std::abs(1.0 / n - dt) <= 1e-15 * dt ? static_cast<int64_t>(n) : 0;
}

double tick_time(int64_t tick, int64_t per_second, double dt) {
  return per_second > 0 ? static_cast<double>(tick) / static_cast<double>(per_second)
                        : static_cast<double>(tick) * dt;
}

void put_string(std::string& out, uint8_t tag, uint64_t index, const std::string& text) {
  out.push_back(static_cast<char>(tag));
  codec::put_varint(out, index);
  codec::put_varint(out, text.size());
  out += text;
}

}  // namespace

void BinaryTrajectoryRecorder::State::start(const Simulation& simulation) {
  started = true;
  dt = simulation.dt();
  per_second = steps_per_second(dt);
  buffer.append(codec::kMagic);
  buffer.push_back(static_cast<char>(codec::kVersion));
  codec::put_fixed64(buffer, std::bit_cast<uint64_t>(dt));
  codec::put_varint(buffer, static_cast<uint64_t>(per_second));
  codec::put_varint(buffer, static_cast<uint64_t>(every));
  codec::put_varint(buffer, codec::zigzag(simulation.tick()));
  last_frame = simulation.tick();
}

void BinaryTrajectoryRecorder::State::encode(const Simulation& simulation, uint32_t index,
                                             int64_t& previous) {
  codec::EntityHistory& history = entities[index];
  Steady& seen = steady[index];
  const EntityState& state = simulation.state(index);
  uint32_t mask = 0;
  uint32_t raw = 0;
  // The record's body (road and lane, at most 10 + 10 bytes, then nine numbers of 10), made
  // before its head (index step, mask and raw bits, at most 10 + 5 + 5), which needs the mask.
  constexpr size_t kHead = 20;
  char body[20 + detail::kRowFields * 10];
  char* out = body;
  if (!state.placed) {
    seen.valid = false;
    if (!history.present) {
      return;
    }
    history.present = false;
    mask = codec::kPresenceBit;  // gone: nothing else follows
  } else {
    if (seen.valid && history.present && detail::same_row_inputs(seen.inputs, state)) {
      return;  // the same row as last time, which its history predicts to repeat
    }
    if (!history.present) {
      history.appear();
      mask |= codec::kPresenceBit;
    }
    const detail::RowValues row = detail::row_values(state);
    const uint32_t road = row.on_road ? state.road->road : 0;
    if (row.on_road != history.on_road || road != history.road) {
      mask |= codec::kRoadBit;
      if (row.on_road && (road >= road_named.size() || !road_named[road])) {
        road_named.resize(std::max<size_t>(road_named.size(), road + 1), false);
        road_named[road] = true;
        put_string(roads, codec::kTagRoad, road, simulation.road_id(road));
      }
      out = codec::put_varint(out, row.on_road ? uint64_t{road} + 1 : 0);
      history.on_road = row.on_road;
      history.road = road;
      history.fields[detail::kFieldS].fresh = true;
      history.fields[detail::kFieldT].fresh = true;
    }
    if (row.on_road && row.lane != history.lane) {
      mask |= codec::kLaneBit;
      out = codec::put_varint(out, codec::zigzag(int64_t{row.lane} - history.lane));
      history.lane = row.lane;
    }
    // s and t only on a road (the CSV leaves them empty off it).
    const int fields = row.on_road ? detail::kRowFields : detail::kFieldS;
    bool repeats = true;  // every field predicted to keep its value
    for (int f = 0; f < fields; ++f) {
      const detail::Scaled& v = row.fields[f];
      codec::FieldHistory& field = history.fields[f];
      if (!v.exact) {
        raw |= 1u << f;
        out = codec::put_fixed64(out, std::bit_cast<uint64_t>(v.raw));
        field.fresh = true;
        repeats = false;
        continue;
      }
      const int64_t residual = v.units - field.predicted();
      if (residual != 0) {
        mask |= 1u << f;
        out = codec::put_varint(out, codec::zigzag(residual));
      }
      field.accept(v.units);
      repeats = repeats && field.change == 0;
    }
    if (raw != 0) {
      mask |= codec::kRawBit;
    }
    // While the inputs stay these, the row stays this one and every prediction holds: the
    // next ticks need neither the row nor a record.
    seen.valid = repeats;
    if (repeats) {
      seen.inputs = detail::row_inputs(state);
    }
  }
  if (mask == 0) {
    return;  // as predicted: nothing to store
  }
  const auto body_size = static_cast<size_t>(out - body);
  if (frame.size() < frame_size + kHead + body_size) {
    frame.resize(std::max(2 * frame.size(), frame_size + kHead + sizeof body));
  }
  char* end = frame.data() + frame_size;
  end = codec::put_varint(end, static_cast<uint64_t>(index - previous));
  end = codec::put_varint(end, mask);
  if (raw != 0) {
    end = codec::put_varint(end, raw);
  }
  std::memcpy(end, body, body_size);
  frame_size = static_cast<size_t>(end - frame.data()) + body_size;
  previous = index;
}

void BinaryTrajectoryRecorder::State::record(const Simulation& simulation) {
  if (!started) {
    start(simulation);
  }
  const int64_t tick = simulation.tick();
  last_recorded = tick;
  while (entities.size() < simulation.entity_count()) {
    put_string(buffer, codec::kTagEntity, entities.size(), simulation.entity(entities.size()).name);
    entities.emplace_back();
    steady.emplace_back();
  }
  roads.clear();
  frame_size = 0;
  int64_t previous = -1;
  for (uint32_t i = 0; i < entities.size(); ++i) {
    // encode's first test, without the call: most entities of a long run stand.
    const EntityState& state = simulation.state(i);
    if (steady[i].valid && entities[i].present && state.placed &&
        detail::same_row_inputs(steady[i].inputs, state)) {
      continue;
    }
    encode(simulation, i, previous);
  }
  const double time = simulation.time();
  const bool odd_time =
      std::bit_cast<uint64_t>(time) != std::bit_cast<uint64_t>(tick_time(tick, per_second, dt));
  if (frame_size == 0 && !odd_time) {
    return;  // every present entity as predicted: the tick costs nothing
  }
  buffer += roads;
  if (odd_time) {
    buffer.push_back(static_cast<char>(codec::kTagTime));
    codec::put_fixed64(buffer, std::bit_cast<uint64_t>(time));
  }
  buffer.push_back(static_cast<char>(codec::kTagFrame));
  codec::put_varint(buffer, codec::zigzag(tick - last_frame));
  buffer.append(frame.data(), frame_size);
  codec::put_varint(buffer, 0);
  last_frame = tick;
  if (buffer.size() > (1u << 20)) {
    flush();
  }
}

void BinaryTrajectoryRecorder::State::flush() {
  crc = codec::crc32(crc, buffer);
  file.stream().write(buffer.data(), static_cast<std::streamsize>(buffer.size()));
  buffer.clear();
}

BinaryTrajectoryRecorder::BinaryTrajectoryRecorder(std::filesystem::path file, int64_t every)
    : state_(std::make_unique<State>(std::move(file), every)) {}

BinaryTrajectoryRecorder::~BinaryTrajectoryRecorder() = default;

void BinaryTrajectoryRecorder::on_step(const Simulation& simulation) {
  if (simulation.tick() % state_->every != 0) {
    return;
  }
  state_->record(simulation);
}

void BinaryTrajectoryRecorder::finish(const Simulation& simulation) {
  State& state = *state_;
  if (state.last_recorded != simulation.tick()) {
    state.record(simulation);
  }
  state.buffer.push_back(static_cast<char>(codec::kTagEnd));
  codec::put_varint(state.buffer, codec::zigzag(simulation.tick()));
  state.flush();
  std::string end;
  const uint32_t crc = state.crc;
  for (int i = 0; i < 4; ++i) {
    end.push_back(static_cast<char>((crc >> (8 * i)) & 0xff));
  }
  state.file.stream().write(end.data(), static_cast<std::streamsize>(end.size()));
  state.file.commit();
}

}  // namespace corsa::engine
