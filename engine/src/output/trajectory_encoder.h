#pragma once

// The binary trajectory's encoder (docs/trajectory-format.md): it turns the rows of recorded
// ticks into the file's bytes, reading them either from copies taken out of the simulation
// (TrajectoryRowCopy: it then reads nothing of the simulation, so that it can run on a thread of
// its own while the simulation steps on, output/trajectory_binary.cpp) or, on the simulation's
// thread, straight from the entities' states (EntityStateRows: no copy). The bytes are the same
// either way.

#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "corsa/core/atomic_file.h"
#include "corsa/engine/simulation.h"
#include "output/trajectory_codec.h"
#include "output/trajectory_rows.h"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace corsa::engine::detail {

/// An entity's row inputs at a recorded tick, copied from its EntityState: the numbers in
/// RowField order (s and t 0 off the road), the road and lane (0 off the road).
struct TrajectoryRowCopy {
  std::array<double, kRowFields> values{};
  uint32_t road = 0;
  int32_t lane = 0;
  bool placed = false;
  bool on_road = false;
};

/// The copy of `state` (inline: the recorder makes one per entity and recorded tick).
inline void copy_row(TrajectoryRowCopy& row, const EntityState& state) {
  row.values[kFieldX] = state.pose.x;
  row.values[kFieldY] = state.pose.y;
  row.values[kFieldZ] = state.pose.z;
  row.values[kFieldH] = state.pose.h;
  row.values[kFieldP] = state.pose.p;
  row.values[kFieldR] = state.pose.r;
  row.values[kFieldSpeed] = state.speed;
  row.placed = state.placed;
  row.on_road = state.road.has_value();
  if (row.on_road) {
    row.values[kFieldS] = state.road->s;
    row.values[kFieldT] = state.road->t;
    row.road = state.road->road;
    row.lane = state.road->lane;
  } else {
    row.values[kFieldS] = 0.0;
    row.values[kFieldT] = 0.0;
    row.road = 0;
    row.lane = 0;
  }
}

// A row's inputs as the encoder reads them, from a copy or from the entity's state: field F's
// value (s and t only while on a road), presence, road and lane.
template <int F>
inline const double& row_value(const TrajectoryRowCopy& row) {
  return row.values[F];
}
inline bool row_placed(const TrajectoryRowCopy& row) { return row.placed; }
inline bool row_on_road(const TrajectoryRowCopy& row) { return row.on_road; }
inline uint32_t row_road(const TrajectoryRowCopy& row) { return row.road; }
inline int32_t row_lane(const TrajectoryRowCopy& row) { return row.lane; }

template <int F>
inline const double& row_value(const EntityState& state) {
  static_assert(F >= 0 && F < kRowFields);
  if constexpr (F == kFieldX) {
    return state.pose.x;
  } else if constexpr (F == kFieldY) {
    return state.pose.y;
  } else if constexpr (F == kFieldZ) {
    return state.pose.z;
  } else if constexpr (F == kFieldH) {
    return state.pose.h;
  } else if constexpr (F == kFieldP) {
    return state.pose.p;
  } else if constexpr (F == kFieldR) {
    return state.pose.r;
  } else if constexpr (F == kFieldSpeed) {
    return state.speed;
  } else if constexpr (F == kFieldS) {
    return state.road->s;
  } else {
    return state.road->t;
  }
}
inline bool row_placed(const EntityState& state) { return state.placed; }
inline bool row_on_road(const EntityState& state) { return state.road.has_value(); }
inline uint32_t row_road(const EntityState& state) { return state.road->road; }
inline int32_t row_lane(const EntityState& state) { return state.road->lane; }
/// Field F's bits, read as an integer: where they are only compared, without the detour through
/// a vector register that a read of the double takes (Track::takes_below_decimals's test of a
/// number that keeps its bits: three instructions against four).
template <int F, class Row>
inline uint64_t row_bits(const Row& row) {
  uint64_t bits = 0;
  std::memcpy(&bits, &row_value<F>(row), sizeof bits);
  return bits;
}

/// Whether the row's x to speed (fields 0 to kFieldS - 1) are `bits`' first seven, bit for bit:
/// their differences gathered without a branch, so that a standing entity costs one test.
template <class Row, int... F>
inline uint64_t motion_difference(const Row& row, const uint64_t* bits,
                                  std::integer_sequence<int, F...> /*fields*/) {
  return ((std::bit_cast<uint64_t>(row_value<F>(row)) ^ bits[F]) | ...);
}
template <class Row>
inline bool same_motion(const Row& row, const uint64_t* bits) {
  return motion_difference(row, bits, std::make_integer_sequence<int, kFieldS>()) == 0;
}
#if defined(__SSE2__)
/// The differences of an entity's x to speed from `bits`' first seven, gathered in a vector
/// (0 when they are the same bits): the pose's six numbers lie side by side and are compared two
/// at a time. `bits` is 16-byte aligned (TrajectoryEncoder::Track's).
inline __m128i motion_difference(const EntityState& state, const uint64_t* bits) {
  static_assert(offsetof(Pose, y) == 8 && offsetof(Pose, z) == 16 && offsetof(Pose, h) == 24 &&
                offsetof(Pose, p) == 32 && offsetof(Pose, r) == 40 && sizeof(Pose) == 48);
  static_assert(kFieldX == 0 && kFieldR == 5 && kFieldSpeed == 6);
  const auto* pose = reinterpret_cast<const __m128i*>(&state.pose);
  const auto* last = reinterpret_cast<const __m128i*>(bits);
  __m128i difference = _mm_xor_si128(_mm_loadu_si128(pose), _mm_load_si128(last));
  difference =
      _mm_or_si128(difference, _mm_xor_si128(_mm_loadu_si128(pose + 1), _mm_load_si128(last + 1)));
  difference =
      _mm_or_si128(difference, _mm_xor_si128(_mm_loadu_si128(pose + 2), _mm_load_si128(last + 2)));
  return _mm_or_si128(difference,
                      _mm_xor_si128(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(&state.speed)),
                                    _mm_loadl_epi64(last + 3)));
}
/// Whether the state's x to speed are `bits`' first seven, bit for bit (16 instructions
/// against 22 apart).
inline bool same_motion(const EntityState& state, const uint64_t* bits) {
  return _mm_movemask_epi8(_mm_cmpeq_epi8(motion_difference(state, bits), _mm_setzero_si128())) ==
         0xffff;
}
#endif

/// The rows of the simulation's current tick, read from the entities' states where they are.
struct EntityStateRows {
  EntityStates states;
  const Simulation* simulation = nullptr;
  /// The entities' counts of their states' writes (Simulation::state_changes), which the skip
  /// pass reads; none (states that are not a simulation's): every state is tested.
  EntityStateChanges changes;
  const EntityState& operator[](size_t index) const { return states[index]; }
  /// The OpenDRIVE id of road `road` (the map holds it).
  const std::string& road_id(uint32_t road) const { return simulation->road_id(road); }
};

/// One recorded tick: its rows are the `entities` copies that follow the previous tick's.
struct TickRowsHead {
  int64_t tick = 0;
  double time = 0.0;  ///< s, Simulation::time()
  uint32_t entities = 0;
};

class TrajectoryEncoder {
 public:
  /// `every`: a tick in `every` is recorded (and the last).
  TrajectoryEncoder(std::filesystem::path path, int64_t every);

  /// Names entity `index` (entities are named in order, before the first tick that counts them).
  void name_entity(std::string name) { names_.push_back(std::move(name)); }
  /// The OpenDRIVE id of road `road`, before the first tick a row copy is on it (the string
  /// must outlive the encoder: the map holds it; rows read from the states need none).
  void name_road(uint32_t road, const std::string* id);

  /// Encodes one recorded tick (`rows[i]`, i below head.entities: TrajectoryRowCopy* or
  /// EntityStateRows). `dt`: the run's step (s). Returns the rows that had to be coded: those
  /// not skipped as the steady repeat of their last row (the tick's work).
  ///
  /// Inline, for the tick at which most entities stand: the skip pass alone, and when it leaves
  /// nothing to code (every row kept only moved below its decimals) at a tick of the header's
  /// time, the tick is done without the call of the coder (record_tick, whose size makes its
  /// entry and exit cost a third of such a tick).
  template <class Rows>
  [[gnu::always_inline]] uint32_t record(double dt, const TickRowsHead& head, const Rows& rows) {
    const uint32_t count = head.entities;
    // count - 1 < tracked_: some entities, each tracked (so started); 2 * last_coded_ < count:
    // most rows of the last tick were skipped.
    if (count - 1 < tracked_ && 2 * last_coded_ < count) [[likely]] {
      const uint32_t kept = skip_pass(rows, count);
      const uint32_t left = kept == 0 ? 0 : take_below_decimals(rows, kept);
      if (left == 0 && head.tick == due_tick_ &&
          std::bit_cast<uint64_t>(head.time) == std::bit_cast<uint64_t>(due_time_)) [[likely]] {
        last_coded_ = kept;
        advance_due(head.tick);
        return kept;  // every present entity as predicted: the tick costs nothing
      }
      return record_tick(dt, head, rows, kept, left);
    }
    return record_tick(dt, head, rows, kNoSkipPass, 0);
  }
  /// Ends the file at `last_tick` and commits it (InputError when it cannot be written).
  void finish(int64_t last_tick);

 private:
  /// The writer's side of an entity's history (codec::EntityHistory's predictions, kept as the
  /// value each field is predicted to take next, so that a moving entity's field costs a
  /// subtraction and no test of its history's state). 240 bytes, all a row's coding reads of
  /// the entity besides its row: between two recorded ticks the simulation's own data push
  /// most of it out of the first-level cache, so every byte more is a miss more.
  struct Track {
    /// The road and lane (first, at offsets 0 and 8 as in RoadCoordinates: the skip pass
    /// compares them with a row's in one vector).
    uint32_t road = 0;
    uint32_t fresh = trajectory_codec::kFieldBits;  ///< fields predicted 0 (history afresh)
    int lane = 0;
    bool present = false;
    bool on_road = false;
    /// The last row repeats its prediction: a row of the same inputs (bits, road and lane) is
    /// the same row again, and needs neither to be made nor a record.
    bool steady = false;
    /// on_road while steady, else kUnsteady or more (which no row's on-road flag is): the skip pass
    /// tests steadiness and the road flag in one comparison. Kept by set_steady, and set to
    /// kBelowDecimals by takes_below_decimals.
    uint8_t steady_road = kUnsteady;
    /// The bits of the fields' last values (16-byte aligned: same_motion reads them in pairs).
    alignas(16) std::array<uint64_t, kRowFields> bits{};
    std::array<int64_t, kRowFields> last{};  ///< the value last taken
    std::array<int64_t, kRowFields> next{};  ///< last + its change: the prediction
    /// Fields whose last value came from the bits in `bits` and repeated the one before: while
    /// the bits stay, the field is as predicted and keeps its history (z, pitch and roll on a
    /// flat road, a steady speed), without scaling it again.
    uint32_t still = 0;
    /// The entity's count of its state's writes (Simulation::state_changes) when the skip pass
    /// last saw its row pass (the state then the steady repeat of the last row, and the track as it
    /// is: only a row that does not pass changes it), or a count it has moved past. While the
    /// entity's count is this, its row passes without a test.
    uint32_t seen = UINT32_MAX;

    /// Whether placed `row` has the inputs of the steady last row. While steady, every field
    /// taken last time (s and t on a road) holds the bits of its last row in `bits`; off the
    /// road a row's s, t and lane are 0.
    template <class Row>
    bool repeats(const Row& row) const {
      if (!same_motion(row, bits.data()) || row_on_road(row) != on_road) {
        return false;
      }
      // Road, lane, s and t gathered without a branch, as the motion.
      return !on_road ||
             ((uint64_t{row_road(row) ^ road} | static_cast<uint32_t>(row_lane(row) ^ lane) |
               differs<kFieldS>(row) | differs<kFieldT>(row)) == 0);
    }
    /// encode's first test: whether `row` is placed and repeats the steady last row, so that
    /// it needs neither to be made nor a record.
    template <class Row>
    bool skips(const Row& row) const {
      return steady && row_placed(row) && repeats(row);
    }
    static constexpr uint8_t kUnsteady = 2;
    /// steady_road of a steady track whose last row moved below its decimals (a standing
    /// entity whose pose is recomputed at each step: its next row most likely moves so again).
    /// The skip pass, whose comparison of the bits would fail, then leaves the row to
    /// take_below_decimals at once; a row that repeats the bits there returns it to on_road.
    static constexpr uint8_t kBelowDecimals = 4;
    /// Sets steady, `on_road_now` being on_road (kUnsteady and kUnsteady + 1 are both no row's
    /// flag: no branch on `now`).
    void set_steady(bool now, bool on_road_now) {
      steady = now;
      steady_road = static_cast<uint8_t>(unsigned{on_road_now} + (now ? 0u : kUnsteady));
    }
    /// The skip pass's test: skips(row), for an entity's state with its numbers (s and t on a
    /// road) gathered in one vector of differences, two at a time.
    template <class Row>
    bool passes(const Row& row) const {
      return skips(row);
    }
#if defined(__SSE2__)
    bool passes(const EntityState& state) const {
      static_assert(offsetof(RoadCoordinates, t) == offsetof(RoadCoordinates, s) + 8);
      static_assert(offsetof(RoadCoordinates, road) == 0 && offsetof(RoadCoordinates, lane) == 8);
      if (static_cast<uint8_t>(state.road.has_value()) != steady_road || !state.placed) {
        return false;
      }
      __m128i difference = motion_difference(state, bits.data());
      if (on_road) {
        const auto* place = reinterpret_cast<const __m128i*>(&*state.road);
        difference = _mm_or_si128(
            difference,
            _mm_xor_si128(_mm_loadu_si128(place + 1),
                          _mm_loadu_si128(reinterpret_cast<const __m128i*>(&bits[kFieldS]))));
        // The road and the lane, this track's first and third words (the second and fourth, the
        // section and padding there, fresh and the flags here, masked off).
        const __m128i words = _mm_xor_si128(_mm_loadu_si128(place),
                                            _mm_load_si128(reinterpret_cast<const __m128i*>(this)));
        difference = _mm_or_si128(difference, _mm_and_si128(words, _mm_set_epi32(0, -1, 0, -1)));
      }
      return _mm_movemask_epi8(_mm_cmpeq_epi8(difference, _mm_setzero_si128())) == 0xffff;
    }
#endif
    template <int F, class Row>
    uint64_t differs(const Row& row) const {
      return std::bit_cast<uint64_t>(row_value<F>(row)) ^ bits[F];
    }

    /// For a steady track and placed `row` on its road and lane: whether every number of `row`
    /// prints as the last row's (each either the same bits or within half a unit of its last
    /// decimal, encode's test for a still field), taking the bits of each number that differ.
    /// The row then needs no record and the track stays steady: what encode would do, without
    /// its work (a standing entity whose pose is recomputed at every step moves only below its
    /// decimals). While steady, every field taken (s and t on a road) is still, with `last` its
    /// units. (When a number does not print so, the row goes to encode, whose test of the numbers
    /// before it would have taken the same bits: taken here already, they are as predicted there.)
    /// `kMark`: steady_road says whether the row moved below its decimals (for the skip pass;
    /// kBelowDecimals is only a hint, that a track without it keeps).
    template <bool kMark, class Row>
    bool takes_below_decimals(const Row& row) {
      if (row_on_road(row) != on_road ||
          (on_road && (row_road(row) != road || row_lane(row) != lane))) {
        return false;
      }
      if constexpr (kMark) {
        // kBelowDecimals once a number's bits differ (prints_as_last), as the row is taken.
        // (When it is not, encode sets steady_road.)
        steady_road = static_cast<uint8_t>(on_road);
      }
      return prints_as_last<kMark, kFieldX, kFieldY, kFieldZ, kFieldH, kFieldP, kFieldR,
                            kFieldSpeed>(row) &&
             (!on_road || prints_as_last<kMark, kFieldS, kFieldT>(row));
    }
    template <bool kMark, int... F, class Row>
    bool prints_as_last(const Row& row) {
      return (field_prints_as_last<kMark, F>(row) && ...);
    }
    /// Whether field F of `row` prints as its last value: the same bits, or else (steady_road
    /// then kBelowDecimals, with kMark) within half a unit of its last decimal, its bits then
    /// taken.
    template <bool kMark, int F, class Row>
    bool field_prints_as_last(const Row& row) {
      const uint64_t now = row_bits<F>(row);
      if (now == bits[F]) {
        return true;
      }
      if constexpr (kMark) {
        steady_road = kBelowDecimals;
      }
      // Exact as in encode: `last` is an integer below 9e15 and a value within half a unit of it
      // has it as its rounding (a NaN or a value far off fails the test).
      if (!(std::fabs(std::bit_cast<double>(now) * decimal_text::kScale[kFieldDecimals[F]] -
                      static_cast<double>(last[F])) < 0.5)) {
        return false;
      }
      bits[F] = now;
      return true;
    }
  };
  static_assert(sizeof(Track) == 240 && offsetof(Track, road) == 0 && offsetof(Track, lane) == 8);

  /// A record's head (index step, mask and raw bits) and body (road and lane, nine numbers) at
  /// their largest, bytes.
  static constexpr size_t kMaxHead = 10 + 5 + 5;
  static constexpr size_t kMaxBody = 10 + 10 + kRowFields * 10;
  /// A frame's head at its largest: a time record (tag and f64), the frame's tag and its tick
  /// step (a varint).
  static constexpr size_t kFrameHead = 1 + 8 + 1 + 10;
  /// The bytes the buffer gathers before they go to the file: few enough that the buffer stays
  /// below malloc's mmap threshold (128 KiB) and is reused from one flush to the next. (At 1
  /// MiB, a recording of a few hundred KB grew it by doublings into fresh mappings, about 200
  /// page faults.)
  static constexpr size_t kFlushBytes = size_t{1} << 16;

  /// record_tick's `kept` when the tick's skip pass has not run.
  static constexpr uint32_t kNoSkipPass = UINT32_MAX;

  /// The tick's coding apart from record's inline part: `kept` is the count of rows the skip
  /// pass kept, or kNoSkipPass (then it runs here, or the one pass for moving entities), and
  /// `left` the first of pending_ that take_below_decimals left to code.
  template <class Rows>
  [[gnu::noinline]] uint32_t record_tick(double dt, const TickRowsHead& head, const Rows& rows,
                                         uint32_t kept, uint32_t left);
  /// Most rows of the last tick were coded (entities that move): one pass over the first
  /// `count` rows, encode's first test beside it. Returns the rows not skipped.
  template <class Rows>
  [[gnu::noinline]] uint32_t code_every_row(const Rows& rows, uint32_t count);
  /// Most entities stand: the first `left` rows of pending_, in order. (Apart from the skip
  /// pass, in a loop of its own, so that the pass's few values stay in registers: in a loop
  /// with encode inlined, the loop's counters live on the stack.)
  template <class Rows>
  [[gnu::noinline]] void code_pending(const Rows& rows, uint32_t left);
  /// Of the first `kept` rows of pending_, those of a steady track that moved only below their
  /// decimals are taken as they are (Track::takes_below_decimals), and the others kept in
  /// order; returns their count.
  template <class Rows>
  [[gnu::always_inline]] uint32_t take_below_decimals(const Rows& rows, uint32_t kept) {
    uint32_t* pending = pending_.data();
    Track* tracks = entities_.data();
    uint32_t left = 0;
    for (uint32_t k = 0; k < kept; ++k) {
      const uint32_t i = pending[k];
      Track& track = tracks[i];
      if (!track.steady || !row_placed(rows[i]) ||
          !track.template takes_below_decimals<true>(rows[i])) {
        pending[left++] = i;
      }
    }
    return left;
  }
  /// The skip pass: the index of each of the first `count` rows that is not the steady repeat
  /// of its last row, in order, into pending_; returns their count.
  template <class Rows>
  [[gnu::always_inline]] uint32_t skip_pass(const Rows& rows, uint32_t count) {
    uint32_t* pending = pending_.data();
    Track* tracks = entities_.data();
    uint32_t coded = 0;
    if constexpr (std::is_same_v<Rows, EntityStateRows>) {
      if (rows.changes.size() < count) [[unlikely]] {
        return skip_pass(rows.states, count);  // states without their counts (tests)
      }
      // An entity whose state has not been written since its row last passed passes again: one
      // comparison. Otherwise the test of its state, whose count is then kept when it passes,
      // and else one below it (never the count while the entity's track is coded; the count
      // would have to wrap between two recorded ticks to come back to it).
      const EntityStates states = rows.states;
      const EntityStateChanges counts = rows.changes;
      for (uint32_t i = 0; i < count; ++i) {
        const uint32_t changes = counts[i];
        Track& track = tracks[i];
        if (changes == track.seen) [[likely]] {
          continue;
        }
        const bool passes = track.passes(states[i]);
        track.seen = passes ? changes : changes - 1;
        if (!passes) {
          pending[coded++] = i;
        }
      }
    } else {
      // Two entities a round: a test of the loop's end less for each (the pass is most of a
      // tick of standing entities).
#pragma GCC unroll 2
      for (uint32_t i = 0; i < count; ++i) {
        if (!tracks[i].passes(rows[i])) {
          pending[coded++] = i;
        }
      }
    }
    return coded;
  }
  /// The tick expected after `tick` and its time by the header, worked out one recorded tick
  /// ahead (so that the next tick does not wait for the division).
  void advance_due(int64_t tick) {
    due_tick_ = tick + every_;
    due_time_ = tick_time(due_tick_);
  }
  /// The time of `tick` by the header: tick / per_second, or tick x dt.
  double tick_time(int64_t tick) const {
    return per_second_ > 0 ? static_cast<double>(tick) / static_cast<double>(per_second_)
                           : static_cast<double>(tick) * dt_;
  }
  void start(double dt, int64_t tick);
  /// Tracks entities up to `count` (their names written) and makes the frame's room for them.
  void add_entities(uint32_t count);
  /// Appends the record of entity `index` (its track `track`) to `frame_` when its row differs
  /// from the prediction (`previous`: the index of the frame's last record, -1 before the first).
  template <class Row>
  void encode(uint32_t index, Track& track, const Row& row, int64_t& previous);
  void flush();

  AtomicFile file_;
  int64_t every_;
  std::string buffer_;  ///< bytes not yet written to the file
  uint32_t crc_ = 0;    ///< of the bytes written so far
  bool started_ = false;
  int64_t per_second_ = 0;  ///< N when the time of tick k is k / N
  double dt_ = 0.0;
  int64_t last_frame_ = 0;
  /// The tick expected to be recorded next (the last one plus `every`) and its time by the
  /// header (tick_time), worked out ahead of it.
  int64_t due_tick_ = INT64_MIN;
  double due_time_ = 0.0;
  std::vector<std::string> names_;
  std::vector<Track> entities_;
  uint32_t tracked_ = 0;  ///< entities_.size()
  /// The entities a tick's skip pass left to code, in order (room for every entity).
  std::vector<uint32_t> pending_;
  /// The rows the last tick coded: most of its entities' (they move) or not (they stand).
  uint32_t last_coded_ = 0;
  std::vector<const std::string*> road_ids_;  ///< by road index, null until named
  /// The states being encoded (EntityStateRows), whose simulation names the roads not named.
  const EntityStateRows* state_rows_ = nullptr;
  std::vector<bool> road_named_;  ///< written as a road record
  std::string roads_;             ///< road records of roads first met at this tick
  /// The entity records of this tick: the bytes of `frame_` from kFrameHead (the room of the
  /// frame's head) to frame_size_ (`frame_` only grows, so that a record is written in place
  /// without clearing its room first).
  std::vector<char> frame_;
  size_t frame_size_ = 0;
};

}  // namespace corsa::engine::detail
