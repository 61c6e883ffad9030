// The dataset folder (see corsa/sensors/dataset_writer.h and docs/datasets.md).

#include "corsa/sensors/dataset_writer.h"

#include <tbb/task_group.h>

#include <cmath>
#include <cstdio>
#include <system_error>

#include "corsa/core/atomic_file.h"
#include "corsa/core/diagnostic.h"
#include "corsa/core/json.h"
#include "corsa/core/output_lock.h"
#include "corsa/core/strings.h"
#include "corsa/core/version.h"
#include "corsa/sensors/semantic.h"
#include "corsa/sensors/writers.h"
#include "dataset_folder.h"
#include "kitti_export.h"
#include "preview_stream.h"

namespace corsa::sensors {
namespace {

namespace fs = std::filesystem;

void make_dir(const fs::path& dir) {
  std::error_code error;
  fs::create_directories(dir, error);
  if (error) {
    throw InputError(make_error(dir.string(), 0, "cannot create the folder: " + error.message()));
  }
}

std::string num(double value) { return format_double(value); }

Json environment_json(const engine::EnvironmentState& e) {
  Json out = {{"date", std::to_string(e.year) + "-" + std::to_string(e.month) + "-" +
                           std::to_string(e.day)},
              {"time_of_day", e.time_of_day},
              {"utc_offset_hours", e.utc_offset_hours ? Json(*e.utc_offset_hours) : Json()},
              {"fog_visual_range", e.fog_visual_range},  // infinite (no fog): null
              {"precipitation", e.precipitation == engine::PrecipitationType::kRain   ? "rain"
                                : e.precipitation == engine::PrecipitationType::kSnow ? "snow"
                                                                                      : "dry"},
              {"precipitation_intensity", e.precipitation_intensity},
              {"cloud_cover", e.cloud_cover},
              {"wind_speed", e.wind_speed},
              {"wind_direction", e.wind_direction},
              {"road_friction_scale", e.road_friction_scale},
              {"wet_road", e.wet_road}};
  if (e.sun_azimuth && e.sun_elevation) {
    out["sun_azimuth"] = *e.sun_azimuth;
    out["sun_elevation"] = *e.sun_elevation;
  }
  return out;
}

Json entity_json(const engine::EntitySnapshot& e) {
  Json out = {
      {"instance_id", e.instance_id},
      {"name", e.name},
      {"category", static_cast<int>(e.category)},
      {"pose", {e.pose.x, e.pose.y, e.pose.z, e.pose.h, e.pose.p, e.pose.r}},
      {"box",
       {e.box.center_x, e.box.center_y, e.box.center_z, e.box.length, e.box.width, e.box.height}},
      {"speed", e.speed},
      {"velocity", {e.vx, e.vy, e.vz}},
      {"yaw_rate", e.yaw_rate},
      {"visible", e.visible}};
  // VisibilityAction's SensorReferenceSet: the sensors for which the opposite of visible holds.
  if (!e.sensor_exceptions.empty()) {
    Json names = Json::array();
    for (const std::string& name : e.sensor_exceptions) {
      names.push_back(name);
    }
    out["sensor_exceptions"] = std::move(names);
  }
  return out;
}

}  // namespace

std::string frame_stem(int64_t frame) {
  char text[32];
  std::snprintf(text, sizeof text, "%06lld", static_cast<long long>(frame));
  return text;
}

struct DatasetWriter::Pending {
  std::vector<SensorFrame> frames;
  std::vector<std::vector<fs::path>> files;  ///< per frame, filled by its task
  int64_t tick = 0;
  double time = 0.0;
  std::string pose_rows;  ///< the pose file's index row(s), after the sensor files
  size_t overlap = 0;     ///< pairs of entities interpenetrating at this capture
  tbb::task_group tasks;
};

DatasetWriter::DatasetWriter(SensorSystem& system, fs::path directory, DatasetRunInfo info,
                             DatasetFormat format, bool replace, KittiOptions kitti)
    : system_(system), directory_(std::move(directory)), info_(std::move(info)), format_(format) {
  std::error_code error;
  if (fs::exists(directory_, error) && !fs::is_directory(directory_, error)) {
    throw InputError(make_error(directory_.string(), 0, "exists and is not a folder"));
  }
  make_dir(directory_);
  lock_ = std::make_unique<OutputLock>(directory_);  // one writer per dataset folder
  remove_stale_temporaries(directory_, 2);
  detail::prepare_dataset_folder(directory_, replace);
  if (format_ == DatasetFormat::kKitti) {
    kitti_ = std::make_unique<detail::KittiExport>(system_, directory_ / "kitti", kitti);
  }
  make_dir(directory_ / "poses");
  write_calibration(system_, directory_);
  write_file_atomic(directory_ / "classes.json", class_table_json());
  index_ = "capture,tick,time,sensor,frame,file,overlap\n";
  write_file_atomic(directory_ / "frames.csv", index_);
  write_run_json(nullptr);
}

DatasetWriter::~DatasetWriter() {
  if (pending_) {
    try {
      pending_->tasks.wait();
    } catch (...) {  // NOLINT(bugprone-empty-catch): a destructor must not throw; finish() reports
    }
  }
}

void DatasetWriter::capture(const engine::WorldSnapshot& world,
                            std::span<const std::string> sensors) {
  // Rendering this capture overlaps with the previous capture's file tasks (both cores busy).
  std::vector<SensorFrame> frames = system_.capture(world, sensors);
  if (preview_) {
    preview_->add(frames);
  }
  complete_pending();
  auto batch = std::make_unique<Pending>();
  batch->frames = std::move(frames);
  batch->files.resize(batch->frames.size());
  batch->tick = world.tick;
  batch->time = world.time;
  Json sensor_poses = Json::array();
  for (const SensorFrame& f : batch->frames) {
    sensor_poses.push_back({{"sensor", f.sensor},
                            {"frame", f.frame},
                            {"world_from_sensor", matrix_json(f.world_from_sensor)}});
  }
  Json entities = Json::array();
  for (const engine::EntitySnapshot& e : world.entities) {
    entities.push_back(entity_json(e));
  }
  Json overlaps = Json::array();
  for (const auto& [a, b] : world.overlaps) {
    overlaps.push_back({a, b});
  }
  const Json pose = {{"capture", captures_},
                     {"tick", world.tick},
                     {"time", world.time},
                     {"sensors", std::move(sensor_poses)},
                     {"entities", std::move(entities)},
                     {"overlaps", std::move(overlaps)},
                     {"environment", environment_json(world.environment)}};
  const std::string pose_file = "poses/" + frame_stem(captures_) + ".json";
  write_file_atomic(directory_ / pose_file, json_document(pose));
  // Captures where entities interpenetrate (a collision) are flagged on every row of the index.
  batch->overlap = world.overlaps.size();
  batch->pose_rows = std::to_string(captures_) + "," + std::to_string(world.tick) + "," +
                     num(world.time) + ",poses,," + pose_file + "," +
                     std::to_string(batch->overlap) + "\n";
  // One task per sensor: each writes only its own folder, so the encoders run side by side and
  // with the next capture's rendering. The KITTI export numbers its frames in capture order: one
  // task writes all of it.
  Pending& b = *batch;
  for (size_t i = 0; i < b.frames.size(); ++i) {
    b.tasks.run([this, &b, i] {
      const SensorFrame& f = b.frames[i];
      b.files[i] = write_sensor_frame(f, *system_.rig().find(f.sensor), directory_);
    });
  }
  if (kitti_) {
    b.tasks.run([this, &b] { kitti_->write(b.frames); });
  }
  pending_ = std::move(batch);
}

void DatasetWriter::complete_pending() {
  if (!pending_) {
    return;
  }
  const std::unique_ptr<Pending> done = std::move(pending_);
  done->tasks.wait();  // rethrows a task's exception (the capture is then not indexed)
  std::string rows;
  for (size_t i = 0; i < done->frames.size(); ++i) {
    const SensorFrame& f = done->frames[i];
    for (const fs::path& file : done->files[i]) {
      rows += std::to_string(captures_) + "," + std::to_string(done->tick) + "," + num(done->time) +
              "," + f.sensor + "," + std::to_string(f.frame) + "," + file.generic_string() + "," +
              std::to_string(done->overlap) + "\n";
      ++rows_;
    }
  }
  rows += done->pose_rows;
  ++rows_;
  // The index last: it names the capture only once every file of it is in place.
  index_ += rows;
  write_file_atomic(directory_ / "frames.csv", index_);
  ++captures_;
  last_tick_ = done->tick;
  last_time_ = done->time;
}

void DatasetWriter::finish(const DatasetEnd& end) {
  complete_pending();
  if (kitti_) {
    kitti_->finish();
  }
  write_run_json(&end);
}

void DatasetWriter::stream_preview() {
  if (!preview_) {
    preview_ = std::make_unique<detail::PreviewStream>(system_.rig(), directory_);
  }
}

std::optional<StreamedVideo> DatasetWriter::take_preview_video() {
  return preview_ ? preview_->finish() : std::nullopt;
}

int64_t DatasetWriter::kitti_frames() const { return kitti_ ? kitti_->frames() : 0; }
int64_t DatasetWriter::kitti_skipped() const { return kitti_ ? kitti_->skipped() : 0; }

void DatasetWriter::write_run_json(const DatasetEnd* end) const {
  Json parameters = Json::object();
  for (const auto& [name, value] : info_.parameters) {
    parameters[name] = value;
  }
  Json sensors = Json::array();
  for (const SensorSpec& s : system_.rig().sensors) {
    sensors.push_back({{"name", s.name},
                       {"kind", sensor_kind_name(s.kind)},
                       {"entity", s.entity},
                       {"rate", s.rate_hz}});
  }
  Json run = {
      {"corsa_version", version()},
      // 2: camera labels give vehicles' lights ("lights", "lamps"); otherwise as 1.
      {"dataset_format_version", 2},
      {"scenario", info_.scenario},
      {"parameters", std::move(parameters)},
      {"seed", info_.seed},
      {"dt", info_.dt},
      {"duration", info_.duration},
      {"rig", info_.rig},
      {"format", format_ == DatasetFormat::kKitti ? "kitti" : "corsa"},
      {"overrides",
       {{"time_of_day", info_.time_of_day}, {"weather", info_.weather}, {"npc", info_.npc}}},
      {"sensors", std::move(sensors)},
      {"status", end != nullptr ? end->status : "running"},
      {"captures", captures_},
      {"files", rows_},
      {"last_capture_tick", last_tick_},
      {"last_capture_time", last_time_}};
  if (kitti_) {
    run["kitti_frames"] = kitti_->frames();
    run["kitti_frames_without_lidar"] = kitti_->skipped();
  }
  if (end != nullptr) {
    run["end_reason"] = end->end_reason;
    run["end_tick"] = end->tick;
    run["end_time"] = end->time;
    run["windows"] = end->windows;
  }
  write_file_atomic(directory_ / "run.json", json_document(run));
}

}  // namespace corsa::sensors
