#pragma once

// The buffers of one camera pass and its stages (private; camera_render.cpp runs them):
//   1. trace (camera_trace.cpp): one primary ray through each pixel centre gives depth, class
//      and instance; for RGB the surface there, its shading terms and the visibilities
//      estimated with sun, sky, light, reflection and glass rays (camera_rays.cpp);
//   2. filter the visibilities across neighbours of the same surface (camera_denoise.cpp);
//   3. composite: terms x visibilities, through the air (in stage 1 itself, pixel by pixel, when
//      neither the filter nor the edge samples read the terms: Pass::direct);
//   4. anti-alias edge pixels with extra sub-pixel samples (camera_edges.cpp).

#include <embree3/rtcore.h>

#include <cstdint>
#include <mutex>
#include <optional>
#include <vector>

#include "brdf.h"
#include "carrier.h"
#include "corsa/sensors/camera_render.h"
#include "shading.h"

namespace corsa::sensors::detail {

/// A colour in single precision (buffers).
struct Color3f {
  float r = 0.0f, g = 0.0f, b = 0.0f;
  Color3f() = default;
  explicit Color3f(Color c)
      : r(static_cast<float>(c.r)), g(static_cast<float>(c.g)), b(static_cast<float>(c.b)) {}
  Color get() const { return {r, g, b}; }
};

/// Where the centre sample of a pixel lies: what the filter and the edge test compare across
/// neighbourhoods, kept apart from the shading (32 bytes a pixel, two to a cache line).
struct PixelGeometry {
  float position[3] = {0, 0, 0};  ///< tracer-local
  float normal[3] = {0, 0, 0};
  float distance = 0.0f;    ///< along the ray; infinite for the sky
  uint32_t surface_id = 0;  ///< 0: sky
};

/// The light of the centre sample of a pixel, as the later stages need it.
struct PixelRecord {
  ShadeTerms terms;  ///< (double colours: the terms are read once per pixel and sample)
  Color3f mirrored;  ///< radiance from the mirror direction (mirror surfaces)
  Color3f behind;    ///< radiance through glass
  bool has_mirrored = false;
  bool has_behind = false;
};

/// Visibilities of a pixel's centre sample in single precision (filtered in place).
struct PixelVisibility {
  float sun = 1.0f;
  float sky[3] = {1.0f, 1.0f, 1.0f};
  float lights = 1.0f;

  Visibility get() const { return {sun, {sky[0], sky[1], sky[2]}, lights}; }
};

/// The interleaved patterns (brdf.h) of a frame's secondary rays (camera_rays.cpp): the
/// directions of the sky rays.
struct RayPatterns {
  InterleavedPattern sky;

  RayPatterns() = default;
  explicit RayPatterns(uint64_t frame_seed) : sky(pixel_key(frame_seed, 0, 0x5eed04)) {}
};

/// Everything one pass shares.
struct Pass {
  const SceneData* scene = nullptr;
  const CameraModel* model = nullptr;
  const float* rays = nullptr;  ///< per pixel centre, optical frame
  const RenderSettings* settings = nullptr;
  const ShadingContext* shading = nullptr;
  float rotation[3][3] = {};  ///< optical frame to map, single precision
  Rigid cam_early, cam_late;  ///< inverse poses at +-kMotionHalf (motion vectors)
  bool motion = false;        ///< compute motion vectors
  Vec3 origin_local;
  CarrierExit carrier;  ///< where primary rays leave the carrying vehicle
  CameraImages* out = nullptr;
  std::vector<PixelGeometry>* geometry = nullptr;
  std::vector<PixelRecord>* records = nullptr;
  std::vector<PixelVisibility>* visibility = nullptr;
  std::vector<float>* motion_vectors = nullptr;  ///< pixels over 2 kMotionHalf seconds
  std::vector<PixelVisibility>* visibility_scratch = nullptr;  ///< the filter's other buffer
  std::vector<uint8_t>* edges = nullptr;                       ///< anti-aliasing marks
  /// Set when no later stage reads a pixel's terms and visibilities (no filter, no extra edge
  /// samples): stage 1 then composites each pixel itself into these 3 floats a pixel, and
  /// `records` and `visibility` are neither written nor read.
  float* direct = nullptr;
  /// With `direct`: each pixel's distance along its ray (infinite for the sky), the one field of
  /// its geometry a later stage reads (the precipitation's depth test); `geometry` is then
  /// neither written nor read (32 bytes a pixel less to store).
  float* distances = nullptr;
  RayPatterns patterns;  ///< of the frame's seed
  int width = 0;
  int height = 0;
};

/// What lane k of a packet traced from the pass's origin along unit `dir` hit, as shading needs
/// it: ids, barycentrics, tracer-local position, world normal facing the viewer, and `label`.
SurfaceHit primary_hit(const Pass& p, const RTCRayHit16& rh, int k, Vec3 dir,
                       const SceneData::Label& label);

/// The per-pixel buffers of one pass. A renderer keeps them from frame to frame: at 1280x720
/// they take about 200 MB, and fresh pages every frame (page faults and the kernel zeroing
/// them) cost about a fifth of a `fast` frame. Every stage writes each pixel it later reads, so
/// nothing needs clearing between frames. One pass at a time holds `mutex`; a pass that finds
/// them in use (two cameras of one renderer at once) allocates its own.
struct FrameBuffers {
  std::mutex mutex;
  std::vector<PixelGeometry> geometry;
  std::vector<PixelRecord> records;
  std::vector<PixelVisibility> visibility;
  std::vector<PixelVisibility> visibility_scratch;
  std::vector<float> motion_vectors;
  std::vector<float> linear;  ///< radiance, 3 floats a pixel
  /// The anti-aliasing's copy of the composited image, then the motion blur's other buffer
  /// (swapped with linear).
  std::vector<float> linear_copy;
  std::vector<float> distances;  ///< along each pixel's ray, for the precipitation
  std::vector<uint8_t> edges;
};

/// Motion vectors are computed over +-kMotionHalf seconds and scaled to the exposure time.
inline constexpr double kMotionHalf = 0.005;

/// Unit ray direction in the map frame through image point (x, y) (pixel units; centres at
/// integers), interpolated between the precomputed pixel-centre rays.
Vec3 ray_at(const Pass& p, double x, double y);

/// ray_at() at the centre of pixel `px` (the same value, without the interpolation).
inline Vec3 centre_ray(const Pass& p, size_t px) {
  const float* v = p.rays + 3 * px;
  const Vec3 local = normalized(Vec3{v[0], v[1], v[2]});
  const auto& m = p.rotation;
  return {m[0][0] * local.x + m[0][1] * local.y + m[0][2] * local.z,
          m[1][0] * local.x + m[1][1] * local.y + m[1][2] * local.z,
          m[2][0] * local.x + m[2][1] * local.y + m[2][2] * local.z};
}

/// Ray batches of a tile, kept between tiles to save allocations (one per thread range).
struct TileScratch {
  std::vector<RTCRay16> sun;    ///< sun shadow rays, 16 to a packet (lanes in use: sun_owner)
  std::vector<int> sun_owner;   ///< the pixel (0..15) a sun ray belongs to
  std::vector<RTCRay> rays;     ///< shadow rays to the lights
  std::vector<int> ray_owner;   ///< the pixel (0..15) a ray belongs to
  std::vector<RTCRayHit> hits;  ///< rays that need their hit (sky, mirror, glass)
  std::vector<int> hit_owner;
  std::vector<int> hit_kind;
  std::vector<RTCRayHit> far;         ///< sky rays past their near stretch, through the entities
  std::vector<RTCRayHit> far_static;  ///< the same through the far static scene
  std::vector<size_t> far_index;      ///< index into `hits`
  std::vector<RTCRay> second;         ///< shadow rays from the secondary hits
  std::vector<int> second_owner;      ///< index into `hits`
  std::vector<float> weights;
  std::vector<std::optional<SurfacePoint>> found;  ///< per hit: the surface a mirror or glass
                                                   ///< ray found
  std::vector<int> sun_seen;                       ///< per hit: -1 no shadow ray, 0 shadowed, 1 lit

  void clear() {
    sun_owner.clear();
    rays.clear();
    ray_owner.clear();
    hits.clear();
    hit_owner.clear();
    hit_kind.clear();
  }
};

/// Stage 1 for the 4x4 pixel tile at (col0, row0).
void trace_tile(const Pass& p, int col0, int row0, TileScratch& scratch);

/// Stage 2: filters the visibilities in place (deterministic on any thread count).
void filter_visibility(const Pass& p);

/// Stage 3: the radiance of every pixel's centre sample into `linear` (3 floats a pixel).
void composite(const Pass& p, std::vector<float>& linear);

/// Stage 3 for one pixel: its terms times its visibilities (each rounded to the single
/// precision the buffers keep), seen through the air over `distance` (rounded likewise) along
/// its centre ray. A pass that composites at once (Pass::direct) does the same a tile at a time,
/// with the air's exponentials of Lighting::transmittances.
Color composite_pixel(const Pass& p, size_t px, const ShadeTerms& terms, const PixelVisibility& vis,
                      float distance);

/// Stage 4: anti-aliases pixels whose neighbours show another surface or depth. `centre` gets
/// a copy of the image before it (the samples read their neighbours' centre radiance there).
/// Returns the number of pixels resampled.
size_t antialias_edges(const Pass& p, std::vector<float>& linear, std::vector<float>& centre);

}  // namespace corsa::sensors::detail
