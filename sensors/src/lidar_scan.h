#pragma once

// The inner loop of LidarSimulator::scan: fires packets of 16 beams through Embree and turns
// their hits into points (private to the library).

#include <array>
#include <cstddef>
#include <cstdint>

#include "carrier.h"
#include "corsa/sensors/lidar.h"
#include "scene_data.h"

namespace corsa::sensors::detail {

/// Beams per Embree packet (rtcIntersect16).
constexpr int kPacketSize = 16;

/// Everything one revolution's packets share; set up once per scan.
struct LidarScanContext {
  const SceneData* scene = nullptr;
  const LidarOptions* options = nullptr;
  /// Body-frame beam directions in packets: for packet p, 16 x then 16 y then 16 z at
  /// packet_directions + 48 p (lanes past the last beam repeat it).
  const float* packet_directions = nullptr;
  uint64_t rays = 0;     ///< beams in the revolution
  int channels = 0;      ///< beams per azimuth step
  float rotation[3][3];  ///< sensor body frame to map frame
  Vec3 origin;           ///< sensor position, tracer-local (map minus the scene origin)
  float range = 0.0f;    ///< metres
  double weather = 0.0;  ///< fog + rain extinction, 1/m
  uint64_t frame_key = 0;
  CarrierExit carrier;
  std::array<double, kSemanticClassCount> reflectivity{};
};

/// Traces packets [first, last) and writes their points, in firing order, from `out` on (room
/// for 16 points per packet); returns how many it wrote.
size_t scan_packets(const LidarScanContext& c, uint64_t first, uint64_t last, LidarPoint* out);

}  // namespace corsa::sensors::detail
