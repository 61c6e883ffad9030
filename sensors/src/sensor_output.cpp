// Files of sensor frames (see sensor_system.h for the layout).

#include <cstdio>
#include <filesystem>

#include "corsa/core/atomic_file.h"
#include "corsa/core/diagnostic.h"
#include "corsa/sensors/sensor_system.h"
#include "corsa/sensors/writers.h"

namespace corsa::sensors {
namespace {

namespace fs = std::filesystem;

fs::path sensor_dir(const fs::path& directory, const std::string& sensor) {
  const fs::path dir = directory / sensor;
  std::error_code error;
  fs::create_directories(dir, error);
  if (error) {
    throw InputError(make_error(dir.string(), 0, "cannot create the folder: " + error.message()));
  }
  return dir;
}

std::string stem(int64_t frame) {
  char text[32];
  std::snprintf(text, sizeof text, "%06lld", static_cast<long long>(frame));
  return text;
}

}  // namespace

std::vector<fs::path> write_sensor_frame(const SensorFrame& f, const SensorSpec& s,
                                         const fs::path& directory) {
  const fs::path dir = sensor_dir(directory, s.name);
  const std::string base = stem(f.frame);
  std::vector<fs::path> written;
  auto out = [&](const std::string& suffix) {
    written.push_back(fs::path(s.name) / (base + suffix));
    return dir / (base + suffix);
  };
  const int w = f.camera.width;
  const int h = f.camera.height;
  switch (s.kind) {
    case SensorKind::kRgbCamera:
      write_png_rgb8(out(".png"), w, h, f.camera.rgb);
      break;
    case SensorKind::kDepthCamera:
      write_exr_float(out(".exr"), w, h, f.camera.depth);
      write_png_gray16(out(".png"), w, h, depth_to_millimetres(f.camera.depth));
      break;
    case SensorKind::kSemanticCamera:
      write_png_gray8(out(".png"), w, h, f.camera.semantic);
      write_png_rgb8(out("_color.png"), w, h, colorize_semantic(f.camera.semantic));
      break;
    case SensorKind::kInstanceCamera:
      write_png_gray16(out(".png"), w, h, instance_to_u16(f.camera.instance));
      break;
    case SensorKind::kBirdsEyeCamera:
      write_png_rgb8(out(".png"), f.birds_eye.width, f.birds_eye.height, f.birds_eye.rgb);
      break;
    case SensorKind::kLidar:
      write_ply(out(".ply"), f.cloud);
      write_pcd(out(".pcd"), f.cloud);
      write_kitti_bin(out(".bin"), f.cloud);
      write_point_labels(out(".label"), f.cloud);
      break;
  }
  if (s.kind != SensorKind::kBirdsEyeCamera) {
    write_file_atomic(out("_labels.json"),
                      labels_json(f.labels, s.kind != SensorKind::kLidar, f.static_labels));
  }
  return written;
}

void write_calibration(const SensorSystem& system, const fs::path& directory) {
  for (const auto& s : system.rig().sensors) {
    const fs::path dir = sensor_dir(directory, s.name);
    write_file_atomic(dir / "calibration.json", calibration_json(s, system.camera_model(s.name)));
  }
}

SensorCaptureSink::SensorCaptureSink(SensorSystem& system, fs::path directory)
    : system_(system), directory_(std::move(directory)) {
  write_calibration(system_, directory_);
}

void SensorCaptureSink::capture(const engine::WorldSnapshot& world,
                                std::span<const std::string> sensors) {
  for (const SensorFrame& f : system_.capture(world, sensors)) {
    const auto files = write_sensor_frame(f, *system_.rig().find(f.sensor), directory_);
    files_.insert(files_.end(), files.begin(), files.end());
  }
}

}  // namespace corsa::sensors
