#pragma once

// RGB shading and image post-processing for the camera renderer (private). A shaded sample is
// split into terms that do not depend on visibility and the visibilities that multiply them
// (sun, sky, local lights), so that the noisy visibilities, estimated with few rays, can be
// filtered without blurring the textures (see camera_render.cpp).

#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "corsa/sensors/camera_model.h"
#include "corsa/sensors/camera_render.h"
#include "corsa/sensors/environment.h"
#include "light_list.h"
#include "scene_data.h"

namespace corsa::sensors::detail {

/// Sample counts of a quality preset (corsa/sensors/rig.h RenderQuality).
struct QualitySettings {
  int sun_rays = 1;            ///< shadow rays towards the sun per pixel
  bool soft_sun = false;       ///< aim them over the solar disc (soft shadows)
  int sky_rays = 0;            ///< occlusion rays per pixel (0: the unoccluded sky light)
  bool bounce_shadow = false;  ///< occluders lit by the sun get a shadow ray of their own
  int light_rays = 0;          ///< shadow rays towards street and vehicle lights (0: unshadowed)
  bool reflections = false;    ///< mirror rays on smooth surfaces (else the sky is mirrored)
  bool transmission = false;   ///< rays through glass
  int edge_samples = 0;        ///< extra sub-pixel samples on edge pixels (anti-aliasing)
  bool denoise = false;        ///< filter the visibilities across similar neighbours
  bool bloom = false;          ///< glare of very bright pixels
  bool motion_blur = false;    ///< smear each pixel along its image motion during the exposure
  bool glossy_sky = false;     ///< rough reflections see the sky light along the mirror direction
                               ///< (else the sky light on the normal)
  bool trilinear = false;      ///< texture noise blended between two mip levels (else the nearest)
  bool sensor_noise = false;   ///< the sensor's shot and read noise (when the camera asks for it)
};
QualitySettings quality_settings(RenderQuality quality);

/// Everything shading needs, prepared once per frame.
struct ShadingContext {
  const SceneData* scene = nullptr;
  const Lighting* lighting = nullptr;
  LightList lights;
  std::vector<uint32_t> entity_lamps;  ///< by instance pool index: lit LightRole bits
  uint32_t static_lamps = 0;           ///< lit LightRole bits of static lamps (street lamps)
  double darkness = 0.0;               ///< 0 day .. 1 night (lit windows)
  double pixel_angle = 1e-3;           ///< radians per pixel, for texture footprints
  double ground_z = 0.0;               ///< tracer-local height of the ground (fog density)
  /// By instance pool index: the lamps' LightStateAction looks; empty when no entity has one.
  std::vector<LampLooks> entity_looks;
  QualitySettings quality;
  /// Tracer-local height of the camera (NaN: none) and the air there: most rays seen through
  /// the air start at the eye, and its fog and haze densities are the same for all of them.
  double eye_z = std::numeric_limits<double>::quiet_NaN();
  Lighting::AirStart eye_air;
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

/// A surface point's material as the lighting needs it.
struct SurfacePoint {
  Vec3 position;
  Vec3 normal;
  Vec3 view_dir;
  double distance = 0.0;
  Color diffuse;  ///< diffuse albedo (base colour without the metal part, darkened when wet)
  Color f0;       ///< specular reflectance at normal incidence
  double roughness = 0.8;
  double clearcoat = 0.0;
  double transmission = 0.0;
  Color emission;
  /// Mirror-like enough to trace a reflection ray (clear coat, glass, metal, puddles).
  bool mirror = false;
  uint32_t surface_id = 0;  ///< the same for samples of one object and material (AA reuse)
};

/// The bit of SurfacePoint::surface_id set on foliage and on facade walls: foliage's facets
/// stand for clumps of leaves and a wall's folds into its window reveals are soft in shade, so a
/// fold between two of them is no edge to anti-alias (camera_edges.cpp); outlines, depth steps
/// and other materials (panes, sills) still are. The other 31 bits are the surface's hash.
inline constexpr uint32_t kFoldlessSurface = 0x80000000u;

/// Radiance of a sample = base + sun * sun visibility + sky (x) sky visibility + lights *
/// light visibility (per channel for the sky: its bounce has a colour).
struct ShadeTerms {
  Color base;  ///< emission, mirrored and transmitted light
  Color sun;
  Color sky;
  Color lights;
};

/// Visibilities estimated with rays (1 = unoccluded), and the radiance of secondary rays.
struct Visibility {
  double sun = 1.0;
  Color sky{1.0, 1.0, 1.0};
  double lights = 1.0;
};

ShadingContext make_shading_context(const SceneData& scene, const Lighting& lighting,
                                    double pixel_angle, RenderQuality quality);
/// Tells the context where the camera is (tracer-local), for the air in front of it.
void place_eye(ShadingContext& c, Vec3 eye);

/// The material at a hit, prefiltered to the pixel footprint (`footprint_scale` widens it for
/// secondary rays), with wet road, puddles and snow cover applied.
SurfacePoint surface_at(const ShadingContext& c, const SurfaceHit& hit,
                        double footprint_scale = 1.0);

/// SurfacePoint::surface_id of a hit on material `id` of geometry `geom_id` of instance
/// `inst_id` (Embree's ids), without shading it.
uint32_t surface_id_of(const SceneData& d, unsigned inst_id, unsigned geom_id, MaterialId id);

/// The visibility-independent terms of a surface point. `mirrored` is the radiance arriving
/// from the mirror direction and `behind` the radiance seen through glass (`has_*` false: the
/// sky and the dark cabin stand in).
ShadeTerms shade_terms(const ShadingContext& c, const SurfacePoint& s, const Color* mirrored,
                       const Color* behind);

inline Color combine(const ShadeTerms& t, const Visibility& v) {
  return t.base + t.sun * v.sun + t.sky * v.sky + t.lights * v.lights;
}

/// Radiance of a point seen by a secondary ray (a reflection or through glass): its material
/// lit by the sun (shadowed when `sun_visible` is false), the sky and the lights unshadowed.
Color shade_secondary(const ShadingContext& c, const SurfacePoint& s, bool sun_visible);

/// Sky radiance seen along a ray, with the air (fog, haze, rain) in front of it.
Color sky_seen(const ShadingContext& c, Vec3 origin, Vec3 direction);
/// Radiance `at` a surface `distance` metres along a ray, seen through the air.
Color through_air(const ShadingContext& c, Color radiance, Vec3 origin, Vec3 direction,
                  double distance);

/// Motion blur along per-pixel motion vectors (pixels, 2 floats per pixel, times `scale`):
/// `linear` becomes the blurred image; `scratch` is swapped with it (its old contents are lost).
void motion_blur(std::vector<float>& linear, const std::vector<float>& motion, float scale,
                 int width, int height, std::vector<float>& scratch);

/// The exposure (linear scale before the tone curve) of a frame: the rig's manual one, or the
/// metered one with its exposure time (s) and ISO.
struct Exposure {
  double scale = 1.0;
  double shutter_s = 0.004;
  double iso = 100.0;
};
/// The display value (before the tone curve) auto exposure gives a scene's log-average
/// luminance `scene_cd_m2` (cd/m^2): 0.18 from dusk (30 cd/m^2) up, falling below it as the
/// square root of the luminance (0.02 at 0.4 cd/m^2, a street lit at night), at least 0.005.
double exposure_key(double scene_cd_m2);
Exposure choose_exposure(const std::vector<float>& linear, int width, int height,
                         const RgbOptions& options);

/// Glare: a share of the light of very bright pixels spread around them, in place.
void bloom(std::vector<float>& linear, int width, int height, double threshold);

/// Exposure, vignetting, sensor noise, the filmic tone curve, display encoding and 8-bit
/// quantisation of linear radiance.
std::vector<uint8_t> develop(const std::vector<float>& linear, int width, int height,
                             const RgbOptions& options, const Exposure& exposure,
                             uint64_t frame_seed);

/// Falling rain or snow drawn into linear radiance before development: streaks and flakes at
/// random depths in front of the scene (only where the scene is farther), blurred over the
/// exposure time, lit by the sky, slanted by the wind across the view (`lateral_wind`, m/s
/// towards the image's right) over their fall speed. Deterministic per seed.
void draw_precipitation(std::vector<float>& linear, const std::vector<float>& depth, int width,
                        int height, double fx, const Lighting& lighting, double lateral_wind,
                        double exposure_s, uint64_t frame_seed);

}  // namespace corsa::sensors::detail
