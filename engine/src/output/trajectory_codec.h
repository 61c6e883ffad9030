#pragma once

// The pieces of the binary trajectory format (docs/trajectory-format.md) that its writer
// (trajectory_binary.cpp) and reader (trajectory_reader.cpp) share: the header, record tags,
// field bits, variable-length integers, the per-field prediction and the checksum. Both sides
// run the same prediction over the same integers, so a value costs only its surprise.

#include <array>
#include <cstdint>
#include <string>
#include <string_view>

#include "output/trajectory_rows.h"

namespace corsa::engine::detail::trajectory_codec {

inline constexpr std::string_view kMagic = "CORSATRJ";
inline constexpr uint8_t kVersion = 1;

/// Record tags.
enum Tag : uint8_t {
  kTagEntity = 'E',  ///< varint index, varint length, name bytes
  kTagRoad = 'R',    ///< varint road index, varint length, id bytes
  kTagTime = 'T',    ///< 8 bytes: the next frame's time, when it is not tick / per_second
  kTagFrame = 'F',   ///< varint tick - previous frame's tick, entity records, varint 0
  kTagEnd = 'Z',     ///< varint last tick, 4 bytes CRC-32 of every byte before them
};

/// Bits of an entity record's mask: the numeric fields (RowField order) whose value is not the
/// predicted one, then the lane, the road, presence and raw values.
inline constexpr uint32_t kLaneBit = 1u << kRowFields;
inline constexpr uint32_t kRoadBit = 1u << (kRowFields + 1);
inline constexpr uint32_t kPresenceBit = 1u << (kRowFields + 2);
inline constexpr uint32_t kRawBit = 1u << (kRowFields + 3);
inline constexpr uint32_t kFieldBits = (1u << kRowFields) - 1;
inline constexpr uint32_t kAllBits = (1u << (kRowFields + 4)) - 1;

/// Limits a reader holds a file to (a damaged file must not make it allocate without end).
inline constexpr uint64_t kMaxEntities = 1u << 24;
inline constexpr uint64_t kMaxRoads = 1u << 24;
inline constexpr uint64_t kMaxName = 1u << 16;

inline void put_varint(std::string& out, uint64_t value) {
  while (value >= 0x80) {
    out.push_back(static_cast<char>((value & 0x7f) | 0x80));
    value >>= 7;
  }
  out.push_back(static_cast<char>(value));
}

/// The same into a buffer with room for 10 bytes; returns the end.
inline char* put_varint(char* out, uint64_t value) {
  while (value >= 0x80) {
    *out++ = static_cast<char>((value & 0x7f) | 0x80);
    value >>= 7;
  }
  *out++ = static_cast<char>(value);
  return out;
}

inline uint64_t zigzag(int64_t value) {
  return (static_cast<uint64_t>(value) << 1) ^ static_cast<uint64_t>(value >> 63);
}
inline int64_t unzigzag(uint64_t value) {
  return static_cast<int64_t>(value >> 1) ^ -static_cast<int64_t>(value & 1);
}

inline void put_fixed64(std::string& out, uint64_t value) {
  for (int i = 0; i < 8; ++i) {
    out.push_back(static_cast<char>((value >> (8 * i)) & 0xff));
  }
}
inline char* put_fixed64(char* out, uint64_t value) {
  for (int i = 0; i < 8; ++i) {
    *out++ = static_cast<char>((value >> (8 * i)) & 0xff);
  }
  return out;
}

/// One numeric field's history: the next value is predicted to repeat the last change (a
/// vehicle at constant speed on a straight costs nothing); `fresh` after the entity appears, its
/// road changes or a raw value, when the prediction is 0 (the value itself is stored).
struct FieldHistory {
  int64_t last = 0;
  int64_t change = 0;
  bool fresh = true;

  int64_t predicted() const { return fresh ? 0 : last + change; }
  void accept(int64_t value) {
    change = fresh ? 0 : value - last;
    last = value;
    fresh = false;
  }
};

/// What both sides know of an entity between recorded ticks.
struct EntityHistory {
  bool present = false;
  bool on_road = false;
  uint32_t road = 0;
  int lane = 0;
  std::array<FieldHistory, kRowFields> fields;
  std::array<Scaled, kRowFields> values;  ///< the current values (the reader's rows)

  void appear() {
    present = true;
    on_road = false;
    road = 0;
    lane = 0;
    fields = {};
  }
};

/// CRC-32 (IEEE 802.3, reflected, as zlib computes it), updated over `data`.
uint32_t crc32(uint32_t crc, std::string_view data);

}  // namespace corsa::engine::detail::trajectory_codec
