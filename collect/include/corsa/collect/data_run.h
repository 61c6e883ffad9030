#pragma once

// Everything that lives for one data-collection run, attached to a simulation before its first
// step: the scene, the sensor system, the dataset writer and the capture timeline. run_dataset()
// (dataset_run.h) drives one; a caller that steps a simulation itself can use it directly:
//
//   DataRun data(options, diagnostics, sensors::load_rig(options.rig));
//   options.run.prepare = [&](engine::Simulation& s) { data.prepare(s); };
//   ... after every step: data.observe(simulation); at the end: data.finish("complete", reason).

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "corsa/collect/dataset_run.h"
#include "corsa/core/json.h"
#include "corsa/engine/capture_timeline.h"
#include "corsa/sensors/preview.h"
#include "corsa/sensors/rig.h"

namespace corsa::sensors {
class Scene;
class SensorSystem;
class DatasetWriter;
}  // namespace corsa::sensors

namespace corsa::collect {

class DataRun {
 public:
  /// `options` and `diagnostics` must outlive this object.
  DataRun(const DatasetRunOptions& options, Diagnostics& diagnostics, sensors::SensorRig rig);
  ~DataRun();
  DataRun(const DataRun&) = delete;
  DataRun& operator=(const DataRun&) = delete;

  /// Binds the rig to the simulation's entities, builds the scene and the sensor system, checks
  /// the capture windows, creates the dataset folder (last, once nothing else can fail) and
  /// attaches the capture timeline. Throws InputError for bad input.
  void prepare(engine::Simulation& simulation);
  /// Notes where the run is (tick, time) for run.json; call after every step.
  void observe(const engine::Simulation& simulation);
  /// Completes the dataset: the last capture's files, the index and run.json with `status`
  /// ("complete" or "interrupted") and `reason`. Nothing when the dataset was never started.
  void finish(const std::string& status, const std::string& reason) const;

  bool started() const { return writer_ != nullptr; }
  int64_t captures() const;
  int64_t files() const;
  /// The sensor system (valid after prepare()); its rig is bound to the run's entities.
  const sensors::SensorSystem& system() const { return *system_; }
  /// After finish(): the preview video encoded during the run (DatasetRunOptions::preview), for
  /// sensors::write_preview; nothing without one.
  std::optional<sensors::StreamedVideo> take_preview_video();

 private:
  void adjust(engine::WorldSnapshot& world) const;

  const DatasetRunOptions& options_;
  Diagnostics& diagnostics_;
  sensors::SensorRig rig_;
  std::unique_ptr<sensors::Scene> scene_;
  std::unique_ptr<sensors::SensorSystem> system_;
  std::unique_ptr<sensors::DatasetWriter> writer_;
  std::unique_ptr<engine::CaptureTimeline> timeline_;
  double start_time_of_day_ = 0.0;  ///< the scenario's clock at tick 0, s
  int64_t last_tick_ = 0;
  double last_time_ = 0.0;
};

/// The capture windows as run.json records them: an array of one JSON object each, with the
/// sensor, the opening and closing ticks (null while open) and the rate (Hz).
Json capture_windows_json(std::span<const engine::CaptureWindow> windows);

}  // namespace corsa::collect
