#include "corsa/sensors/birds_eye.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>

#include "scene_data.h"
#include "shading.h"

namespace corsa::sensors {
namespace {

/// sRGB-like 8-bit encoding lround(255 x^(1/2.2)) of x in [0, 1] without a pow() per channel:
/// the linear values where the code steps up, searched in a table. Code k covers
/// [((k - 0.5) / 255)^2.2, ((k + 0.5) / 255)^2.2), the same split lround makes.
///
/// The code of x is the number of steps at or below it (255 for x >= 1 and NaN, 0 below the
/// first step). A binary search over the 255 steps mispredicted its branches on every channel
/// of every pixel; instead the double's exponent and top mantissa bits pick a bucket (a 2^-8
/// relative width, narrower than the 0.86% between the two closest steps) that holds the count
/// of steps below its start, and at most a step or two more are compared: the same code.
class GammaEncoder {
 public:
  GammaEncoder() {
    for (int k = 0; k < 255; ++k) {
      steps_[k] = std::pow((k + 0.5) / 255.0, 2.2);
    }
    int below = 0;  // the buckets' starts rise: each count goes on from the previous one
    for (size_t i = 0; i < starts_.size(); ++i) {
      const double start = std::bit_cast<double>((i + bucket(kLow)) << kBucketShift);
      below = count(start, below);
      starts_[i] = static_cast<uint8_t>(below);
    }
  }
  uint8_t operator()(double x) const {
    if (!(x < 1.0)) {
      return 255;  // every step is below 1; NaN compares below none of them
    }
    if (!(x >= kLow)) {
      return 0;  // below the first step (negative and zero too)
    }
    return count(x, starts_[bucket(x) - bucket(kLow)]);
  }

 private:
  /// Below the first step, (0.5 / 255)^2.2 = 1.1e-6.
  static constexpr double kLow = 0x1p-20;
  static constexpr int kBucketShift = 44;  // 52 mantissa bits less the 8 kept
  static uint64_t bucket(double x) { return std::bit_cast<uint64_t>(x) >> kBucketShift; }
  /// Steps at or below x, counting on from `from` (which are known to be).
  uint8_t count(double x, int from) const {
    int k = from;
    while (k < 255 && steps_[static_cast<size_t>(k)] <= x) {
      ++k;
    }
    return static_cast<uint8_t>(k);
  }

  std::array<double, 255> steps_{};
  /// Buckets from kLow up to 1 (exponents -20 to -1, 256 buckets each).
  std::array<uint8_t, 20 * 256> starts_{};
};

}  // namespace

BirdsEyeImage render_birds_eye(const Scene& scene, const BirdsEyeOptions& o,
                               const Rigid& world_from_body, const Lighting* lighting) {
  const detail::SceneData& d = scene.data();
  BirdsEyeImage img;
  img.width = o.width;
  img.height = o.height;
  const size_t n = static_cast<size_t>(o.width) * o.height;
  img.rgb.assign(3 * n, 0);
  img.semantic.assign(n, 0);
  img.instance.assign(n, 0);
  const bool shaded = o.style == BirdsEyeStyle::kRgb && lighting != nullptr;
  detail::ShadingContext shading;
  if (shaded) {
    // Footprints in metres: one pixel covers mpp at "distance" 1.
    shading =
        detail::make_shading_context(d, *lighting, o.extent_m / o.width, RenderQuality::kFast);
  }
  const double heading = o.follow_heading ? std::atan2(world_from_body.rotation.m[1][0],
                                                       world_from_body.rotation.m[0][0])
                                          : M_PI / 2.0;  // north up
  const Vec3 up{std::cos(heading), std::sin(heading), 0.0};
  const Vec3 right{std::sin(heading), -std::cos(heading), 0.0};
  const double mpp = o.extent_m / o.width;
  const Vec3 centre = d.to_local(world_from_body.translation);
  const double top = centre.z + o.altitude_m;
  const double cx = (o.width - 1) / 2.0;
  const double cy = (o.height - 1) / 2.0;
  const GammaEncoder encode;
  tbb::parallel_for(tbb::blocked_range<int>(0, o.height), [&](const tbb::blocked_range<int>& r) {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    for (int row = r.begin(); row != r.end(); ++row) {
      for (int col0 = 0; col0 < o.width; col0 += 16) {
        alignas(64) RTCRayHit16 rh;
        alignas(64) int valid[16];
        for (int k = 0; k < 16; ++k) {
          const int col = col0 + k;
          valid[k] = col < o.width ? -1 : 0;
          const Vec3 p = centre + right * ((col - cx) * mpp) + up * ((cy - row) * mpp);
          rh.ray.org_x[k] = static_cast<float>(p.x);
          rh.ray.org_y[k] = static_cast<float>(p.y);
          rh.ray.org_z[k] = static_cast<float>(top);
          rh.ray.dir_x[k] = 0.0f;
          rh.ray.dir_y[k] = 0.0f;
          rh.ray.dir_z[k] = -1.0f;
          rh.ray.tnear[k] = 0.0f;
          rh.ray.tfar[k] = static_cast<float>(2.0 * o.altitude_m + 100.0);
          rh.ray.mask[k] = 0xFFFFFFFFu;
          rh.ray.flags[k] = 0;
          rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
          rh.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
        }
        rtcIntersect16(valid, d.top, &context, &rh);
        for (int k = 0; k < 16 && col0 + k < o.width; ++k) {
          if (rh.hit.geomID[k] == RTC_INVALID_GEOMETRY_ID) {
            continue;
          }
          const size_t px = static_cast<size_t>(row) * o.width + col0 + k;
          const auto label = d.label(rh.hit.instID[0][k], rh.hit.geomID[k], rh.hit.primID[k]);
          img.semantic[px] = static_cast<uint8_t>(label.semantic);
          img.instance[px] = label.instance_id;
          Rgb8 c = semantic_color(label.semantic);
          if (shaded) {
            Vec3 nrm = d.world_normal(rh.hit.instID[0][k],
                                      {rh.hit.Ng_x[k], rh.hit.Ng_y[k], rh.hit.Ng_z[k]});
            if (nrm.z < 0.0) {
              nrm = -nrm;
            }
            detail::SurfaceHit hit;
            hit.inst_id = rh.hit.instID[0][k];
            hit.geom_id = rh.hit.geomID[k];
            hit.prim_id = rh.hit.primID[k];
            hit.u = rh.hit.u[k];
            hit.v = rh.hit.v[k];
            hit.position = {rh.ray.org_x[k], rh.ray.org_y[k], top - rh.ray.tfar[k]};
            hit.normal = nrm;
            hit.view_dir = {0.0, 0.0, -1.0};
            hit.distance = 1.0;
            hit.semantic = label.semantic;
            hit.entity = label.entity;
            // A map view: lit by the sun and the open sky, no shadows or tone curve.
            const detail::SurfacePoint s = detail::surface_at(shading, hit);
            const Color v = detail::combine(detail::shade_terms(shading, s, nullptr, nullptr),
                                            detail::Visibility{});
            c = {encode(v.r), encode(v.g), encode(v.b)};
          }
          img.rgb[3 * px] = c.r;
          img.rgb[3 * px + 1] = c.g;
          img.rgb[3 * px + 2] = c.b;
        }
      }
    }
  });
  return img;
}

}  // namespace corsa::sensors
