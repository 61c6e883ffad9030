#pragma once

// The KITTI object-detection layout of a dataset (`--format kitti`; private to the library):
//
//   DIR/kitti/training/image_2/NNNNNN.png   the rig's first RGB camera, rectified (pinhole P2)
//   DIR/kitti/training/label_2/NNNNNN.txt   label lines (kitti.h), DontCare for far/small objects
//   DIR/kitti/training/calib/NNNNNN.txt     P0-P3 = K [I | 0], R0_rect = I, Tr_velo_to_cam,
//                                           Tr_imu_to_velo = I
//   DIR/kitti/training/velodyne/NNNNNN.bin  the rig's first LiDAR, float32 x y z intensity
//   DIR/kitti/ImageSets/{train,val,trainval}.txt   frame ids: the first 80% train, the rest val
//
// One KITTI frame per capture holding the camera (and, when the rig has a LiDAR, the LiDAR: a
// capture without it is left out, as KITTI loaders expect every file of a frame).

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "corsa/sensors/kitti.h"
#include "corsa/sensors/sensor_system.h"

namespace corsa::sensors::detail {

class KittiExport {
 public:
  /// `root` is DIR/kitti. `options.max_distance_m` unset means the first LiDAR's range.
  KittiExport(const SensorSystem& system, std::filesystem::path root, KittiOptions options);

  /// The KITTI frame of one capture's frames, if it makes one. Call in capture order, from one
  /// thread at a time.
  void write(std::span<const SensorFrame> frames);
  /// Writes ImageSets/ for the frames written so far.
  void finish() const;

  int64_t frames() const { return frames_; }
  /// Captures of the camera left out because the LiDAR was not captured with it.
  int64_t skipped() const { return skipped_; }

 private:
  const SensorSystem& system_;
  std::filesystem::path root_;
  KittiOptions options_;
  const SensorSpec* camera_ = nullptr;
  const SensorSpec* lidar_ = nullptr;
  int64_t frames_ = 0;
  int64_t skipped_ = 0;
};

}  // namespace corsa::sensors::detail
