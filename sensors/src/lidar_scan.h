#pragma once

// The inner loop of LidarSimulator::scan: fires packets of 16 beams through Embree and turns
// their hits into points (private to the library).

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "carrier.h"
#include "corsa/sensors/lidar.h"
#include "scene_data.h"

namespace corsa::sensors::detail {

/// Beams per Embree packet (rtcIntersect16).
constexpr int kPacketSize = 16;

class LidarWeatherModel;

/// Everything one revolution's packets share; set up once per scan.
struct LidarScanContext {
  const SceneData* scene = nullptr;
  RTCScene top = nullptr;  ///< what the beams are traced against (moving entities or not)
  const LidarOptions* options = nullptr;
  /// Body-frame beam directions in packets: for packet p, 16 x then 16 y then 16 z at
  /// packet_directions + 48 p (lanes past the last beam repeat it).
  const float* packet_directions = nullptr;
  uint64_t rays = 0;     ///< beams in the revolution
  int channels = 0;      ///< beams per azimuth step
  float rotation[3][3];  ///< sensor body frame to map frame at the capture time
  Vec3 origin;           ///< sensor position at the capture time, tracer-local
  /// With a moving sensor or moving entities, per azimuth step: rotation (9 floats, row-major),
  /// tracer-local origin (3), Embree ray time (1); empty for a still scan.
  std::vector<float> step_poses;
  /// Per azimuth step: the firing time relative to the capture time (s).
  std::vector<float> step_times;
  /// With deskew, per azimuth step: the sensor frame at firing time into the frame at the
  /// capture time (9 rotation floats, then 3 translation floats); empty otherwise.
  std::vector<float> step_deskew;
  float range = 0.0f;                                ///< metres
  double weather = 0.0;                              ///< fog + rain + snow extinction, 1/m
  const LidarWeatherModel* weather_model = nullptr;  ///< early returns; null in clear air
  uint32_t self_instance = 0;                        ///< hits on it are masked (0: none)
  uint64_t frame_key = 0;
  CarrierExit carrier;
  std::array<double, kSemanticClassCount> reflectivity{};

  static constexpr size_t kPoseFloats = 13;
};

/// Traces packets [first, last) and writes their points, in firing order, from `out` on (room
/// for 16 points per packet); returns how many it wrote.
size_t scan_packets(const LidarScanContext& c, uint64_t first, uint64_t last, LidarPoint* out);

}  // namespace corsa::sensors::detail
