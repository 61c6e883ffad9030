#include <algorithm>
#include <charconv>
#include <cstring>
#include <string_view>
#include <vector>

#include "corsa/engine/outputs.h"
#include "output/decimal_text.h"
#include "output/trajectory_rows.h"

namespace corsa::engine {

namespace detail {

namespace {

template <int Decimals>
char* put_fixed(char* out, double value) {
  out = write_fixed<Decimals>(out, value);
  *out++ = ',';
  return out;
}

template <int Decimals>
char* put(char* out, const Scaled& number) {
  out = write_scaled<Decimals>(out, number);
  *out++ = ',';
  return out;
}

char* put(char* out, std::string_view text) {
  std::memcpy(out, text.data(), text.size());
  return out + text.size();
}

}  // namespace

void append_row(std::string& out, std::string_view time_text, std::string_view name,
                const RowValues& v, std::string_view road) {
  // The row is written in place (one resize instead of an append per field, which was a third
  // of the row's cost): room for the strings, ten numbers, the lane and separators.
  const size_t room =
      time_text.size() + name.size() + road.size() + 10 * (kDecimalTextMax + 1) + 16;
  const size_t start = out.size();
  out.resize(start + room);
  char* p = out.data() + start;
  p = put(p, time_text);
  p = put(p, name);
  *p++ = ',';
  p = put<kLengthDecimals>(p, v.fields[kFieldX]);
  p = put<kLengthDecimals>(p, v.fields[kFieldY]);
  p = put<kLengthDecimals>(p, v.fields[kFieldZ]);
  p = put<kAngleDecimals>(p, v.fields[kFieldH]);
  p = put<kAngleDecimals>(p, v.fields[kFieldP]);
  p = put<kAngleDecimals>(p, v.fields[kFieldR]);
  p = put<kLengthDecimals>(p, v.fields[kFieldSpeed]);
  if (v.on_road) {
    p = put(p, road);
    *p++ = ',';
    p = std::to_chars(p, p + 12, v.lane).ptr;
    *p++ = ',';
    p = put<kLengthDecimals>(p, v.fields[kFieldS]);
    p = write_scaled<kLengthDecimals>(p, v.fields[kFieldT]);
  } else {
    p = put(p, ",,,");
  }
  *p++ = '\n';
  out.resize(static_cast<size_t>(p - out.data()));
}

double field_value(const Scaled& number, int decimals) {
  return number.exact ? static_cast<double>(number.units) / decimal_text::kScale[decimals]
                      : number.raw + 0.0;
}

}  // namespace detail

TrajectoryRecorder::TrajectoryRecorder(std::filesystem::path file, int64_t every)
    : file_(std::move(file)), every_(every < 1 ? 1 : every), cache_(std::make_unique<RowCache>()) {
  const std::string_view header = kTrajectoryHeader;
  std::memcpy(room(header.size()), header.data(), header.size());
  used_ = header.size();
}

namespace {

// Grows `buffer` to hold `needed` characters (at least doubling it); apart from room's check so
// that the check, made once per row, is inlined where it is made.
void grow_buffer(std::string& buffer, size_t needed) {
  buffer.resize(std::max(2 * buffer.size(), needed));
}

}  // namespace

inline char* TrajectoryRecorder::room(size_t count) {
  if (buffer_.size() < used_ + count) [[unlikely]] {
    grow_buffer(buffer_, used_ + count);
  }
  return buffer_.data() + used_;
}

namespace {

// Characters the row of an entity named `name` on road `road` (null: off the road) may take
// after its time field.
size_t row_room(std::string_view name, const std::string* road) {
  return name.size() + (road ? road->size() : 0) + 10 * (detail::kDecimalTextMax + 1) + 16;
}

// Writes the row of entity `name` in `state` after its time field at `p` (row_room characters
// there): "name,x,...,t\n" (`road`: the road's id, null off the road); returns its end.
// Flattened: the number writers are inlined into it (the compiler kept write_fixed and
// write_units as calls, two per number, a fifth of the row's instructions).
[[gnu::flatten]] char* write_row_tail(char* p, std::string_view name, const EntityState& state,
                                      const std::string* road) {
  // The numbers straight from the state (write_fixed is write_scaled of scale_decimal, what
  // append_row writes from RowValues), without building the RowValues: 15% of a row's cost.
  p = detail::put(p, name);
  *p++ = ',';
  p = detail::put_fixed<detail::kLengthDecimals>(p, state.pose.x);
  p = detail::put_fixed<detail::kLengthDecimals>(p, state.pose.y);
  p = detail::put_fixed<detail::kLengthDecimals>(p, state.pose.z);
  p = detail::put_fixed<detail::kAngleDecimals>(p, state.pose.h);
  p = detail::put_fixed<detail::kAngleDecimals>(p, state.pose.p);
  p = detail::put_fixed<detail::kAngleDecimals>(p, state.pose.r);
  p = detail::put_fixed<detail::kLengthDecimals>(p, state.speed);
  if (road) {
    p = detail::put(p, *road);
    *p++ = ',';
    p = std::to_chars(p, p + 12, state.road->lane).ptr;
    *p++ = ',';
    p = detail::put_fixed<detail::kLengthDecimals>(p, state.road->s);
    p = detail::write_fixed<detail::kLengthDecimals>(p, state.road->t);
  } else {
    p = detail::put(p, ",,,");
  }
  *p++ = '\n';
  return p;
}

// write_row_tail at the end of `out`.
void append_row_tail(std::string& out, std::string_view name, const EntityState& state,
                     const std::string* road) {
  const size_t start = out.size();
  out.resize(start + row_room(name, road));
  char* const end = write_row_tail(out.data() + start, name, state, road);
  out.resize(static_cast<size_t>(end - out.data()));
}

// The time field of the current tick's rows: the exact text of the time (shortest round-trip,
// so that rows can be matched to steps), made once per tick, and its comma.
std::string_view time_field(const Simulation& simulation,
                            char (&text)[detail::kDecimalTextMax + 1]) {
  char* end = detail::write_exact(text, simulation.time());
  *end++ = ',';
  return std::string_view(text, static_cast<size_t>(end - text));
}

const std::string* road_of(const Simulation& simulation, const EntityState& state) {
  return state.road ? &simulation.road_id(state.road->road) : nullptr;
}

}  // namespace

/// Per entity: the inputs of its last row and, once they repeat, the row's text after the time
/// (an entity standing still gets its row copied instead of written again); its name, and the
/// roads' ids, kept here so that a row asks the simulation only for the entity's state.
struct TrajectoryRecorder::RowCache {
  struct Entry {
    bool valid = false;
    detail::RowInputs inputs;
    std::string text;  ///< empty until the inputs repeat
    std::string name;  ///< the entity's (an entity index keeps its name for the whole run)
  };
  std::vector<Entry> entries;
  /// By road index: its OpenDRIVE id (Simulation::road_id, which the map holds), null until a
  /// row on that road needs it.
  std::vector<const std::string*> road_ids;

  const std::string* road_of(const Simulation& simulation, const EntityState& state) {
    if (!state.road) {
      return nullptr;
    }
    const uint32_t road = state.road->road;
    if (road >= road_ids.size()) [[unlikely]] {
      road_ids.resize(road + 1, nullptr);
    }
    const std::string*& id = road_ids[road];
    if (id == nullptr) [[unlikely]] {
      id = &simulation.road_id(road);
    }
    return id;
  }
};

TrajectoryRecorder::~TrajectoryRecorder() = default;

void TrajectoryRecorder::append_rows(const Simulation& simulation, std::string& out) {
  char time_text[detail::kDecimalTextMax + 1];
  const std::string_view time = time_field(simulation, time_text);
  for (size_t i = 0; i < simulation.entity_count(); ++i) {
    const EntityState& state = simulation.state(i);
    if (!state.placed) {
      continue;  // not added yet or deleted (AddEntityAction, DeleteEntityAction, traffic)
    }
    out += time;
    append_row_tail(out, simulation.entity(i).name, state, road_of(simulation, state));
  }
}

void TrajectoryRecorder::append_cached_rows(const Simulation& simulation) {
  char time_text[detail::kDecimalTextMax + 1];
  const std::string_view time = time_field(simulation, time_text);
  RowCache& cache = *cache_;
  auto& entries = cache.entries;
  const size_t count = simulation.entity_count();
  for (size_t i = entries.size(); i < count; ++i) {
    entries.emplace_back().name = simulation.entity(i).name;
  }
  for (size_t i = 0; i < count; ++i) {
    const EntityState& state = simulation.state(i);
    RowCache::Entry& entry = entries[i];
    if (!state.placed) {
      entry.valid = false;
      continue;
    }
    const std::string& name = entry.name;
    const std::string* road = cache.road_of(simulation, state);
    if (entry.valid && detail::same_row_inputs(entry.inputs, state)) {
      if (entry.text.empty()) {
        append_row_tail(entry.text, name, state, road);
      }
      char* p = room(time.size() + entry.text.size());
      std::memcpy(p, time.data(), time.size());
      std::memcpy(p + time.size(), entry.text.data(), entry.text.size());
      used_ += time.size() + entry.text.size();
      continue;
    }
    entry.valid = true;
    entry.inputs = detail::row_inputs(state);
    entry.text.clear();
    // Written in place behind the rows before it: one check of the room per row. The time is
    // copied at its buffer's fixed size (no memcpy call; the row's room holds it, and the row
    // overwrites what follows the time's end).
    char* const start = room(time.size() + row_room(name, road));
    std::memcpy(start, time_text, sizeof time_text);
    char* const end = write_row_tail(start + time.size(), name, state, road);
    used_ += static_cast<size_t>(end - start);
  }
}

void TrajectoryRecorder::on_step(const Simulation& simulation) {
  if (simulation.tick() % every_ != 0) {
    return;
  }
  append_cached_rows(simulation);
  last_recorded_ = simulation.tick();
  if (used_ > (1u << 20)) {
    flush();
  }
}

void TrajectoryRecorder::flush() {
  file_.stream().write(buffer_.data(), static_cast<std::streamsize>(used_));
  used_ = 0;
}

void TrajectoryRecorder::finish(const Simulation& simulation) {
  if (last_recorded_ != simulation.tick()) {
    append_cached_rows(simulation);
    last_recorded_ = simulation.tick();
  }
  flush();
  file_.commit();
}

}  // namespace corsa::engine
