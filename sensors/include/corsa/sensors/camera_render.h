#pragma once

// Ray-cast cameras: one primary ray per pixel (4x4 packets) gives depth, semantic class and
// instance id; the RGB image adds sun shading with shadow rays, sky, fog, rain, headlights at
// night, motion blur from the motion during the exposure, exposure from ISO and shutter speed,
// sensor noise, gamma and lens distortion. Same bytes for the same seed on any thread count.

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "corsa/sensors/box.h"
#include "corsa/sensors/camera_model.h"
#include "corsa/sensors/environment.h"
#include "corsa/sensors/rig.h"
#include "corsa/sensors/scene.h"

namespace corsa::sensors {

namespace detail {
struct FrameBuffers;
}

/// Which images one render pass produces (cameras sharing intrinsics and pose share a pass).
struct CameraOutputs {
  bool rgb = false;
  bool depth = false;
  bool semantic = false;
  bool instance = false;
};

/// Row-major images of one camera pass; empty vectors for outputs not requested (the instance
/// buffer is always filled: labels need it).
struct CameraImages {
  int width = 0;
  int height = 0;
  std::vector<float> depth;       ///< metres along the optical axis; 0 = nothing within range
  std::vector<uint8_t> semantic;  ///< SemanticClass values
  std::vector<uint32_t> instance;
  std::vector<uint8_t> rgb;  ///< 3 bytes per pixel, R G B, gamma encoded
};

/// Where the camera is and how it moves (for motion blur).
struct CameraMotion {
  Rigid world_from_body;  ///< sensor body frame (x forward, y left, z up) to map
  Vec3 velocity;          ///< m/s, map frame, of the carrying entity
  double yaw_rate = 0.0;  ///< rad/s of the carrying entity
  Vec3 pivot;             ///< the carrying entity's reference point (rotation centre)
};

struct RenderSettings {
  CameraOutputs outputs;
  const Lighting* lighting = nullptr;  ///< required for RGB
  RgbOptions rgb;
  double max_depth_m = 1000.0;
  uint64_t frame_seed = 0;  ///< seeds the sensor noise and rain streaks
  /// Bounding box (map frame) of the entity carrying the camera: primary rays start where they
  /// leave it, so a camera behind the windscreen does not see its own vehicle.
  std::optional<Box3> carrier;
};

class CameraRenderer {
 public:
  /// Precomputes one ray per pixel (undistorting the lens model once).
  explicit CameraRenderer(const CameraIntrinsics& intrinsics);

  CameraImages render(const Scene& scene, const CameraMotion& motion,
                      const RenderSettings& settings) const;

  const CameraModel& model() const { return model_; }
  /// Unit ray of a pixel in the optical frame.
  Vec3 pixel_ray(int col, int row) const;

 private:
  CameraModel model_;
  std::vector<float> rays_;  ///< 3 floats per pixel, optical frame
  /// The per-pixel buffers of a pass, kept from frame to frame (see camera_frame.h).
  std::shared_ptr<detail::FrameBuffers> buffers_;
};

/// Camera optical frame to map for a sensor body pose.
Rigid world_from_optical(const Rigid& world_from_body);

}  // namespace corsa::sensors
