#pragma once

// The binary trajectory (`corsa run --record run.corsatraj`, docs/trajectory-format.md): the
// same rows as the trajectory CSV (every present entity at every recorded tick), stored as the
// integers of their decimals and only where they differ from what the previous ticks predict, so
// that an entity standing still or driving straight at a steady speed costs nothing. The CSV
// export of a binary trajectory is byte for byte the CSV the run would have written.
//
//   corsa::engine::TrajectoryReader reader("run.corsatraj");
//   corsa::engine::TrajectoryFrame frame;
//   while (reader.next(frame)) {
//     for (const auto& row : frame.rows) { ... reader.entity_name(row.entity), row.x ... }
//   }

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "corsa/core/atomic_file.h"
#include "corsa/engine/simulation.h"

namespace corsa::engine {

/// Where the binary trajectory is encoded and written.
enum class RecordingThread : uint8_t {
  kCaller,  ///< in on_step, on the simulation's thread
  /// On a thread of the recorder's own, fed with copies of the recorded ticks' rows in batches,
  /// so that encoding and writing overlap with the next steps on a second core. The file is the
  /// same bytes. It costs more CPU time in all than kCaller (the copies, and the rows read on
  /// another core): it saves wall time when a second core is free.
  kWriter,
  /// On the caller's thread while the ticks' work is small, moving to a writer thread (once,
  /// for the rest of the run) when the recorded ticks code many rows: many entities that move.
  /// The file is the same bytes.
  kAuto,
};

/// Records the binary trajectory while the simulation runs: register it with
/// Simulation::add_observer before the first step, call finish() after the run (as
/// TrajectoryRecorder, the CSV one).
class BinaryTrajectoryRecorder final : public SimulationObserver {
 public:
  /// `every`: record every N-th tick (tick 0 and the last tick are always recorded).
  explicit BinaryTrajectoryRecorder(std::filesystem::path file, int64_t every = 1,
                                    RecordingThread thread = RecordingThread::kCaller);
  ~BinaryTrajectoryRecorder() override;
  void on_step(const Simulation& simulation) override;
  /// Records the final tick if it was skipped and commits the file (throws InputError when it
  /// cannot be written).
  void finish(const Simulation& simulation);
  /// Whether the ticks are now encoded on a writer thread (kWriter from the first recorded
  /// tick; kAuto once its ticks' work moved it there).
  bool on_writer_thread() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

/// One entity at one recorded tick: the numbers of its trajectory CSV row, read back from their
/// decimals (lengths and speeds to 1e-6, angles to 1e-9; the same doubles as parsing the CSV).
struct TrajectoryRow {
  uint32_t entity = 0;               ///< index, in document order (TrajectoryReader::entity_name)
  double x = 0.0, y = 0.0, z = 0.0;  ///< m, world frame
  double h = 0.0, p = 0.0, r = 0.0;  ///< rad
  double speed = 0.0;                ///< m/s
  bool on_road = false;              ///< false: road, lane, s and t are empty in the CSV
  uint32_t road = 0;                 ///< index of the road id (TrajectoryReader::road_id)
  int lane = 0;
  double s = 0.0, t = 0.0;  ///< m, road coordinates
};

/// Every present entity at one recorded tick, in entity order.
struct TrajectoryFrame {
  int64_t tick = 0;
  double time = 0.0;  ///< s
  std::vector<TrajectoryRow> rows;
};

/// Reads a binary trajectory tick by tick. The whole file is checked (structure, limits and
/// checksum) when it is opened: a file that is not a complete Corsa trajectory is an InputError
/// naming it and the byte offset of the problem, never a crash.
class TrajectoryReader {
 public:
  explicit TrajectoryReader(const std::filesystem::path& file);
  ~TrajectoryReader();
  TrajectoryReader(TrajectoryReader&&) noexcept;
  TrajectoryReader& operator=(TrajectoryReader&&) noexcept;

  /// The recorded tick after the last one read (the first at the start); false after the end.
  bool next(TrajectoryFrame& frame);
  /// Back to the first recorded tick.
  void rewind();

  double dt() const;      ///< s, the run's step
  int64_t every() const;  ///< a tick in `every` was recorded (and the last)
  int64_t first_tick() const;
  int64_t last_tick() const;
  size_t frame_count() const;  ///< recorded ticks
  size_t entity_count() const;
  const std::string& entity_name(uint32_t entity) const;
  size_t road_count() const;
  const std::string& road_id(uint32_t road) const;

  /// The rows of the tick last read as trajectory CSV text (appended to `out`, no header).
  void append_csv(std::string& out) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// The trajectory CSV of a binary trajectory, header included: byte for byte what the run's
/// `--record FILE.csv` writes. Throws InputError for a damaged file.
std::string trajectory_csv_of(const std::filesystem::path& binary);
/// The same written to `csv` atomically (`corsa record export`).
void export_trajectory_csv(const std::filesystem::path& binary, const std::filesystem::path& csv);

/// Whether a --record path asks for the binary trajectory (extension .corsatraj).
bool is_binary_trajectory(const std::filesystem::path& file);

}  // namespace corsa::engine
