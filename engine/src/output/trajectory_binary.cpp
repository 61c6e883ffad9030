// The binary trajectory's recorder: at each recorded tick the encoder (output/trajectory_encoder.h)
// either reads the entities' states at once on the simulation's thread, or every entity's row
// inputs are copied and handed, in batches of ticks, to a writer thread of its own, which then
// encodes and writes while the simulation steps on. The encoder reads the rows in tick order
// either way, so the file is the same bytes on either thread, and a run may move from the first
// to the second (RecordingThread::kAuto) at any tick.

#include <algorithm>
#include <bit>
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <exception>
#include <mutex>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "corsa/engine/trajectory_file.h"
#include "output/trajectory_encoder.h"

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#endif

namespace corsa::engine {

namespace {

/// Recorded ticks copied out of the simulation, in order, with the entity names and road ids
/// first needed by them.
struct RecordedTicks {
  std::vector<detail::TickRowsHead> ticks;
  std::vector<detail::TrajectoryRowCopy> rows;  ///< the first `row_count` are the ticks' rows
  size_t row_count = 0;
  std::vector<std::string> names;  ///< of the entities first counted by these ticks, in order
  std::vector<std::pair<uint32_t, const std::string*>> roads;  ///< first met by these ticks

  void clear() {
    ticks.clear();
    row_count = 0;
    names.clear();
    roads.clear();
  }
};

// A batch is handed to the writer thread once it holds this many rows (640 KiB of copies, which
// stay in the second-level cache: a hand-over, one wake-up of the writer, per 341 ticks of 24
// entities), and at most this many batches wait for it: beyond that the simulation waits for
// the writer. With batches of 2,048 rows the wake-ups cost the simulation's thread as much as
// the copies; with 32,768 (2.5 MiB) the writer woke a quarter as often, but the copies, written
// to memory beyond the cache, cost the simulation's thread more (long_motorway, 1,200 s: its CPU
// time 0.711-0.728 s at 8,192 rows, 0.721-0.749 s at 32,768, 0.675-0.694 s without recording).
constexpr size_t kRowsPerBatch = 8192;
constexpr size_t kBatchesQueued = 4;

// RecordingThread::kAuto: the rows coded on the caller's thread are summed over windows of this
// many recorded ticks; a window that coded this many rows a tick on average moves the encoding
// to the writer thread for the rest of the run. Below it the writer costs more CPU time than it
// saves (the copies of every row, standing ones included, and the rows read on the other core:
// long_motorway's 24 moving vehicles, 14% of the run's CPU time on the caller's thread, 17-19% on
// the writer); from about 200 moving vehicles it costs no more (the encoder's state of every
// entity no longer stays in the simulation's caches from tick to tick, but does in the
// writer's). 128 is also the entity count from which the step itself is shared out over threads.
// (docs/performance/recording-writers-and-csv.md, "Recording on the caller's thread unless the
// ticks' work pays for a writer".)
constexpr uint32_t kAutoWindowTicks = 256;
constexpr uint64_t kWriterRowsPerTick = 128;

// The copy of `state` into the batch's row `row` (detail::copy_row's). On x86-64 its words are
// stored past the cache (non-temporal stores): a batch's rows were last read by the writer
// thread on the other core, so that a store into the cache would first fetch each line back
// from there (the copies' main cost on the simulation's thread); the writer reads them from
// memory instead. The stores are ordered before the hand-over by a fence (hand_over).
inline void copy_batch_row(detail::TrajectoryRowCopy& row, const EntityState& state) {
#if defined(__x86_64__) && defined(__GNUC__)
  using detail::TrajectoryRowCopy;
  static_assert(sizeof(TrajectoryRowCopy) == 88 && offsetof(TrajectoryRowCopy, road) == 72 &&
                offsetof(TrajectoryRowCopy, lane) == 76 &&
                offsetof(TrajectoryRowCopy, placed) == 80 &&
                offsetof(TrajectoryRowCopy, on_road) == 81);
  auto* words = reinterpret_cast<long long*>(&row);
  const auto put = [&words](int word, uint64_t value) {
    _mm_stream_si64(words + word, static_cast<long long>(value));
  };
  put(detail::kFieldX, std::bit_cast<uint64_t>(state.pose.x));
  put(detail::kFieldY, std::bit_cast<uint64_t>(state.pose.y));
  put(detail::kFieldZ, std::bit_cast<uint64_t>(state.pose.z));
  put(detail::kFieldH, std::bit_cast<uint64_t>(state.pose.h));
  put(detail::kFieldP, std::bit_cast<uint64_t>(state.pose.p));
  put(detail::kFieldR, std::bit_cast<uint64_t>(state.pose.r));
  put(detail::kFieldSpeed, std::bit_cast<uint64_t>(state.speed));
  const bool on_road = state.road.has_value();
  put(detail::kFieldS, on_road ? std::bit_cast<uint64_t>(state.road->s) : 0);
  put(detail::kFieldT, on_road ? std::bit_cast<uint64_t>(state.road->t) : 0);
  put(9, on_road ? uint64_t{state.road->road} |
                       (uint64_t{static_cast<uint32_t>(state.road->lane)} << 32)
                 : 0);
  put(10, uint64_t{state.placed} | (uint64_t{on_road} << 8));
#else
  detail::copy_row(row, state);
#endif
}

}  // namespace

struct BinaryTrajectoryRecorder::State {
  State(std::filesystem::path path, int64_t every_in, RecordingThread thread_in)
      : encoder(std::move(path), every_in),
        every(every_in < 1 ? 1 : every_in),
        thread(thread_in),
        filling(std::make_unique<RecordedTicks>()) {}
  ~State();

  detail::TrajectoryEncoder encoder;
  int64_t every;
  RecordingThread thread;  ///< kAuto until it moves to kWriter (or for the whole run)
  bool started = false;
  double dt = 0.0;
  int64_t last_recorded = 0;
  size_t named_entities = 0;
  std::vector<bool> road_seen;
  std::unique_ptr<RecordedTicks> filling;  ///< the ticks not yet handed to the encoder
  // kAuto: the recorded ticks and the rows they coded in the current window.
  uint32_t window_ticks = 0;
  uint64_t window_rows = 0;

  // The writer thread and its queue (RecordingThread::kWriter).
  std::thread writer;
  std::mutex mutex;
  std::condition_variable ready;  ///< a batch was queued, or the queue closed
  std::condition_variable room;   ///< a batch was taken
  std::deque<std::unique_ptr<RecordedTicks>> queued;
  std::vector<std::unique_ptr<RecordedTicks>> spare;  ///< encoded batches, for reuse
  bool closed = false;
  bool abandoned = false;    ///< destroyed without finish: the queued ticks are dropped
  std::exception_ptr error;  ///< the encoder's, rethrown by finish

  /// Encodes, or copies, the rows of the simulation's current tick, `tick`. (Inlined into
  /// on_step, with what a tick seldom does out of line: a call less on every tick.)
  [[gnu::always_inline]] inline void capture(const Simulation& simulation, int64_t tick);
  /// Names the entities first counted by the current tick to the encoder.
  [[gnu::noinline]] void name_entities(const Simulation& simulation, size_t count);
  /// At the first recorded tick: the step, and the writer thread when there is one. (Apart
  /// from capture, as is copy_rows, so that the tick's path on the caller's thread stays short.)
  [[gnu::noinline]] void begin(const Simulation& simulation);
  /// kAuto, at the end of a window of ticks (capture sums their coded rows): moves to the writer
  /// thread when the window's work pays for it.
  [[gnu::noinline]] void weigh();
  [[gnu::noinline]] void copy_rows(const Simulation& simulation, int64_t tick);
  void encode(RecordedTicks& batch);
  void hand_over();
  void serve();
  /// Encodes what is left, stops the writer and ends the file at `last_tick`.
  void finish(int64_t last_tick);
};

inline void BinaryTrajectoryRecorder::State::capture(const Simulation& simulation, int64_t tick) {
  if (!started) [[unlikely]] {
    begin(simulation);
  }
  last_recorded = tick;
  if (thread == RecordingThread::kWriter) {
    copy_rows(simulation, tick);
    return;
  }
  // Straight from the states, no copy: the encoder is done with them before the next step.
  // (The rows made where they are passed: a copy of the states less.)
  const detail::EntityStateRows rows{simulation.states(), &simulation, simulation.state_changes()};
  const size_t count = rows.states.size();
  if (named_entities < count) [[unlikely]] {
    name_entities(simulation, count);
  }
  const uint32_t coded =
      encoder.record(dt, {tick, simulation.time(), static_cast<uint32_t>(count)}, rows);
  if (thread == RecordingThread::kAuto) {
    window_rows += coded;
    if (++window_ticks == kAutoWindowTicks) [[unlikely]] {
      weigh();
    }
  }
}

void BinaryTrajectoryRecorder::State::name_entities(const Simulation& simulation, size_t count) {
  for (; named_entities < count; ++named_entities) {
    encoder.name_entity(simulation.entity(named_entities).name);
  }
}

void BinaryTrajectoryRecorder::State::begin(const Simulation& simulation) {
  started = true;
  dt = simulation.dt();
  if (thread == RecordingThread::kWriter) {
    writer = std::thread([this] { serve(); });
  }
}

void BinaryTrajectoryRecorder::State::weigh() {
  if (window_rows >= kAutoWindowTicks * kWriterRowsPerTick) {
    // From the next tick on the rows are copied for the writer, which alone uses the encoder
    // from then on (the recorder's road_seen starts empty: the roads the encoder already wrote
    // are named to it again, and not written twice).
    thread = RecordingThread::kWriter;
    writer = std::thread([this] { serve(); });
  }
  window_ticks = 0;
  window_rows = 0;
}

void BinaryTrajectoryRecorder::State::copy_rows(const Simulation& simulation, int64_t tick) {
  // The states read where they lie, without a call per entity (as the encoder does on the
  // caller's thread).
  const EntityStates states = simulation.states();
  const size_t count = states.size();
  RecordedTicks& batch = *filling;
  for (; named_entities < count; ++named_entities) {
    batch.names.push_back(simulation.entity(named_entities).name);
  }
  const size_t first = batch.row_count;
  if (batch.rows.size() < first + count) {
    // Grown as needed (a short run holds only its rows), reused from batch to batch.
    batch.rows.resize(std::max(first + count, 2 * batch.rows.size()));
  }
  detail::TrajectoryRowCopy* rows = batch.rows.data() + first;
  for (size_t i = 0; i < count; ++i) {
    const EntityState& state = states[i];
    copy_batch_row(rows[i], state);
    if (!state.road.has_value()) {
      continue;
    }
    const uint32_t road = state.road->road;
    if (road >= road_seen.size() || !road_seen[road]) [[unlikely]] {
      road_seen.resize(std::max<size_t>(road_seen.size(), road + 1), false);
      road_seen[road] = true;
      batch.roads.emplace_back(road, &simulation.road_id(road));
    }
  }
  batch.row_count = first + count;
  batch.ticks.push_back({tick, simulation.time(), static_cast<uint32_t>(count)});
  if (batch.row_count >= kRowsPerBatch) {
    hand_over();
  }
}

void BinaryTrajectoryRecorder::State::encode(RecordedTicks& batch) {
  for (std::string& name : batch.names) {
    encoder.name_entity(std::move(name));
  }
  for (const auto& [road, id] : batch.roads) {
    encoder.name_road(road, id);
  }
  const detail::TrajectoryRowCopy* rows = batch.rows.data();
  for (const detail::TickRowsHead& head : batch.ticks) {
    encoder.record(dt, head, rows);
    rows += head.entities;
  }
}

void BinaryTrajectoryRecorder::State::hand_over() {
#if defined(__x86_64__) && defined(__GNUC__)
  _mm_sfence();  // the rows' non-temporal stores (copy_batch_row) before the batch is handed over
#endif
  {
    std::unique_lock lock(mutex);
    room.wait(lock, [this] { return queued.size() < kBatchesQueued; });
    queued.push_back(std::move(filling));
    if (!spare.empty()) {
      filling = std::move(spare.back());
      spare.pop_back();
    }
  }
  ready.notify_one();
  if (!filling) {
    filling = std::make_unique<RecordedTicks>();
  }
}

void BinaryTrajectoryRecorder::State::serve() {
  for (;;) {
    std::unique_ptr<RecordedTicks> batch;
    bool skip = false;
    {
      std::unique_lock lock(mutex);
      ready.wait(lock, [this] { return !queued.empty() || closed; });
      if (queued.empty()) {
        return;
      }
      batch = std::move(queued.front());
      queued.pop_front();
      skip = abandoned || error != nullptr;
    }
    if (!skip) {
      try {
        encode(*batch);
      } catch (...) {
        const std::lock_guard lock(mutex);
        error = std::current_exception();
      }
    }
    batch->clear();
    {
      const std::lock_guard lock(mutex);
      spare.push_back(std::move(batch));
    }
    room.notify_one();
  }
}

void BinaryTrajectoryRecorder::State::finish(int64_t last_tick) {
  if (writer.joinable()) {
    if (!filling->ticks.empty()) {
      hand_over();
    }
    {
      const std::lock_guard lock(mutex);
      closed = true;
    }
    ready.notify_one();
    writer.join();
    if (error) {
      std::rethrow_exception(error);
    }
  }
  encoder.finish(last_tick);
}

BinaryTrajectoryRecorder::State::~State() {
  if (writer.joinable()) {
    {
      const std::lock_guard lock(mutex);
      closed = true;
      abandoned = true;
    }
    ready.notify_one();
    writer.join();
  }
}

BinaryTrajectoryRecorder::BinaryTrajectoryRecorder(std::filesystem::path file, int64_t every,
                                                   RecordingThread thread)
    : state_(std::make_unique<State>(std::move(file), every, thread)) {}

BinaryTrajectoryRecorder::~BinaryTrajectoryRecorder() = default;

void BinaryTrajectoryRecorder::on_step(const Simulation& simulation) {
  State& state = *state_;
  const int64_t tick = simulation.tick();
  // Every tick recorded (the default) needs no division.
  if (state.every != 1 && tick % state.every != 0) {
    return;
  }
  if (state.started && tick <= state.last_recorded) {
    // A tick run again (esmini's ghost restart, whose rows the CSV holds twice): the binary
    // file keeps each tick once, as first recorded (docs/trajectory-format.md).
    return;
  }
  state.capture(simulation, tick);
}

bool BinaryTrajectoryRecorder::on_writer_thread() const {
  return state_->thread == RecordingThread::kWriter;
}

void BinaryTrajectoryRecorder::finish(const Simulation& simulation) {
  State& state = *state_;
  if (!state.started || state.last_recorded < simulation.tick()) {
    state.capture(simulation, simulation.tick());
  }
  // A run that ends while a ghost restart runs ticks again ends at its last tick recorded.
  state.finish(std::max(simulation.tick(), state.last_recorded));
}

}  // namespace corsa::engine
