#pragma once

// The KITTI object-detection format (Geiger, Lenz, Urtasun, CVPR 2012; the devkit's readme.txt):
// rectified camera images whose projection matrix P2 is a pinhole, and label lines
//   type truncated occluded alpha left top right bottom height width length x y z rotation_y
// with `DontCare` regions where objects are not labelled (too far, too small), which KITTI's
// evaluation neither rewards nor punishes. Written by `corsa run --rig --format kitti`
// (docs/datasets.md).

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "corsa/sensors/camera_model.h"
#include "corsa/sensors/labels.h"

namespace corsa::sensors {

/// Which labelled objects become DontCare regions.
struct KittiOptions {
  /// Objects whose tight box (visible pixels) is lower than this (px). KITTI's evaluation counts
  /// nothing below 25 px (its "moderate" and "hard" minimum height).
  double min_height_px = 25.0;
  /// Objects whose box centre is farther than this from the camera (m); nothing: the first
  /// LiDAR's range, or no limit without a LiDAR (KITTI left unlabelled what its laser scanner
  /// could not reach).
  std::optional<double> max_distance_m;
};

/// The pinhole model of a camera: its intrinsics without distortion (the same K).
CameraModel pinhole_of(const CameraModel& camera);

/// Undistorts an image of `camera` onto its pinhole model (same size and K): every pinhole
/// pixel samples the distorted image where the lens put it; colours bilinearly (RGB, 3 bytes a
/// pixel), ids (instance images) from the nearest pixel. Outside the distorted image: 0.
std::vector<uint8_t> rectify_rgb(const CameraModel& camera, std::span<const uint8_t> rgb);
std::vector<uint32_t> rectify_ids(const CameraModel& camera, std::span<const uint32_t> ids);

/// KITTI label lines of one rectified frame: `labels` are the camera's labels (3D boxes in its
/// optical frame), `instance` its rectified instance image, `pinhole` the rectified camera.
/// The 2D box is the tight box of the object's pixels in `instance`, truncation the share of
/// its projected 3D box outside the image; objects `options` rule out become DontCare lines over
/// their tight (or, without pixels, clipped projected) box. `max_distance_m` must be resolved.
std::string kitti_label_lines(std::span<const ObjectLabel> labels, const CameraModel& pinhole,
                              std::span<const uint32_t> instance, const KittiOptions& options);

}  // namespace corsa::sensors
