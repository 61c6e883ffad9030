// The binary trajectory's encoder: at each recorded tick, each entity whose row differs from
// what its previous rows predict gets a record of the differences (docs/trajectory-format.md).

#include "output/trajectory_encoder.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <type_traits>

namespace corsa::engine::detail {

namespace codec = trajectory_codec;

namespace {

// The N of a step dt = 1 / N (the engine then counts time as tick / N), or 0.
int64_t steps_per_second(double dt) {
  const double n = std::round(1.0 / dt);
  return n >= 1.0 && n < 1e9 && std::abs(1.0 / n - dt) <= 1e-15 * dt ? static_cast<int64_t>(n) : 0;
}

void put_string(std::string& out, uint8_t tag, uint64_t index, const std::string& text) {
  out.push_back(static_cast<char>(tag));
  codec::put_varint(out, index);
  codec::put_varint(out, text.size());
  out += text;
}

// Codes an entity's numeric fields into its record's body, one field at a time with the field's
// number known when compiled (its decimals and mask bit constants, no loop over a table): as
// the loop it replaces, about a tenth fewer instructions per row. `Track` is
// TrajectoryEncoder::Track. `kAnyFresh`: whether some field coded may have a fresh history;
// without (a moving entity's usual row) its prediction and change are taken as they are, a few
// instructions less a field.
template <class Track, bool kAnyFresh>
struct TrajectoryFieldCoder {
  Track& track;
  uint32_t& raw;
  uint32_t& mask;
  char* out;
  /// track.still while the fields are coded, stored back by the caller once (as a member of
  /// the track, the compiler stored it after every field: a byte of the body may be any object).
  uint32_t still;
  uint32_t fresh;       ///< track.fresh, read once (it does not change while the fields are coded)
  bool repeats = true;  ///< every field so far predicted to keep its value

  // Inlined whatever the inliner's budget (encode is inlined at two places in record, and the
  // compiler then called s and t out of line: 70 instructions a row more).
  template <int... F, class Row>
  [[gnu::always_inline]] void fields(const Row& row) {
    (field<F>(row_value<F>(row)), ...);
  }

  template <int F>
  [[gnu::always_inline]] void field(double value) {
    constexpr uint32_t kBit = 1u << F;
    constexpr double kFieldScale = decimal_text::kScale[kFieldDecimals[F]];
    const uint64_t bits = std::bit_cast<uint64_t>(value);
    if ((still & kBit) != 0) [[unlikely]] {
      if (bits == track.bits[F]) {
        return;  // the same units again, as predicted: residual and change 0
      }
      // Other bits of the same units (a value that moves only below its last decimal, as a
      // standing entity's recomputed pose does): as predicted too, without rounding. Exact:
      // `last` is an integer below 9e15 and `scaled` within half a unit of it, so the
      // subtraction is exact (Sterbenz) and round_half_away(scaled) is `last`.
      if (std::fabs(value * kFieldScale - static_cast<double>(track.last[F])) < 0.5) {
        track.bits[F] = bits;
        return;
      }
    }
    const int64_t units = decimal_text::round_or_far(value * kFieldScale);
    if (!decimal_text::near_units(units)) [[unlikely]] {
      raw |= kBit;  // stored as it is; its history starts afresh after it
      out = codec::put_fixed64(out, bits);
      still &= ~kBit;
      repeats = false;
      return;
    }
    // A fresh history predicts 0 and records no change: its prediction and last value masked
    // off, without a branch.
    int64_t residual = units - track.next[F];
    int64_t change = units - track.last[F];
    if constexpr (kAnyFresh) {
      const int64_t kept = static_cast<int64_t>((fresh >> F) & 1u) - 1;  // 0 when fresh, else ~0
      residual = units - (track.next[F] & kept);
      change &= kept;
    }
    track.last[F] = units;
    track.next[F] = units + change;
    repeats = repeats & (change == 0);
    track.bits[F] = bits;
    still = (still & ~kBit) | (change == 0 ? kBit : 0u);
    // Whether the residual is 0 follows no pattern where the roads curve and climb (esmini's
    // synchronize: x, y, z, heading, pitch, speed and s each miss their prediction in 58-76%
    // of the rows coded), so a residual of one byte or none is written without a branch on it:
    // its byte is stored either way, and counted only when it is not 0 (the body has room for
    // a field's largest code after it).
    const uint64_t code = codec::zigzag(residual);
    const uint32_t taken = code != 0 ? kBit : 0u;
    mask |= taken;
    if (code < 0x80) [[likely]] {
      *out = static_cast<char>(code);
      out += taken >> F;
    } else {
      out = codec::put_varint(out, code);
    }
  }
};

// Codes the numeric fields of `row` (s and t only `on_road`) into the body at `out` (moved to
// its end); returns whether every field is predicted to keep its value.
template <bool kAnyFresh, class Track, class Row>
[[gnu::always_inline]] inline bool code_row_fields(Track& track, const Row& row, bool on_road,
                                                   uint32_t& raw, uint32_t& mask, char*& out) {
  TrajectoryFieldCoder<Track, kAnyFresh> coder{track, raw, mask, out, track.still, track.fresh};
  coder.template fields<kFieldX, kFieldY, kFieldZ, kFieldH, kFieldP, kFieldR, kFieldSpeed>(row);
  if (on_road) {
    coder.template fields<kFieldS, kFieldT>(row);
  }
  track.still = coder.still;
  out = coder.out;
  return coder.repeats;
}

}  // namespace

TrajectoryEncoder::TrajectoryEncoder(std::filesystem::path path, int64_t every)
    : file_(std::move(path), true), every_(every < 1 ? 1 : every) {}

void TrajectoryEncoder::name_road(uint32_t road, const std::string* id) {
  if (road >= road_ids_.size()) {
    road_ids_.resize(road + 1, nullptr);
  }
  road_ids_[road] = id;
}

void TrajectoryEncoder::start(double dt, int64_t tick) {
  started_ = true;
  dt_ = dt;
  per_second_ = steps_per_second(dt);
  buffer_.append(codec::kMagic);
  buffer_.push_back(static_cast<char>(codec::kVersion));
  codec::put_fixed64(buffer_, std::bit_cast<uint64_t>(dt));
  codec::put_varint(buffer_, static_cast<uint64_t>(per_second_));
  codec::put_varint(buffer_, static_cast<uint64_t>(every_));
  codec::put_varint(buffer_, codec::zigzag(tick));
  last_frame_ = tick;
}

void TrajectoryEncoder::add_entities(uint32_t count) {
  while (entities_.size() < count) {
    put_string(buffer_, codec::kTagEntity, entities_.size(), names_.at(entities_.size()));
    entities_.emplace_back();
  }
  tracked_ = static_cast<uint32_t>(entities_.size());
  pending_.resize(entities_.size());
  // Room for the frame's head, every entity's record at its largest (head and whole body) and
  // the frame's end.
  const size_t room = kFrameHead + size_t{count} * (kMaxHead + kMaxBody) + 1;
  if (frame_.size() < room) {
    frame_.resize(room);
  }
}

template <class Row>
[[gnu::always_inline]] inline void TrajectoryEncoder::encode(uint32_t index, Track& track,
                                                             const Row& row, int64_t& previous) {
  uint32_t mask = 0;
  uint32_t raw = 0;
  // The record's body (road and lane, at most 10 + 10 bytes, then nine numbers of 10), made
  // before its head (index step, mask and raw bits, at most 10 + 5 + 5), which needs the mask.
  char body[kMaxBody];
  char* out = body;
  if (!row_placed(row)) {
    track.set_steady(false, false);
    if (!track.present) {
      return;
    }
    track.present = false;
    mask = codec::kPresenceBit;  // gone: nothing else follows
  } else {
    if (track.steady && track.present && track.repeats(row)) {
      return;  // the same row as last time, which its history predicts to repeat
    }
    if (!track.present) {
      track = Track{};
      track.present = true;
      mask |= codec::kPresenceBit;
    }
    const bool on_road = row_on_road(row);
    const uint32_t road = on_road ? row_road(row) : 0;
    if (on_road != track.on_road || road != track.road) {
      mask |= codec::kRoadBit;
      if (on_road && (road >= road_named_.size() || !road_named_[road])) {
        road_named_.resize(std::max<size_t>(road_named_.size(), road + 1), false);
        road_named_[road] = true;
        const std::string* id = road < road_ids_.size() ? road_ids_[road] : nullptr;
        put_string(roads_, codec::kTagRoad, road, id != nullptr ? *id : state_rows_->road_id(road));
      }
      out = codec::put_varint(out, on_road ? uint64_t{road} + 1 : 0);
      track.on_road = on_road;
      track.road = road;
      track.fresh |= (1u << kFieldS) | (1u << kFieldT);
      track.still &= ~((1u << kFieldS) | (1u << kFieldT));
    }
    if (on_road && row_lane(row) != track.lane) {
      const int32_t lane = row_lane(row);
      mask |= codec::kLaneBit;
      out = codec::put_varint(out, codec::zigzag(int64_t{lane} - track.lane));
      track.lane = lane;
    }
    // s and t only on a road (the CSV leaves them empty off it).
    const int fields = on_road ? kRowFields : kFieldS;
    const bool repeats = (track.fresh & ((1u << fields) - 1)) == 0
                             ? code_row_fields<false>(track, row, on_road, raw, mask, out)
                             : code_row_fields<true>(track, row, on_road, raw, mask, out);
    // The fields taken are predicted from now on, the raw ones start afresh.
    track.fresh = (track.fresh & ~((1u << fields) - 1)) | raw;
    if (raw != 0) {
      mask |= codec::kRawBit;
    }
    // While the inputs stay these, the row stays this one and every prediction holds: the
    // next ticks need neither the row nor a record.
    track.set_steady(repeats, on_road);
  }
  if (mask == 0) {
    return;  // as predicted: nothing to store
  }
  const auto body_size = static_cast<size_t>(out - body);
  // The frame has room for the whole of `body` after every record (record() makes it), so
  // that it is copied at a fixed size (a few vector moves in place of a call of memcpy): its
  // first 32 bytes, which hold most bodies, or all of it; the bytes after its end are not part
  // of the frame.
  char* end = frame_.data() + frame_size_;
  end = codec::put_varint(end, static_cast<uint64_t>(index - previous));
  end = codec::put_varint(end, mask);
  if (raw != 0) {
    end = codec::put_varint(end, raw);
  }
  if (body_size <= 32) {
    std::memcpy(end, body, 32);
  } else {
    std::memcpy(end, body, sizeof body);
  }
  frame_size_ = static_cast<size_t>(end - frame_.data()) + body_size;
  previous = index;
}

template <class Rows>
uint32_t TrajectoryEncoder::code_every_row(const Rows& rows, uint32_t count) {
  // Local copies of where the rows and tracks are, which the compiler keeps in registers
  // across the records written in between (the members it reloads after every store).
  const Rows local_rows = rows;
  Track* tracks = entities_.data();
  int64_t previous = -1;
  uint32_t coded = 0;
  for (uint32_t i = 0; i < count; ++i) {
    const auto& row = local_rows[i];
    Track& track = tracks[i];
    // (The counts of writes are not read here: the rows of this pass mostly move. A track whose
    // seen is its entity's count passes skips as in the skip pass; one coded here has a seen its
    // entity's count has moved past.)
    if (track.skips(row)) {
      continue;
    }
    ++coded;
    if (track.steady && row_placed(row) && track.template takes_below_decimals<false>(row)) {
      continue;
    }
    encode(i, track, row, previous);
  }
  return coded;
}

template <class Rows>
void TrajectoryEncoder::code_pending(const Rows& rows, uint32_t left) {
  const Rows local_rows = rows;
  Track* tracks = entities_.data();
  const uint32_t* pending = pending_.data();
  int64_t previous = -1;
  for (uint32_t k = 0; k < left; ++k) {
    const uint32_t i = pending[k];
    encode(i, tracks[i], local_rows[i], previous);
  }
}

template <class Rows>
uint32_t TrajectoryEncoder::record_tick(double dt, const TickRowsHead& head, const Rows& rows,
                                        uint32_t kept, uint32_t left) {
  if (!started_) {
    start(dt, head.tick);
  }
  const int64_t tick = head.tick;
  if (tracked_ < head.entities) [[unlikely]] {
    add_entities(head.entities);
  }
  frame_size_ = kFrameHead;
  if constexpr (std::is_same_v<Rows, EntityStateRows>) {
    state_rows_ = &rows;
  }
  const uint32_t count = head.entities;
  uint32_t coded = kept;
  if (kept == kNoSkipPass && 2 * last_coded_ >= count) {
    coded = code_every_row(rows, count);
  } else {
    if (kept == kNoSkipPass) {
      coded = skip_pass(rows, count);
      left = take_below_decimals(rows, coded);
    }
    code_pending(rows, left);
  }
  last_coded_ = coded;
  state_rows_ = nullptr;
  const double time = head.time;
  // The time the header gives this tick, divided out one recorded tick ahead (advance_due), so
  // that the tick does not wait for its division here: on a run of standing entities that wait
  // was a tenth of the tick's recording.
  const double due = tick == due_tick_ ? due_time_ : tick_time(tick);
  const bool odd_time = std::bit_cast<uint64_t>(time) != std::bit_cast<uint64_t>(due);
  advance_due(tick);
  if (frame_size_ == kFrameHead && !odd_time) {
    return coded;  // every present entity as predicted: the tick costs nothing
  }
  // (A road is first met by a record, so a tick without records has none.)
  if (!roads_.empty()) [[unlikely]] {
    buffer_ += roads_;
    roads_.clear();
  }
  // The frame's head (the time record, the tag and the tick's step) in the room before its
  // records and its end after them, so that the frame goes to the buffer in one append.
  const uint64_t step = codec::zigzag(tick - last_frame_);
  size_t head_size = (odd_time ? 1 + 8 : 0) + 1 + 1;
  for (uint64_t rest = step; rest >= 0x80; rest >>= 7) {
    ++head_size;
  }
  char* const frame = frame_.data() + kFrameHead - head_size;
  char* at = frame;
  if (odd_time) {
    *at++ = static_cast<char>(codec::kTagTime);
    at = codec::put_fixed64(at, std::bit_cast<uint64_t>(time));
  }
  *at++ = static_cast<char>(codec::kTagFrame);
  codec::put_varint(at, step);
  frame_[frame_size_] = 0;  // the frame's end: varint 0
  buffer_.append(frame, frame_size_ + 1 - (kFrameHead - head_size));
  last_frame_ = tick;
  if (buffer_.size() > kFlushBytes) {
    flush();
  }
  return coded;
}

template uint32_t TrajectoryEncoder::record_tick(double, const TickRowsHead&,
                                                 const TrajectoryRowCopy* const&, uint32_t,
                                                 uint32_t);
template uint32_t TrajectoryEncoder::record_tick(double, const TickRowsHead&,
                                                 const EntityStateRows&, uint32_t, uint32_t);

void TrajectoryEncoder::flush() {
  crc_ = codec::crc32(crc_, buffer_);
  file_.stream().write(buffer_.data(), static_cast<std::streamsize>(buffer_.size()));
  buffer_.clear();
}

void TrajectoryEncoder::finish(int64_t last_tick) {
  buffer_.push_back(static_cast<char>(codec::kTagEnd));
  codec::put_varint(buffer_, codec::zigzag(last_tick));
  flush();
  std::string end;
  for (int i = 0; i < 4; ++i) {
    end.push_back(static_cast<char>((crc_ >> (8 * i)) & 0xff));
  }
  file_.stream().write(end.data(), static_cast<std::streamsize>(end.size()));
  file_.commit();
}

}  // namespace corsa::engine::detail
