// The KITTI layout of a dataset (kitti_export.h).

#include "kitti_export.h"

#include <cmath>
#include <system_error>

#include "corsa/core/atomic_file.h"
#include "corsa/core/diagnostic.h"
#include "corsa/core/strings.h"
#include "corsa/sensors/dataset_writer.h"
#include "corsa/sensors/writers.h"

namespace corsa::sensors::detail {
namespace {

namespace fs = std::filesystem;

void make_dirs(const fs::path& dir) {
  std::error_code error;
  fs::create_directories(dir, error);
  if (error) {
    throw InputError(make_error(dir.string(), 0, "cannot create the folder: " + error.message()));
  }
}

std::string row34(const double m[3][4]) {
  std::string out;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 4; ++c) {
      out += (r + c == 0 ? "" : " ") + format_double(m[r][c]);
    }
  }
  return out;
}

// KITTI's calib file: P0..P3 (3x4), R0_rect (3x3), Tr_velo_to_cam and Tr_imu_to_velo (3x4).
// Every camera matrix is the rectified pinhole K [I | 0]: the images are undistorted onto it.
std::string kitti_calib(const CameraModel& pinhole, const Rigid& optical_from_lidar) {
  const double p[3][4] = {{pinhole.fx(), 0.0, pinhole.cx(), 0.0},
                          {0.0, pinhole.fy(), pinhole.cy(), 0.0},
                          {0.0, 0.0, 1.0, 0.0}};
  double tr[3][4];
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) {
      tr[r][c] = optical_from_lidar.rotation.m[r][c];
    }
  }
  tr[0][3] = optical_from_lidar.translation.x;
  tr[1][3] = optical_from_lidar.translation.y;
  tr[2][3] = optical_from_lidar.translation.z;
  const double identity[3][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}};
  const std::string pp = row34(p);
  return "P0: " + pp + "\nP1: " + pp + "\nP2: " + pp + "\nP3: " + pp +
         "\nR0_rect: 1 0 0 0 1 0 0 0 1\nTr_velo_to_cam: " + row34(tr) +
         "\nTr_imu_to_velo: " + row34(identity) + "\n";
}

}  // namespace

KittiExport::KittiExport(const SensorSystem& system, fs::path root, KittiOptions options)
    : system_(system), root_(std::move(root)), options_(options) {
  for (const SensorSpec& s : system_.rig().sensors) {
    if (camera_ == nullptr && s.kind == SensorKind::kRgbCamera) {
      camera_ = &s;
    }
    if (lidar_ == nullptr && s.kind == SensorKind::kLidar) {
      lidar_ = &s;
    }
  }
  if (!options_.max_distance_m && lidar_ != nullptr) {
    options_.max_distance_m = lidar_->lidar.range_m;
  }
}

void KittiExport::write(std::span<const SensorFrame> frames) {
  const SensorFrame* image = nullptr;
  const SensorFrame* cloud = nullptr;
  for (const SensorFrame& f : frames) {
    image = camera_ != nullptr && f.sensor == camera_->name ? &f : image;
    cloud = lidar_ != nullptr && f.sensor == lidar_->name ? &f : cloud;
  }
  if (image == nullptr) {
    return;
  }
  if (lidar_ != nullptr && cloud == nullptr) {
    ++skipped_;
    return;
  }
  const fs::path training = root_ / "training";
  const std::string stem = frame_stem(frames_);
  for (const char* folder : {"image_2", "label_2", "calib"}) {
    make_dirs(training / folder);
  }
  const CameraModel& camera = *system_.camera_model(camera_->name);
  const CameraModel pinhole = pinhole_of(camera);
  write_png_rgb8(training / "image_2" / (stem + ".png"), image->camera.width, image->camera.height,
                 rectify_rgb(camera, image->camera.rgb));
  const std::vector<uint32_t> instance = rectify_ids(camera, image->camera.instance);
  write_file_atomic(training / "label_2" / (stem + ".txt"),
                    kitti_label_lines(image->labels, pinhole, instance, options_));
  Rigid optical_from_lidar;
  if (cloud != nullptr) {
    const Rigid world_from_optical = image->world_from_sensor * optical_in_body();
    optical_from_lidar = world_from_optical.inverse() * cloud->world_from_sensor;
    make_dirs(training / "velodyne");
    write_kitti_bin(training / "velodyne" / (stem + ".bin"), cloud->cloud);
  }
  write_file_atomic(training / "calib" / (stem + ".txt"), kitti_calib(pinhole, optical_from_lidar));
  ++frames_;
}

void KittiExport::finish() const {
  if (frames_ == 0) {
    return;
  }
  make_dirs(root_ / "ImageSets");
  // Consecutive frames are near copies of each other: a split by time keeps them apart.
  const auto train = static_cast<int64_t>(std::ceil(0.8 * static_cast<double>(frames_)));
  std::string train_ids, val_ids, all_ids;
  for (int64_t k = 0; k < frames_; ++k) {
    const std::string line = frame_stem(k) + "\n";
    (k < train ? train_ids : val_ids) += line;
    all_ids += line;
  }
  write_file_atomic(root_ / "ImageSets" / "train.txt", train_ids);
  write_file_atomic(root_ / "ImageSets" / "val.txt", val_ids);
  write_file_atomic(root_ / "ImageSets" / "trainval.txt", all_ids);
}

}  // namespace corsa::sensors::detail
