#include <bit>
#include <cstring>
#include <string>

#include "corsa/core/atomic_file.h"
#include "corsa/sensors/writers.h"

namespace corsa::sensors {
namespace {

static_assert(std::endian::native == std::endian::little,
              "the binary point cloud writers assume a little-endian host");

template <typename T>
void put(std::string& out, T value) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  out.append(bytes, sizeof(T));
}

/// x y z intensity ring label instance time, 27 bytes per point, packed.
void append_points(std::string& out, const PointCloud& cloud) {
  out.reserve(out.size() + cloud.points.size() * 27);
  for (const auto& p : cloud.points) {
    put(out, p.x);
    put(out, p.y);
    put(out, p.z);
    put(out, p.intensity);
    put(out, p.ring);
    put(out, static_cast<uint8_t>(p.semantic));
    put(out, p.instance_id);
    put(out, p.time);
  }
}

}  // namespace

void write_ply(const std::filesystem::path& path, const PointCloud& cloud) {
  std::string out =
      "ply\nformat binary_little_endian 1.0\ncomment corsa LiDAR scan, sensor body frame "
      "(x forward, y left, z up), metres\nelement vertex " +
      std::to_string(cloud.points.size()) +
      "\nproperty float x\nproperty float y\nproperty float z\nproperty float intensity\n"
      "property ushort ring\nproperty uchar label\nproperty uint instance\nproperty float time\n"
      "end_header\n";
  append_points(out, cloud);
  write_file_atomic(path, out, true);
}

void write_pcd(const std::filesystem::path& path, const PointCloud& cloud) {
  const std::string n = std::to_string(cloud.points.size());
  std::string out =
      "# .PCD v0.7 - corsa LiDAR scan, sensor body frame (x forward, y left, z up), metres\n"
      "VERSION 0.7\nFIELDS x y z intensity ring label instance time\nSIZE 4 4 4 4 2 1 4 4\n"
      "TYPE F F F F U U U F\nCOUNT 1 1 1 1 1 1 1 1\nWIDTH " +
      n + "\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " + n + "\nDATA binary\n";
  append_points(out, cloud);
  write_file_atomic(path, out, true);
}

void write_kitti_bin(const std::filesystem::path& path, const PointCloud& cloud) {
  std::string out;
  out.reserve(cloud.points.size() * 16);
  for (const auto& p : cloud.points) {
    put(out, p.x);
    put(out, p.y);
    put(out, p.z);
    put(out, p.intensity);
  }
  write_file_atomic(path, out, true);
}

void write_point_labels(const std::filesystem::path& path, const PointCloud& cloud) {
  std::string out;
  out.reserve(cloud.points.size() * 4);
  for (const auto& p : cloud.points) {
    const uint32_t instance = std::min<uint32_t>(p.instance_id, 0xFFFFu);
    put(out, static_cast<uint32_t>(static_cast<uint32_t>(p.semantic) | (instance << 16)));
  }
  write_file_atomic(path, out, true);
}

}  // namespace corsa::sensors
