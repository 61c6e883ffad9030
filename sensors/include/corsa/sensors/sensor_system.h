#pragma once

// A rig bound to a scene: renders the due sensors at a world snapshot and writes their files.
// Cameras on the same entity with the same mount and intrinsics share one ray-casting pass (an
// RGB, a depth and a semantic camera cost one set of primary rays).

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "corsa/engine/world_snapshot.h"
#include "corsa/sensors/birds_eye.h"
#include "corsa/sensors/camera_render.h"
#include "corsa/sensors/environment.h"
#include "corsa/sensors/labels.h"
#include "corsa/sensors/lidar.h"
#include "corsa/sensors/rig.h"
#include "corsa/sensors/scene.h"

namespace corsa::sensors {

struct SensorSystemOptions {
  uint64_t seed = 0;     ///< run seed; each frame's noise uses (seed, sensor, frame)
  GeoLocation location;  ///< for the solar position
  /// RGB frames also carry their camera's instance ids (CameraImages::instance), e.g. for the
  /// tight boxes of a KITTI export.
  bool rgb_instances = false;
};

/// One sensor's output at one capture.
struct SensorFrame {
  std::string sensor;
  SensorKind kind = SensorKind::kRgbCamera;
  int64_t frame = 0;  ///< 0-based count of this sensor's captures
  int64_t tick = 0;
  double time = 0.0;
  Rigid world_from_sensor;  ///< sensor body frame to map
  CameraImages camera;      ///< camera kinds (only the sensor's own image is filled)
  BirdsEyeImage birds_eye;
  PointCloud cloud;
  std::vector<ObjectLabel> labels;
  std::vector<StaticObjectLabel> static_labels;  ///< cameras: traffic lights, signs, ...
};

class SensorSystem {
 public:
  /// The rig must have been bound to the scenario (bind_rig); the scene committed.
  SensorSystem(SensorRig rig, Scene& scene, SensorSystemOptions options);
  ~SensorSystem();
  SensorSystem(const SensorSystem&) = delete;
  SensorSystem& operator=(const SensorSystem&) = delete;

  /// Places the snapshot's entities in the scene and renders `sensors` (all when empty), in rig
  /// order. Each sensor sees the entities visible to it (engine::visible_to: an entity whose
  /// sensor_exceptions name some sensors is placed in a separate pass of the scene for them).
  /// Throws InputError when a sensor's entity is missing from the snapshot.
  std::vector<SensorFrame> capture(const engine::WorldSnapshot& world,
                                   std::span<const std::string> sensors);

  const SensorRig& rig() const { return rig_; }
  /// The camera model of a camera sensor (nullptr for LiDAR and bird's-eye).
  const CameraModel* camera_model(const std::string& sensor) const;

 private:
  struct Cache;
  /// Renders `due` (which see the scene's entities as they are placed now) into `frames`.
  void render_pass(const std::vector<const SensorSpec*>& due, const Lighting& lighting,
                   double sweep, std::map<std::string, SensorFrame>& frames,
                   const std::map<std::string, const engine::EntitySnapshot*>& carriers);
  SensorRig rig_;
  Scene& scene_;
  SensorSystemOptions options_;
  std::map<std::string, int64_t> frames_;
  std::unique_ptr<Cache> cache_;
};

/// Writes a frame's files under `directory`/<sensor>/ named by the zero-padded frame number:
/// RGB .png; depth .exr (metres) and .png (millimetres); semantic .png (class ids) and
/// _color.png; instance .png (16-bit ids); bird's-eye .png; LiDAR .ply, .pcd, .bin (KITTI) and
/// .label; and labels .json for cameras and LiDAR. Returns the files written, relative to
/// `directory`, in a fixed order.
std::vector<std::filesystem::path> write_sensor_frame(const SensorFrame& frame,
                                                      const SensorSpec& sensor,
                                                      const std::filesystem::path& directory);

/// Writes <directory>/<sensor>/calibration.json for every sensor of the rig.
void write_calibration(const SensorSystem& system, const std::filesystem::path& directory);

/// A capture sink that renders and writes every due sensor into a directory (the engine calls it
/// at capture times).
class SensorCaptureSink : public engine::CaptureSink {
 public:
  SensorCaptureSink(SensorSystem& system, std::filesystem::path directory);
  void capture(const engine::WorldSnapshot& world, std::span<const std::string> sensors) override;
  /// Files written so far, relative to the directory, in capture order.
  const std::vector<std::filesystem::path>& files() const { return files_; }

 private:
  SensorSystem& system_;
  std::filesystem::path directory_;
  std::vector<std::filesystem::path> files_;
};

}  // namespace corsa::sensors
