// The binary trajectory's writer (docs/trajectory-format.md): at each recorded tick, each entity
// whose row differs from what its previous rows predict gets a record of the differences.

#include <algorithm>
#include <array>
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
  /// The writer's side of an entity's history (codec::EntityHistory's predictions, kept as the
  /// value each field is predicted to take next, so that a moving entity's field costs a
  /// subtraction and no test of its history's state).
  struct Track {
    bool present = false;
    bool on_road = false;
    uint32_t road = 0;
    int lane = 0;
    uint32_t fresh = codec::kFieldBits;  ///< fields whose history starts afresh (predicted 0)
    /// Fields whose last value came from the bits in `bits` and repeated the one before: while
    /// the bits stay, the field is as predicted and keeps its history (z, pitch and roll on a
    /// flat road, a steady speed), without scaling it again.
    uint32_t still = 0;
    std::array<uint64_t, detail::kRowFields> bits{};
    std::array<int64_t, detail::kRowFields> last{};  ///< the value last taken
    std::array<int64_t, detail::kRowFields> next{};  ///< last + its change: the prediction
  };
  std::vector<Track> entities;
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
  /// is as predicted again: it is skipped without making its row. `state` is the entity's.
  void encode(const Simulation& simulation, uint32_t index, const EntityState& state,
              int64_t& previous);
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

namespace {

// Codes an entity's numeric fields into its record's body, one field at a time with the field's
// number known when compiled (its decimals and mask bit constants, no loop over a table): as
// the loop it replaces, about a tenth fewer instructions per row. `Track` is
// BinaryTrajectoryRecorder::State::Track.
template <class Track>
struct FieldCoder {
  Track& track;
  uint32_t& raw;
  uint32_t& mask;
  char* out;
  bool repeats = true;  ///< every field so far predicted to keep its value

  template <int... F>
  void fields(const double (&values)[detail::kRowFields]) {
    (field<F>(values[F]), ...);
  }

  template <int F>
  void field(double value) {
    constexpr uint32_t kBit = 1u << F;
    const uint64_t bits = std::bit_cast<uint64_t>(value);
    if ((track.still & kBit) != 0 && bits == track.bits[F]) {
      return;  // the same units again, as predicted: residual and change 0
    }
    const double scaled = value * detail::decimal_text::kScale[detail::kFieldDecimals[F]];
    if (!(std::fabs(scaled) < detail::decimal_text::kExactLimit)) {
      raw |= kBit;  // stored as it is; its history starts afresh after it
      out = codec::put_fixed64(out, bits);
      track.still &= ~kBit;
      repeats = false;
      return;
    }
    const int64_t units = detail::decimal_text::round_half_away(scaled);
    const bool fresh = (track.fresh & kBit) != 0;
    const int64_t residual = units - (fresh ? 0 : track.next[F]);
    const int64_t change = fresh ? 0 : units - track.last[F];
    track.last[F] = units;
    track.next[F] = units + change;
    repeats = repeats & (change == 0);
    track.bits[F] = bits;
    track.still = change == 0 ? track.still | kBit : track.still & ~kBit;
    if (residual != 0) {
      mask |= kBit;
      out = codec::put_varint(out, codec::zigzag(residual));
    }
  }
};

}  // namespace

void BinaryTrajectoryRecorder::State::encode(const Simulation& simulation, uint32_t index,
                                             const EntityState& state, int64_t& previous) {
  Track& track = entities[index];
  Steady& seen = steady[index];
  uint32_t mask = 0;
  uint32_t raw = 0;
  // The record's body (road and lane, at most 10 + 10 bytes, then nine numbers of 10), made
  // before its head (index step, mask and raw bits, at most 10 + 5 + 5), which needs the mask.
  constexpr size_t kHead = 20;
  char body[20 + detail::kRowFields * 10];
  char* out = body;
  if (!state.placed) {
    seen.valid = false;
    if (!track.present) {
      return;
    }
    track.present = false;
    mask = codec::kPresenceBit;  // gone: nothing else follows
  } else {
    if (seen.valid && track.present && detail::same_row_inputs(seen.inputs, state)) {
      return;  // the same row as last time, which its history predicts to repeat
    }
    if (!track.present) {
      track = Track{};
      track.present = true;
      mask |= codec::kPresenceBit;
    }
    const bool on_road = state.road.has_value();
    const uint32_t road = on_road ? state.road->road : 0;
    if (on_road != track.on_road || road != track.road) {
      mask |= codec::kRoadBit;
      if (on_road && (road >= road_named.size() || !road_named[road])) {
        road_named.resize(std::max<size_t>(road_named.size(), road + 1), false);
        road_named[road] = true;
        put_string(roads, codec::kTagRoad, road, simulation.road_id(road));
      }
      out = codec::put_varint(out, on_road ? uint64_t{road} + 1 : 0);
      track.on_road = on_road;
      track.road = road;
      track.fresh |= (1u << detail::kFieldS) | (1u << detail::kFieldT);
      track.still &= ~((1u << detail::kFieldS) | (1u << detail::kFieldT));
    }
    if (on_road && state.road->lane != track.lane) {
      mask |= codec::kLaneBit;
      out = codec::put_varint(out, codec::zigzag(int64_t{state.road->lane} - track.lane));
      track.lane = state.road->lane;
    }
    // The row's numbers as row_values scales them; s and t only on a road (the CSV leaves them
    // empty off it).
    const double values[detail::kRowFields] = {state.pose.x,
                                               state.pose.y,
                                               state.pose.z,
                                               state.pose.h,
                                               state.pose.p,
                                               state.pose.r,
                                               state.speed,
                                               on_road ? state.road->s : 0.0,
                                               on_road ? state.road->t : 0.0};
    const int fields = on_road ? detail::kRowFields : detail::kFieldS;
    FieldCoder<Track> coder{track, raw, mask, out};
    coder.fields<detail::kFieldX, detail::kFieldY, detail::kFieldZ, detail::kFieldH,
                 detail::kFieldP, detail::kFieldR, detail::kFieldSpeed>(values);
    if (on_road) {
      coder.fields<detail::kFieldS, detail::kFieldT>(values);
    }
    const bool repeats = coder.repeats;
    out = coder.out;
    // The fields taken are predicted from now on, the raw ones start afresh.
    track.fresh = (track.fresh & ~((1u << fields) - 1)) | raw;
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
  // Room for the whole of `body`, so that it is copied at its full, fixed size (a few vector
  // moves in place of a call of memcpy); the bytes after its end are not part of the frame.
  if (frame.size() < frame_size + kHead + sizeof body) {
    frame.resize(std::max(2 * frame.size(), frame_size + kHead + sizeof body));
  }
  char* end = frame.data() + frame_size;
  end = codec::put_varint(end, static_cast<uint64_t>(index - previous));
  end = codec::put_varint(end, mask);
  if (raw != 0) {
    end = codec::put_varint(end, raw);
  }
  std::memcpy(end, body, sizeof body);
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
    encode(simulation, i, state, previous);
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
