#pragma once

// The dataset folder of `corsa run --rig RIG -o DIR` (DESIGN.md, "File formats"; docs/datasets.md):
//
//   DIR/run.json             scenario, parameters, seed, step, rig, versions, status, windows
//   DIR/frames.csv           index: capture,tick,time,sensor,frame,file,overlap (one row per
//                            file; overlap: entity pairs interpenetrating at the capture)
//   DIR/poses/NNNNNN.json    per capture: every entity's pose and box, every captured sensor's
//                            world_from_sensor, the environment
//   DIR/<sensor>/...         the sensor's files (write_sensor_frame) and calibration.json
//   DIR/kitti/...            with DatasetFormat::kKitti: training/ (image_2 rectified, velodyne,
//                            label_2, calib) and ImageSets/ (kitti.h, docs/datasets.md)
//
// Written capture by capture: the sensor files and the pose file first (each atomically), then
// frames.csv is rewritten atomically, so the index only ever names complete captures. The files
// of a capture are encoded on TBB tasks (one per sensor) while the next capture renders; that
// capture's index rows are added when the next capture (or finish()) has waited for them. run.json
// says "running" while the run goes on, then "complete" or "interrupted" with where it stopped;
// a dataset whose run.json still says "running" was killed, and its index is still consistent.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "corsa/core/json.h"
#include "corsa/engine/world_snapshot.h"
#include "corsa/sensors/kitti.h"
#include "corsa/sensors/preview.h"
#include "corsa/sensors/sensor_system.h"

namespace corsa {
class OutputLock;
}

namespace corsa::sensors {

namespace detail {
class KittiExport;
class PreviewStream;
}  // namespace detail

enum class DatasetFormat { kCorsa, kKitti };

/// What run.json records about the run (everything needed to reproduce it).
struct DatasetRunInfo {
  std::string scenario;                                         ///< as the user named it
  std::vector<std::pair<std::string, std::string>> parameters;  ///< resolved global parameters
  uint64_t seed = 0;
  double dt = 0.01;
  double duration = 0.0;
  std::string rig;          ///< as the user named it
  std::string time_of_day;  ///< --time-of-day as given, empty when not overridden
  std::string weather;      ///< --weather as given
  std::string npc;          ///< --npc as given
};

/// How the run ended, for run.json.
struct DatasetEnd {
  std::string status;      ///< "complete" or "interrupted"
  std::string end_reason;  ///< the engine's end reason, or what interrupted it
  int64_t tick = 0;        ///< last simulated tick
  double time = 0.0;       ///< s
  /// Capture windows, a JSON array of objects, e.g. from the capture timeline.
  Json windows = Json::array();
};

class DatasetWriter final : public engine::CaptureSink {
 public:
  DatasetWriter(const DatasetWriter&) = delete;
  DatasetWriter& operator=(const DatasetWriter&) = delete;
  /// Waits for the files still being written (errors are dropped: call finish() to see them).
  ~DatasetWriter() override;

  /// Creates the folder and locks it for this writer (corsa/core/output_lock.h) until destroyed.
  /// It must be absent or empty, or with `replace` hold a previous dataset and nothing else,
  /// whose own files are then removed (only those: see prepare_dataset_folder in
  /// src/dataset_folder.h). Writes the calibration files and a "running" run.json. Throws
  /// InputError when the folder cannot be used.
  /// `kitti` chooses the DontCare regions of the KITTI labels (DatasetFormat::kKitti); the
  /// system must then keep instance ids with RGB frames (SensorSystemOptions::rgb_instances).
  DatasetWriter(SensorSystem& system, std::filesystem::path directory, DatasetRunInfo info,
                DatasetFormat format, bool replace, KittiOptions kitti = {});

  void capture(const engine::WorldSnapshot& world, std::span<const std::string> sensors) override;

  /// Waits for the last capture's files, indexes them and rewrites run.json with how the run
  /// ended. Throws what writing those files threw (InputError for an I/O failure).
  void finish(const DatasetEnd& end);
  /// Encodes the preview video (write_preview) from the captures as they come, on a thread of its
  /// own beside the next captures' rendering, instead of from the dataset's files after the run.
  void stream_preview();
  /// After finish(): the video stream_preview() encoded, for write_preview; nothing without one
  /// or when it could not be encoded.
  std::optional<StreamedVideo> take_preview_video();

  /// Captures and files in the index (a capture still being written is not counted).
  int64_t captures() const { return captures_; }
  int64_t files() const { return static_cast<int64_t>(rows_); }
  const std::filesystem::path& directory() const { return directory_; }
  /// KITTI frames written, and captures of the camera left out for want of the LiDAR.
  int64_t kitti_frames() const;
  int64_t kitti_skipped() const;

 private:
  struct Pending;  ///< a capture whose files are being written

  void write_run_json(const DatasetEnd* end) const;
  /// Waits for the pending capture's files, then adds its rows to frames.csv.
  void complete_pending();

  SensorSystem& system_;
  std::filesystem::path directory_;
  DatasetRunInfo info_;
  DatasetFormat format_;
  std::string index_;  ///< frames.csv as written so far
  size_t rows_ = 0;
  int64_t captures_ = 0;
  int64_t last_tick_ = -1;
  double last_time_ = 0.0;
  std::unique_ptr<detail::KittiExport> kitti_;
  std::unique_ptr<detail::PreviewStream> preview_;
  std::unique_ptr<Pending> pending_;
  std::unique_ptr<OutputLock> lock_;
};

/// The file name stem of a frame number: six digits, zero-padded ("000042").
std::string frame_stem(int64_t frame);

}  // namespace corsa::sensors
