// The binary trajectory's reader and its CSV export (docs/trajectory-format.md). Opening checks
// the file's structure, limits and checksum; reading runs the writer's prediction over the
// stored differences, checking each value's range, so a damaged file is an InputError with the
// byte offset of the problem, never a crash or an unbounded allocation.

#include <bit>
#include <climits>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "corsa/core/atomic_file.h"
#include "corsa/core/diagnostic.h"
#include "corsa/engine/outputs.h"
#include "corsa/engine/trajectory_file.h"
#include "output/decimal_text.h"
#include "output/trajectory_codec.h"
#include "output/trajectory_rows.h"

namespace corsa::engine {

namespace codec = detail::trajectory_codec;

namespace {

// a / b rounded toward -infinity (b > 0): ticks before time 0 count like the others.
int64_t floor_div(int64_t a, int64_t b) { return a / b - (a % b != 0 && a < 0 ? 1 : 0); }

// Values beyond this many units cannot come from the writer (it stores them raw).
constexpr int64_t kMaxUnits = 9'000'000'000'000'000;

}  // namespace

struct TrajectoryReader::Impl {
  std::string file;  ///< as named, for messages
  std::string data;
  size_t body = 0;  ///< offset of the first record
  size_t end = 0;   ///< offset of the end record
  double dt = 0.0;
  int64_t per_second = 0;
  int64_t every = 1;
  int64_t first_tick = 0;
  int64_t last_tick = 0;
  size_t frames = 0;
  std::vector<std::string> names;
  std::vector<std::string> roads;
  std::vector<bool> road_known;

  // Iteration.
  size_t pos = 0;
  bool started = false;
  int64_t tick = 0;
  double time = 0.0;
  int64_t last_frame = 0;
  size_t defined = 0;  ///< entities named so far in the iteration
  std::vector<codec::EntityHistory> entities;
  std::vector<bool> touched;

  [[noreturn]] void fail(size_t at, const std::string& what) const {
    throw InputError(Diagnostic{
        Severity::kError, file, 0, -1, "",
        "not a readable Corsa binary trajectory: " + what + " (byte " + std::to_string(at) + ")"});
  }

  uint8_t byte(size_t& at) const {
    if (at >= data.size()) {
      fail(at, "the file ends early");
    }
    return static_cast<uint8_t>(data[at++]);
  }
  uint64_t varint(size_t& at) const {
    const size_t start = at;
    uint64_t value = 0;
    for (int shift = 0; shift < 64; shift += 7) {
      const uint8_t b = byte(at);
      value |= static_cast<uint64_t>(b & 0x7f) << shift;
      if ((b & 0x80) == 0) {
        return value;
      }
    }
    fail(start, "a number runs past 64 bits");
  }
  uint64_t fixed64(size_t& at) const {
    if (data.size() - std::min(at, data.size()) < 8) {
      fail(at, "the file ends early");
    }
    uint64_t value = 0;
    for (int i = 0; i < 8; ++i) {
      value |= static_cast<uint64_t>(static_cast<uint8_t>(data[at + i])) << (8 * i);
    }
    at += 8;
    return value;
  }
  std::string text(size_t& at) const {
    const uint64_t length = varint(at);
    if (length > codec::kMaxName || length > data.size() - std::min(at, data.size())) {
      fail(at, "a name is too long");
    }
    std::string out = data.substr(at, length);
    at += length;
    return out;
  }

  // What the structure check carries from one record to the next.
  struct RecordCheck {
    size_t known = 0;           ///< entities named so far
    int64_t frame_tick = 0;     ///< tick of the last frame
    bool time_pending = false;  ///< a time record waits for its frame
    bool first_frame = true;
    bool off_interval = false;  ///< the last frame's tick lies off the recording interval
  };

  void open(const std::filesystem::path& path);
  void check_records();
  void check_road(size_t& at, size_t start);
  void check_frame(size_t& at, size_t start, RecordCheck& c);
  void check_end(size_t& at, size_t start, const RecordCheck& c);
  /// Skips (check) or applies one entity record of a frame at `at`; false at the frame's end.
  bool entity_record(size_t& at, int64_t& previous, size_t known, bool apply);
  /// The road and lane parts of an entity record (kRoadBit, kLaneBit of `mask`).
  void record_road_lane(size_t& at, uint64_t mask, codec::EntityHistory& h, bool apply) const;
  /// The row fields of an entity record: raw doubles, or predictions plus stored residuals.
  void record_fields(size_t& at, uint64_t mask, uint64_t raw, codec::EntityHistory& h,
                     bool apply) const;
  int64_t next_tick(int64_t from) const;
  void read_frame();
};

void TrajectoryReader::Impl::open(const std::filesystem::path& path) {
  file = path.string();
  data = read_file(path);
  size_t at = 0;
  if (data.size() < codec::kMagic.size() ||
      std::memcmp(data.data(), codec::kMagic.data(), codec::kMagic.size()) != 0) {
    fail(0, "it does not start with " + std::string(codec::kMagic));
  }
  at = codec::kMagic.size();
  const uint8_t version = byte(at);
  if (version != codec::kVersion) {
    fail(at - 1, "version " + std::to_string(version) + " (this Corsa reads version " +
                     std::to_string(codec::kVersion) + ")");
  }
  dt = std::bit_cast<double>(fixed64(at));
  if (!(dt > 0.0) || !std::isfinite(dt)) {
    fail(at - 8, "the step is not a positive number");
  }
  const uint64_t n = varint(at);
  const uint64_t e = varint(at);
  if (n > 1'000'000'000 || e < 1 || e > (uint64_t{1} << 40)) {
    fail(at, "the header's step count or recording interval is out of range");
  }
  per_second = static_cast<int64_t>(n);
  every = static_cast<int64_t>(e);
  first_tick = codec::unzigzag(varint(at));
  body = at;
  check_records();
}

bool TrajectoryReader::Impl::entity_record(size_t& at, int64_t& previous, size_t known,
                                           bool apply) {
  const size_t start = at;
  const uint64_t gap = varint(at);
  if (gap == 0) {
    return false;
  }
  if (gap > known || static_cast<uint64_t>(previous + 1) + gap - 1 >= known) {
    fail(start, "a record names an entity the file has not named");
  }
  const auto index = static_cast<uint32_t>(previous + static_cast<int64_t>(gap));
  previous = index;
  const uint64_t mask = varint(at);
  const uint64_t raw = (mask & codec::kRawBit) != 0 ? varint(at) : 0;
  if ((mask & ~uint64_t{codec::kAllBits}) != 0 || (raw & ~uint64_t{codec::kFieldBits}) != 0 ||
      (raw & mask) != 0 || ((mask & codec::kRawBit) != 0) != (raw != 0) || mask == 0) {
    fail(start, "an entity record's field mask is invalid");
  }
  codec::EntityHistory scratch;
  codec::EntityHistory& h = apply ? entities[index] : scratch;
  if (apply) {
    touched[index] = true;
  }
  if ((mask & codec::kPresenceBit) != 0 && (apply ? h.present : false) &&
      mask == codec::kPresenceBit) {
    h.present = false;  // gone
    return true;
  }
  if (apply) {
    if ((mask & codec::kPresenceBit) != 0) {
      if (h.present) {
        fail(start, "an entity leaves with values");
      }
      h.appear();
    } else if (!h.present) {
      fail(start, "a record for an entity that is not there");
    }
  } else if (mask == codec::kPresenceBit) {
    return true;  // structure only: appearing or leaving, nothing follows either way
  }
  record_road_lane(at, mask, h, apply);
  const int fields = !apply || h.on_road ? detail::kRowFields : detail::kFieldS;
  if (apply && (mask | raw) & (((1u << detail::kRowFields) - 1) & ~((1u << fields) - 1))) {
    fail(start, "road coordinates for an entity off the road");
  }
  record_fields(at, mask, raw, h, apply);
  return true;
}

void TrajectoryReader::Impl::record_road_lane(size_t& at, uint64_t mask, codec::EntityHistory& h,
                                              bool apply) const {
  if ((mask & codec::kRoadBit) != 0) {
    const uint64_t code = varint(at);
    if (code > 0 && (code - 1 >= road_known.size() || !road_known[code - 1])) {
      fail(at, "a record names a road the file has not named");
    }
    h.on_road = code > 0;
    h.road = code > 0 ? static_cast<uint32_t>(code - 1) : 0;
    h.fields[detail::kFieldS].fresh = true;
    h.fields[detail::kFieldT].fresh = true;
  }
  if ((mask & codec::kLaneBit) != 0) {
    const int64_t lane = int64_t{h.lane} + codec::unzigzag(varint(at));
    if (lane < INT_MIN || lane > INT_MAX || (apply && !h.on_road)) {
      fail(at, "a lane is out of range");
    }
    h.lane = static_cast<int>(lane);
  }
}

void TrajectoryReader::Impl::record_fields(size_t& at, uint64_t mask, uint64_t raw,
                                           codec::EntityHistory& h, bool apply) const {
  const int fields = !apply || h.on_road ? detail::kRowFields : detail::kFieldS;
  for (int f = 0; f < fields; ++f) {
    codec::FieldHistory& field = h.fields[f];
    if ((raw >> f) & 1) {
      h.values[f] = detail::Scaled{false, 0, std::bit_cast<double>(fixed64(at))};
      field.fresh = true;
      continue;
    }
    int64_t value = field.predicted();
    if ((mask >> f) & 1) {
      const int64_t residual = codec::unzigzag(varint(at));
      if (residual > kMaxUnits * 4 || residual < -kMaxUnits * 4) {
        fail(at, "a value is out of range");
      }
      value += residual;
    }
    if (!apply) {
      continue;  // structure only: values are checked when read
    }
    if (value > kMaxUnits || value < -kMaxUnits) {
      fail(at, "a value is out of range");
    }
    field.accept(value);
    h.values[f] = detail::Scaled{true, value, 0.0};
  }
}

void TrajectoryReader::Impl::check_records() {
  size_t at = body;
  RecordCheck c;
  c.frame_tick = first_tick;
  while (true) {
    const size_t start = at;
    const uint8_t tag = byte(at);
    if (c.time_pending && tag != codec::kTagFrame) {
      fail(start, "a time record is not followed by a frame");
    }
    switch (tag) {
      case codec::kTagEntity: {
        const uint64_t index = varint(at);
        if (index != names.size() || index >= codec::kMaxEntities) {
          fail(start, "entities are not named in order");
        }
        names.push_back(text(at));
        ++c.known;
        break;
      }
      case codec::kTagRoad:
        check_road(at, start);
        break;
      case codec::kTagTime:
        fixed64(at);
        c.time_pending = true;
        break;
      case codec::kTagFrame:
        check_frame(at, start, c);
        break;
      case codec::kTagEnd:
        check_end(at, start, c);
        return;
      default:
        fail(start, "unknown record");
    }
  }
}

void TrajectoryReader::Impl::check_road(size_t& at, size_t start) {
  const uint64_t index = varint(at);
  if (index >= codec::kMaxRoads) {
    fail(start, "a road index is out of range");
  }
  if (index >= roads.size()) {
    roads.resize(index + 1);
    road_known.resize(index + 1, false);
  }
  roads[index] = text(at);
  road_known[index] = true;
}

void TrajectoryReader::Impl::check_frame(size_t& at, size_t start, RecordCheck& c) {
  c.time_pending = false;
  const int64_t delta = codec::unzigzag(varint(at));
  if (delta < (c.first_frame ? 0 : 1) || delta > (int64_t{1} << 50)) {
    fail(start, "frames are not in tick order");
  }
  if (c.off_interval) {
    fail(start, "a frame follows one off the recording interval");
  }
  c.frame_tick += delta;
  // Only the last tick may lie off the recording interval (checked at the end).
  c.off_interval = c.frame_tick % every != 0;
  c.first_frame = false;
  int64_t previous = -1;
  while (entity_record(at, previous, c.known, false)) {
  }
}

void TrajectoryReader::Impl::check_end(size_t& at, size_t start, const RecordCheck& c) {
  end = start;
  last_tick = codec::unzigzag(varint(at));
  if (data.size() - at != 4) {
    fail(at, "the end record is not at the end");
  }
  uint32_t stored = 0;
  for (int i = 0; i < 4; ++i) {
    stored |= static_cast<uint32_t>(static_cast<uint8_t>(data[at + i])) << (8 * i);
  }
  if (stored != codec::crc32(0, std::string_view(data).substr(0, at))) {
    fail(at, "the checksum does not match (the file is damaged)");
  }
  // Ticks may be negative: a run with a ghost starts before time 0 (controllers/follow_ghost.h).
  if (last_tick < first_tick || (!c.first_frame && c.frame_tick > last_tick) ||
      (c.off_interval && c.frame_tick != last_tick) ||
      (first_tick % every != 0 && first_tick != last_tick)) {
    fail(start, "the recorded ticks do not fit the header");
  }
  frames = 1 + static_cast<size_t>(floor_div(last_tick, every) - floor_div(first_tick, every)) +
           (last_tick % every != 0 && last_tick != first_tick ? 1 : 0);
  if (first_tick % every != 0) {
    frames = 1;
  }
}

int64_t TrajectoryReader::Impl::next_tick(int64_t from) const {
  const int64_t next = (floor_div(from, every) + 1) * every;
  return next <= last_tick ? next : last_tick;
}

void TrajectoryReader::Impl::read_frame() {
  std::fill(touched.begin(), touched.end(), false);
  bool have_time = false;
  while (pos < end) {
    size_t at = pos;
    const uint8_t tag = byte(at);
    if (tag == codec::kTagEntity) {
      varint(at);  // named at open
      ++defined;
      entities.emplace_back();
      touched.push_back(false);
      text(at);
    } else if (tag == codec::kTagRoad) {
      varint(at);
      text(at);
    } else if (tag == codec::kTagTime) {
      size_t peek = at + 8;
      const uint8_t next_tag = byte(peek);
      const int64_t frame_tick = last_frame + codec::unzigzag(varint(peek));
      if (next_tag != codec::kTagFrame || frame_tick != tick) {
        break;
      }
      time = std::bit_cast<double>(fixed64(at));
      have_time = true;
    } else if (tag == codec::kTagFrame) {
      const int64_t frame_tick = last_frame + codec::unzigzag(varint(at));
      if (frame_tick != tick) {
        if (frame_tick < tick) {
          fail(pos, "a frame's tick is not a recorded tick");
        }
        break;
      }
      last_frame = frame_tick;
      int64_t previous = -1;
      while (entity_record(at, previous, defined, true)) {
      }
    } else {
      break;
    }
    pos = at;
  }
  if (!have_time) {
    time = per_second > 0 ? static_cast<double>(tick) / static_cast<double>(per_second)
                          : static_cast<double>(tick) * dt;
  }
  // Entities without a record are where their history predicts.
  for (size_t i = 0; i < entities.size(); ++i) {
    codec::EntityHistory& h = entities[i];
    if (!h.present || touched[i]) {
      continue;
    }
    // (A raw value always comes with a record: here every field is as predicted.)
    const int fields = h.on_road ? detail::kRowFields : detail::kFieldS;
    for (int f = 0; f < fields; ++f) {
      const int64_t value = h.fields[f].predicted();
      if (value > kMaxUnits || value < -kMaxUnits) {
        fail(pos, "a predicted value is out of range");
      }
      h.fields[f].accept(value);
      h.values[f] = detail::Scaled{true, value, 0.0};
    }
  }
}

TrajectoryReader::TrajectoryReader(const std::filesystem::path& file)
    : impl_(std::make_unique<Impl>()) {
  impl_->open(file);
  rewind();
}

TrajectoryReader::~TrajectoryReader() = default;
TrajectoryReader::TrajectoryReader(TrajectoryReader&&) noexcept = default;
TrajectoryReader& TrajectoryReader::operator=(TrajectoryReader&&) noexcept = default;

void TrajectoryReader::rewind() {
  Impl& impl = *impl_;
  impl.pos = impl.body;
  impl.started = false;
  impl.tick = impl.first_tick;
  impl.last_frame = impl.first_tick;
  impl.defined = 0;
  impl.entities.clear();
  impl.touched.clear();
}

bool TrajectoryReader::next(TrajectoryFrame& frame) {
  Impl& impl = *impl_;
  if (impl.started) {
    if (impl.tick >= impl.last_tick) {
      return false;
    }
    impl.tick = impl.next_tick(impl.tick);
  }
  impl.started = true;
  impl.read_frame();
  frame.tick = impl.tick;
  frame.time = impl.time;
  frame.rows.clear();
  for (uint32_t i = 0; i < impl.entities.size(); ++i) {
    const codec::EntityHistory& h = impl.entities[i];
    if (!h.present) {
      continue;
    }
    TrajectoryRow row;
    row.entity = i;
    const auto value = [&](int f) {
      return detail::field_value(h.values[f], detail::kFieldDecimals[f]);
    };
    row.x = value(detail::kFieldX);
    row.y = value(detail::kFieldY);
    row.z = value(detail::kFieldZ);
    row.h = value(detail::kFieldH);
    row.p = value(detail::kFieldP);
    row.r = value(detail::kFieldR);
    row.speed = value(detail::kFieldSpeed);
    row.on_road = h.on_road;
    if (h.on_road) {
      row.road = h.road;
      row.lane = h.lane;
      row.s = value(detail::kFieldS);
      row.t = value(detail::kFieldT);
    }
    frame.rows.push_back(row);
  }
  return true;
}

void TrajectoryReader::append_csv(std::string& out) const {
  const Impl& impl = *impl_;
  char time_text[detail::kDecimalTextMax + 1];
  char* time_end = detail::write_exact(time_text, impl.time);
  *time_end++ = ',';
  const std::string_view time(time_text, static_cast<size_t>(time_end - time_text));
  for (uint32_t i = 0; i < impl.entities.size(); ++i) {
    const codec::EntityHistory& h = impl.entities[i];
    if (!h.present) {
      continue;
    }
    detail::RowValues values;
    for (int f = 0; f < detail::kRowFields; ++f) {
      values.fields[f] = h.values[f];
    }
    values.on_road = h.on_road;
    values.lane = h.lane;
    detail::append_row(out, time, impl.names[i], values,
                       h.on_road ? std::string_view(impl.roads[h.road]) : std::string_view());
  }
}

double TrajectoryReader::dt() const { return impl_->dt; }
int64_t TrajectoryReader::every() const { return impl_->every; }
int64_t TrajectoryReader::first_tick() const { return impl_->first_tick; }
int64_t TrajectoryReader::last_tick() const { return impl_->last_tick; }
size_t TrajectoryReader::frame_count() const { return impl_->frames; }
size_t TrajectoryReader::entity_count() const { return impl_->names.size(); }
const std::string& TrajectoryReader::entity_name(uint32_t entity) const {
  return impl_->names.at(entity);
}
size_t TrajectoryReader::road_count() const { return impl_->roads.size(); }
const std::string& TrajectoryReader::road_id(uint32_t road) const { return impl_->roads.at(road); }

std::string trajectory_csv_of(const std::filesystem::path& binary) {
  TrajectoryReader reader(binary);
  std::string out = kTrajectoryHeader;
  TrajectoryFrame frame;
  while (reader.next(frame)) {
    reader.append_csv(out);
  }
  return out;
}

void export_trajectory_csv(const std::filesystem::path& binary, const std::filesystem::path& csv) {
  write_file_atomic(csv, trajectory_csv_of(binary));
}

bool is_binary_trajectory(const std::filesystem::path& file) {
  return file.extension() == ".corsatraj";
}

}  // namespace corsa::engine
