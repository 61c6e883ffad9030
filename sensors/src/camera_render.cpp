#include "corsa/sensors/camera_render.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <mutex>

#include "camera_frame.h"
#include "scene_data.h"
#include "shading.h"

namespace corsa::sensors {
namespace {

constexpr int kTile = 4;  // 4x4 pixels = one 16-ray packet

/// Camera pose at a time offset dt (s) from the capture, for motion blur.
Rigid camera_at(const CameraMotion& m, const Rigid& world_from_cam, double dt) {
  const Rigid spin = rigid_from_pose(0, 0, 0, m.yaw_rate * dt, 0, 0);
  Rigid moved;
  moved.rotation = spin.rotation * world_from_cam.rotation;
  moved.translation =
      m.pivot + m.velocity * dt + spin.rotation * (world_from_cam.translation - m.pivot);
  return moved;
}

bool anything_moves(const Scene& scene, const CameraMotion& motion) {
  bool moving = norm(motion.velocity) > 0.0 || motion.yaw_rate != 0.0;
  for (const auto& e : scene.entities()) {
    moving = moving || e.vx != 0.0 || e.vy != 0.0 || e.vz != 0.0 || e.yaw_rate != 0.0;
  }
  return moving;
}

/// Depth along each pixel's ray (infinite for the sky), for the precipitation's depth test.
void ray_distances(const std::vector<detail::PixelGeometry>& records, std::vector<float>& out) {
  out.resize(records.size());
  for (size_t i = 0; i < records.size(); ++i) {
    out[i] = records[i].distance;
  }
}

}  // namespace

Rigid world_from_optical(const Rigid& world_from_body) {
  return world_from_body * optical_in_body();
}

CameraRenderer::CameraRenderer(const CameraIntrinsics& intrinsics)
    : model_(intrinsics), buffers_(std::make_shared<detail::FrameBuffers>()) {
  const int w = intrinsics.width;
  const int h = intrinsics.height;
  rays_.resize(static_cast<size_t>(w) * h * 3);
  // Undistorting every pixel is iterative (~0.3 s for 1280x720): rows in parallel.
  tbb::parallel_for(tbb::blocked_range<int>(0, h), [&](const tbb::blocked_range<int>& rows) {
    for (int row = rows.begin(); row != rows.end(); ++row) {
      for (int col = 0; col < w; ++col) {
        const Vec3 r = model_.ray({static_cast<double>(col), static_cast<double>(row)});
        float* out = &rays_[3 * (static_cast<size_t>(row) * w + col)];
        out[0] = static_cast<float>(r.x);
        out[1] = static_cast<float>(r.y);
        out[2] = static_cast<float>(r.z);
      }
    }
  });
}

Vec3 CameraRenderer::pixel_ray(int col, int row) const {
  const float* r = &rays_[3 * (static_cast<size_t>(row) * model_.width() + col)];
  return {r[0], r[1], r[2]};
}

CameraImages CameraRenderer::render(const Scene& scene, const CameraMotion& motion,
                                    const RenderSettings& settings) const {
  const int w = model_.width();
  const int h = model_.height();
  const size_t n = static_cast<size_t>(w) * h;
  CameraImages out;
  out.width = w;
  out.height = h;
  out.instance.assign(n, 0);
  if (settings.outputs.depth) {
    out.depth.assign(n, 0.0f);
  }
  if (settings.outputs.semantic) {
    out.semantic.assign(n, 0);
  }
  RenderSettings effective = settings;
  effective.outputs.rgb = settings.outputs.rgb && settings.lighting != nullptr;
  const bool rgb = effective.outputs.rgb;
  std::unique_lock<std::mutex> lock(buffers_->mutex, std::try_to_lock);
  detail::FrameBuffers own;  // only when another pass holds the kept buffers
  detail::FrameBuffers& b = lock.owns_lock() ? *buffers_ : own;
  std::vector<detail::PixelRecord>& records = b.records;
  std::vector<float>& motion_vectors = b.motion_vectors;
  detail::ShadingContext shading;
  detail::Pass p;
  p.scene = &scene.data();
  p.model = &model_;
  p.rays = rays_.data();
  p.settings = &effective;
  p.width = w;
  p.height = h;
  p.patterns = detail::RayPatterns(effective.frame_seed);
  const Rigid world_from_cam = world_from_optical(motion.world_from_body);
  p.origin_local = scene.data().to_local(world_from_cam.translation);
  for (int r = 0; r < 3; ++r) {
    for (int k = 0; k < 3; ++k) {
      p.rotation[r][k] = static_cast<float>(world_from_cam.rotation.m[r][k]);
    }
  }
  p.carrier = detail::CarrierExit(settings.carrier, world_from_cam.translation);
  p.out = &out;
  if (rgb) {
    shading = detail::make_shading_context(scene.data(), *settings.lighting, 1.0 / model_.fx(),
                                           settings.rgb.quality);
    detail::place_eye(shading, p.origin_local);
    p.shading = &shading;
    b.linear.resize(3 * n);
    if (!shading.quality.denoise && shading.quality.edge_samples <= 0) {
      // Nothing reads a pixel's terms or geometry after it is shaded: composite it at once and
      // keep only its distance (the same bytes, without the about 180 bytes a pixel written and
      // read back).
      p.direct = b.linear.data();
      b.distances.resize(n);
      p.distances = b.distances.data();
    } else {
      b.geometry.resize(n);
      p.geometry = &b.geometry;
      records.resize(n);
      b.visibility.resize(n);
      b.visibility_scratch.resize(n);
      b.edges.resize(n);
      p.records = &records;
      p.visibility = &b.visibility;
      p.visibility_scratch = &b.visibility_scratch;
      p.edges = &b.edges;
    }
    // `fast` leaves out the blur, and with it the motion vectors that only the blur reads.
    p.motion = shading.quality.motion_blur && anything_moves(scene, motion);
    if (p.motion) {
      p.cam_early = camera_at(motion, world_from_cam, -detail::kMotionHalf).inverse();
      p.cam_late = camera_at(motion, world_from_cam, detail::kMotionHalf).inverse();
      motion_vectors.assign(2 * n, 0.0f);
      p.motion_vectors = &motion_vectors;
    }
  }
  const int tiles_x = (w + kTile - 1) / kTile;
  const int tiles_y = (h + kTile - 1) / kTile;
  tbb::parallel_for(tbb::blocked_range<int>(0, tiles_y), [&](const tbb::blocked_range<int>& r) {
    detail::TileScratch scratch;
    for (int ty = r.begin(); ty != r.end(); ++ty) {
      for (int tx = 0; tx < tiles_x; ++tx) {
        detail::trace_tile(p, tx * kTile, ty * kTile, scratch);
      }
    }
  });
  if (!rgb) {
    return out;
  }
  if (shading.quality.denoise) {
    detail::filter_visibility(p);
  }
  std::vector<float>& linear = b.linear;
  if (p.direct == nullptr) {
    detail::composite(p, linear);
    detail::antialias_edges(p, linear, b.linear_copy);
  }
  const detail::Exposure exposure = detail::choose_exposure(linear, w, h, settings.rgb);
  if (p.motion) {
    // The vectors span 2 kMotionHalf seconds; the blur spans the exposure time.
    const float scale = static_cast<float>(exposure.shutter_s / (2.0 * detail::kMotionHalf));
    detail::motion_blur(linear, motion_vectors, scale, w, h, b.linear_copy);
  }
  if (shading.quality.bloom) {
    // Only light far beyond white glares: lamps, bulbs and the sun, not a lit window.
    detail::bloom(linear, w, h, 64.0 / exposure.scale);  // a lit window at night stays below
  }
  // OpenSCENARIO's wind direction is where it blows to; the image's right is the optical x axis.
  const Lighting& light = *settings.lighting;
  const Vec3 wind{light.wind_speed * std::cos(light.wind_direction),
                  light.wind_speed * std::sin(light.wind_direction), 0.0};
  const double lateral_wind = dot(wind, world_from_cam.rotation.column(0));
  if (p.direct == nullptr) {
    ray_distances(b.geometry, b.distances);  // stage 1 wrote them itself otherwise
  }
  detail::draw_precipitation(linear, b.distances, w, h, model_.fx(), light, lateral_wind,
                             exposure.shutter_s, settings.frame_seed);
  // `fast` develops without sensor noise: a clean image, and no random draw per channel.
  RgbOptions developed = settings.rgb;
  developed.noise = developed.noise && shading.quality.sensor_noise;
  out.rgb = detail::develop(linear, w, h, developed, exposure, settings.frame_seed);
  return out;
}

}  // namespace corsa::sensors
