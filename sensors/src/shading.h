#pragma once

// RGB shading and image post-processing for the camera renderer (private).

#include <cstdint>
#include <span>
#include <vector>

#include "corsa/sensors/camera_model.h"
#include "corsa/sensors/camera_render.h"
#include "corsa/sensors/environment.h"
#include "scene_data.h"

namespace corsa::sensors::detail {

/// A vehicle headlight: position (tracer-local), unit beam direction, intensity.
struct Headlight {
  Vec3 position;
  Vec3 direction;
  double intensity = 0.0;
};

/// Everything shading needs, prepared once per frame.
struct ShadingContext {
  const SceneData* scene = nullptr;
  const Lighting* lighting = nullptr;
  std::vector<Headlight> headlights;
  std::vector<uint32_t> entity_lamps;  ///< by instance pool index: lit LightRole bits
  uint32_t static_lamps = 0;           ///< lit LightRole bits of static lamps (street lamps)
  double darkness = 0.0;               ///< 0 day .. 1 night (lit windows)
  double pixel_angle = 1e-3;           ///< radians per pixel, for texture footprints
};

/// What a camera ray hit, as shading needs it.
struct SurfaceHit {
  unsigned inst_id = 0;
  unsigned geom_id = 0;
  unsigned prim_id = 0;
  double u = 0.0;  ///< Embree's barycentric coordinates
  double v = 0.0;
  Vec3 position;  ///< tracer-local
  Vec3 normal;    ///< world, unit, facing the viewer
  Vec3 view_dir;  ///< unit, from the eye
  double distance = 0.0;
  SemanticClass semantic = SemanticClass::kUnlabeled;
  int entity = -1;  ///< instance pool index, -1 static
};

/// `pixel_angle`: the angle one pixel covers (radians), or for orthographic views the metres
/// per pixel divided by the distance passed in hits.
ShadingContext make_shading_context(const SceneData& scene, const Lighting& lighting,
                                    double pixel_angle);

/// Linear radiance of a surface point, before fog.
Color shade_hit(const ShadingContext& c, const SurfaceHit& hit, bool sunlit);

/// Fog and rain extinction over `distance` metres (infinite for the sky).
Color apply_fog(const Lighting& l, Color radiance, double distance);

/// Motion blur along per-pixel motion vectors (pixels, 2 floats per pixel), in place.
void motion_blur(std::vector<float>& linear, const std::vector<float>& motion, int width,
                 int height);

/// Exposure, sensor noise, gamma and 8-bit quantisation of linear radiance.
std::vector<uint8_t> develop(const std::vector<float>& linear, int width, int height,
                             const RgbOptions& options, uint64_t frame_seed);

/// Rain streaks drawn over the developed image (intensity mm/h), deterministic per seed.
void draw_rain(std::vector<uint8_t>& rgb, int width, int height, const Lighting& lighting,
               uint64_t frame_seed);

}  // namespace corsa::sensors::detail
