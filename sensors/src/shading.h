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
  std::vector<Color> entity_albedo;  ///< by instance pool index
  std::vector<Color> static_albedo;  ///< by static geometry id (when the mesh has a colour)
  std::vector<char> static_has_color;
  std::array<Color, kSemanticClassCount> class_albedo;
};

/// Diffuse albedo (linear) of a hit: the entity's paint, the mesh's colour, or its class's.
inline Color surface_albedo(const ShadingContext& c, const SceneData::Label& label,
                            unsigned geom_id) {
  if (label.entity >= 0) {
    return c.entity_albedo[label.entity];
  }
  if (c.static_has_color[geom_id]) {
    return c.static_albedo[geom_id];
  }
  return c.class_albedo[static_cast<size_t>(label.semantic)];
}

ShadingContext make_shading_context(const SceneData& scene, const Lighting& lighting);

/// Linear radiance of a surface point (tracer-local position), before fog.
Color shade_surface(const ShadingContext& c, Vec3 position, Vec3 normal, Vec3 view_dir,
                    SemanticClass semantic, Color albedo, bool sunlit);

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
