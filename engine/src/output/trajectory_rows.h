#pragma once

// The numbers of one trajectory row (docs/engine.md, "Output files") as both trajectory files
// hold them: each rounded to its decimals (Scaled), so that the CSV written during a run and the
// CSV exported from a binary trajectory (output/trajectory_binary.h) are the same bytes.

#include <array>
#include <bit>
#include <cstdint>
#include <string>
#include <string_view>

#include "corsa/engine/entity_state.h"
#include "output/decimal_text.h"

namespace corsa::engine::detail {

// Decimals of the trajectory's numbers: 1 um for lengths and 1 um/s for speeds, 1 nrad for
// angles (1 nrad of heading moves a point 5 m away by 5 nm). esmini writes 3 decimals; these
// keep every digit a test or a golden comparison could need at a fraction of the cost of the
// shortest round-trip text.
inline constexpr int kLengthDecimals = 6;
inline constexpr int kAngleDecimals = 9;

/// The numeric fields of a row, in file order.
enum RowField : int {
  kFieldX,
  kFieldY,
  kFieldZ,
  kFieldH,
  kFieldP,
  kFieldR,
  kFieldSpeed,
  kFieldS,
  kFieldT,
  kRowFields
};

/// Decimals of each numeric field.
inline constexpr int kFieldDecimals[kRowFields] = {
    kLengthDecimals, kLengthDecimals, kLengthDecimals, kAngleDecimals, kAngleDecimals,
    kAngleDecimals,  kLengthDecimals, kLengthDecimals, kLengthDecimals};

struct RowValues {
  Scaled fields[kRowFields];  ///< s and t only when on_road
  bool on_road = false;
  int lane = 0;
};

/// What a placed entity's row is made of, bit for bit: the numbers (s and t 0 off the road),
/// the road and the lane. Equal inputs give the same row, so a writer that has the row of
/// equal inputs at hand (an entity standing still) need not make it again.
struct RowInputs {
  std::array<uint64_t, kRowFields> bits{};
  bool on_road = false;
  uint32_t road = 0;
  int lane = 0;

  bool operator==(const RowInputs&) const = default;
};

inline RowInputs row_inputs(const EntityState& state) {
  RowInputs in;
  in.bits = {std::bit_cast<uint64_t>(state.pose.x),
             std::bit_cast<uint64_t>(state.pose.y),
             std::bit_cast<uint64_t>(state.pose.z),
             std::bit_cast<uint64_t>(state.pose.h),
             std::bit_cast<uint64_t>(state.pose.p),
             std::bit_cast<uint64_t>(state.pose.r),
             std::bit_cast<uint64_t>(state.speed),
             0,
             0};
  if (state.road) {
    in.on_road = true;
    in.road = state.road->road;
    in.lane = state.road->lane;
    in.bits[kFieldS] = std::bit_cast<uint64_t>(state.road->s);
    in.bits[kFieldT] = std::bit_cast<uint64_t>(state.road->t);
  }
  return in;
}

/// Whether `state` has the inputs `in` (row_inputs(state) == in), stopping at the first field
/// that differs: a moving entity's x mostly.
inline bool same_row_inputs(const RowInputs& in, const EntityState& state) {
  const auto same = [](uint64_t bits, double value) {
    return bits == std::bit_cast<uint64_t>(value);
  };
  if (!same(in.bits[kFieldX], state.pose.x) || !same(in.bits[kFieldY], state.pose.y) ||
      !same(in.bits[kFieldZ], state.pose.z) || !same(in.bits[kFieldH], state.pose.h) ||
      !same(in.bits[kFieldP], state.pose.p) || !same(in.bits[kFieldR], state.pose.r) ||
      !same(in.bits[kFieldSpeed], state.speed) || in.on_road != state.road.has_value()) {
    return false;
  }
  return !state.road ||
         (in.road == state.road->road && in.lane == state.road->lane &&
          same(in.bits[kFieldS], state.road->s) && same(in.bits[kFieldT], state.road->t));
}

/// The row values of an entity's state (inline: the binary recorder makes one per moving
/// entity and tick).
inline RowValues row_values(const EntityState& state) {
  RowValues v;
  v.fields[kFieldX] = scale_decimal<kLengthDecimals>(state.pose.x);
  v.fields[kFieldY] = scale_decimal<kLengthDecimals>(state.pose.y);
  v.fields[kFieldZ] = scale_decimal<kLengthDecimals>(state.pose.z);
  v.fields[kFieldH] = scale_decimal<kAngleDecimals>(state.pose.h);
  v.fields[kFieldP] = scale_decimal<kAngleDecimals>(state.pose.p);
  v.fields[kFieldR] = scale_decimal<kAngleDecimals>(state.pose.r);
  v.fields[kFieldSpeed] = scale_decimal<kLengthDecimals>(state.speed);
  v.on_road = state.road.has_value();
  if (v.on_road) {
    v.lane = state.road->lane;
    v.fields[kFieldS] = scale_decimal<kLengthDecimals>(state.road->s);
    v.fields[kFieldT] = scale_decimal<kLengthDecimals>(state.road->t);
  }
  return v;
}

/// Appends the CSV row `time_text` (with its comma), `name`, the numbers, and `road` (the road
/// id; unused off the road).
void append_row(std::string& out, std::string_view time_text, std::string_view name,
                const RowValues& values, std::string_view road);

/// A field's value read back from its row text: units / 10^decimals (the IEEE quotient is the
/// correctly rounded value of the decimal, what parsing the CSV gives), or the raw value.
double field_value(const Scaled& number, int decimals);

}  // namespace corsa::engine::detail
