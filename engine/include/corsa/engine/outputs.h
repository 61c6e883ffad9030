#pragma once

// The files a run writes (DESIGN.md, "File formats Corsa writes"), each atomically (a temporary
// file renamed into place when complete) and deterministically (same run, same bytes; numbers
// in the shortest text that reads back to the same double, except as noted):
//   - trajectory CSV: `time,entity,x,y,z,h,p,r,speed,road,lane,s,t`, one row per entity per
//     recorded step, entities in document order; road, lane, s, t empty off the road; lengths
//     and speeds rounded to 6 decimals, angles to 9 (docs/engine.md, "Output files");
//   - event log CSV: `time,type,element,transition,state`, every storyboard transition;
//   - run summary JSON: scenario, parameters, seed, step, end reason, sim time, steps, wall
//     time, real-time factor, final entity states, collisions. Only wall time and real-time
//     factor differ between identical runs.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

#include "corsa/core/atomic_file.h"
#include "corsa/engine/simulation.h"

namespace corsa::engine {

/// Records the trajectory CSV while the simulation runs: register it with
/// Simulation::add_observer before the first step, call finish() after the run.
class TrajectoryRecorder final : public SimulationObserver {
 public:
  /// `every`: record every N-th tick (tick 0 and the last tick are always recorded).
  explicit TrajectoryRecorder(std::filesystem::path file, int64_t every = 1);
  ~TrajectoryRecorder() override;
  void on_step(const Simulation& simulation) override;
  /// Records the final tick if it was skipped and commits the file (throws InputError when it
  /// cannot be written).
  void finish(const Simulation& simulation);

  /// The CSV rows of the current tick (for tests and other writers).
  static void append_rows(const Simulation& simulation, std::string& out);

 private:
  struct RowCache;
  void flush();
  /// append_rows into buffer_, copying the rows of entities whose state is as it was.
  void append_cached_rows(const Simulation& simulation);

  AtomicFile file_;
  int64_t every_;
  int64_t last_recorded_ = -1;
  /// Rows not yet written: the first used_ characters (the string only grows, so that a row is
  /// written into it without zeroing its room first).
  std::string buffer_;
  size_t used_ = 0;
  std::unique_ptr<RowCache> cache_;
  /// Room for `count` more characters at buffer_'s end (used_ unchanged).
  char* room(size_t count);
};

/// Header line of the trajectory CSV (with newline).
inline constexpr const char* kTrajectoryHeader = "time,entity,x,y,z,h,p,r,speed,road,lane,s,t\n";

/// The event log as CSV text / written to a file.
std::string event_log_csv(const Simulation& simulation);
void write_event_log(const Simulation& simulation, const std::filesystem::path& file);

/// The run summary as JSON text / written to a file.
std::string summary_json(const Simulation& simulation, double wall_seconds);
void write_summary(const Simulation& simulation, const std::filesystem::path& file,
                   double wall_seconds);

}  // namespace corsa::engine
