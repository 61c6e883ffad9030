#pragma once

// Writers for sensor outputs. Every file goes through corsa::AtomicFile (it appears complete or
// not at all) and the same data always gives the same bytes.
//
// Images are encoded by OpenCV. OpenCV 4.6 only encodes EXR when the OPENCV_IO_ENABLE_OPENEXR
// environment variable allows it, and reads that variable once, at the first EXR operation of the
// process. write_exr_float() therefore sets it to "1" (once, before its first encode) so that
// EXR output never depends on the user's environment; if EXR was already used in this process
// with the codec disabled, it fails with a clear error instead of writing nothing.

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "corsa/core/json.h"
#include "corsa/sensors/camera_model.h"
#include "corsa/sensors/geometry.h"
#include "corsa/sensors/labels.h"
#include "corsa/sensors/lidar.h"
#include "corsa/sensors/rig.h"

namespace corsa::sensors {

// --- images (PNG, EXR) ------------------------------------------------------------------------

/// 8-bit RGB (3 bytes per pixel, R G B order).
void write_png_rgb8(const std::filesystem::path& path, int width, int height,
                    std::span<const uint8_t> rgb);
/// 8-bit single channel (e.g. semantic class ids).
void write_png_gray8(const std::filesystem::path& path, int width, int height,
                     std::span<const uint8_t> values);
/// 16-bit single channel (depth in millimetres, instance ids).
void write_png_gray16(const std::filesystem::path& path, int width, int height,
                      std::span<const uint16_t> values);
/// 32-bit float single channel OpenEXR (depth in metres).
void write_exr_float(const std::filesystem::path& path, int width, int height,
                     std::span<const float> values);

/// Depth in metres to 16-bit millimetres: 0 stays 0 (nothing), depths beyond 65.535 m become 0
/// too (the format cannot hold them; the EXR keeps the full range).
std::vector<uint16_t> depth_to_millimetres(std::span<const float> depth_m);
/// Instance ids as 16-bit values (ids above 65535 are clamped to 65535).
std::vector<uint16_t> instance_to_u16(std::span<const uint32_t> ids);
/// Class ids to their palette colours (RGB).
std::vector<uint8_t> colorize_semantic(std::span<const uint8_t> classes);

// --- point clouds ----------------------------------------------------------------------------

/// Binary little-endian PLY: x y z intensity (float), ring (ushort), label (uchar, the class id
/// of the dataset's class table; PCL's name for a point's class), instance (uint), time (float,
/// firing time relative to the capture, s).
void write_ply(const std::filesystem::path& path, const PointCloud& cloud);
/// PCD v0.7 binary with the same fields under the same names.
void write_pcd(const std::filesystem::path& path, const PointCloud& cloud);
/// KITTI velodyne .bin: float32 x y z intensity per point.
void write_kitti_bin(const std::filesystem::path& path, const PointCloud& cloud);
/// Per-point labels as in SemanticKITTI .label: uint32 per point, the class id of the dataset's
/// class table (the same ids as the semantic images and the PLY/PCD label field, not
/// SemanticKITTI's own numbering) in the low 16 bits and the instance id in the high 16 bits.
void write_point_labels(const std::filesystem::path& path, const PointCloud& cloud);

// --- calibration and labels (text) -----------------------------------------------------------

/// 4x4 homogeneous matrix as JSON rows.
Json matrix_json(const Rigid& t);
/// Calibration of a sensor as JSON: intrinsics (cameras: K, distortion, size; LiDAR: channels,
/// elevations, azimuth steps) and extrinsics (T_entity_sensor: sensor body frame in the entity
/// frame; cameras also T_sensor_optical). `camera` may be null for LiDAR.
std::string calibration_json(const SensorSpec& sensor, const CameraModel* camera);
/// Labels of one frame as JSON (see docs/sensors.md for the fields). A camera lists parked
/// vehicles among `static_objects` only; a LiDAR among its `objects`.
std::string labels_json(std::span<const ObjectLabel> labels, bool camera,
                        std::span<const StaticObjectLabel> static_labels = {});

/// The sensor body frame in the entity frame from a rig mount.
Rigid entity_from_sensor(const Mount& mount);

}  // namespace corsa::sensors
