#include "corsa/sensors/lidar.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <numbers>

#include "carrier.h"
#include "fast_normal.h"
#include "scene_data.h"

namespace corsa::sensors {
namespace {

constexpr int kColumnsPerBlock = 32;
constexpr double kDeg = std::numbers::pi / 180.0;

struct ScanContext {
  const detail::SceneData* scene;
  const LidarOptions* options;
  const float* directions;  // body frame
  float rotation[3][3];     // body to map
  Vec3 origin;              // sensor position, tracer-local
  double weather;           // 1/m
  uint64_t frame_seed;
  int channels;
  detail::CarrierExit carrier;
  std::array<double, kSemanticClassCount> reflectivity;
};

/// Decides whether a hit becomes a point and where; writes it at `out` and says whether it did.
class ReturnModel {
 public:
  ReturnModel(const ScanContext& c, uint64_t seed) : c_(c), rng_(seed) {}

  bool make(const RTCRayHit16& rh, int lane, const float* dir_body, LidarPoint& out) {
    const double r = rh.ray.tfar[lane];
    const LidarOptions& o = *c_.options;
    const unsigned inst = rh.hit.instID[0][lane];
    const auto label = c_.scene->label(inst, rh.hit.geomID[lane], rh.hit.primID[lane]);
    Vec3 n{rh.hit.Ng_x[lane], rh.hit.Ng_y[lane], rh.hit.Ng_z[lane]};
    if (inst != 0) {
      n = c_.scene->instances[inst - 1].normal_matrix * n;  // object to world normal
    }
    const Vec3 d{rh.ray.dir_x[lane], rh.ray.dir_y[lane], rh.ray.dir_z[lane]};
    const double cos_inc = std::fabs(dot(n, d)) / std::sqrt(dot(n, n));
    double intensity = c_.reflectivity[static_cast<size_t>(label.semantic)] * cos_inc *
                       std::exp(-o.atmosphere_attenuation_rate * r);
    if (c_.weather > 0.0) {
      const double transmission = std::exp(-2.0 * c_.weather * r);
      if (rng_.uniform01() >= transmission) {
        return false;
      }
      intensity *= transmission;
    }
    if (o.dropoff_general_rate > 0.0 && rng_.uniform01() < o.dropoff_general_rate) {
      return false;
    }
    if (intensity < o.dropoff_intensity_limit && o.dropoff_zero_intensity > 0.0 &&
        rng_.uniform01() < o.dropoff_zero_intensity) {
      return false;
    }
    const double range = o.noise_stddev_m > 0.0 ? r + o.noise_stddev_m * normal_.next(rng_) : r;
    out.x = static_cast<float>(dir_body[0] * range);
    out.y = static_cast<float>(dir_body[1] * range);
    out.z = static_cast<float>(dir_body[2] * range);
    out.intensity = static_cast<float>(intensity);
    out.semantic = label.semantic;
    out.instance_id = label.instance_id;
    return true;
  }

 private:
  const ScanContext& c_;
  RandomStream rng_;
  detail::NormalPairs normal_;
};

/// Fires the beams of azimuth columns [first, last) in packets of 16, writing the points from
/// `out` on; returns how many it wrote.
size_t scan_block(const ScanContext& c, int first, int last, uint64_t block, LidarPoint* out) {
  ReturnModel model(c, detail::block_seed(c.frame_seed, block));
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  const size_t begin = static_cast<size_t>(first) * c.channels;
  const size_t end = static_cast<size_t>(last) * c.channels;
  alignas(64) RTCRayHit16 rh;
  alignas(64) int valid[16];
  const float far = static_cast<float>(c.options->range_m);
  const auto& m = c.rotation;
  const float ox = static_cast<float>(c.origin.x);
  const float oy = static_cast<float>(c.origin.y);
  const float oz = static_cast<float>(c.origin.z);
  size_t written = 0;
  int ring = 0;
  int step = first;
  for (size_t i = begin; i < end; i += 16) {
    const int n = static_cast<int>(std::min<size_t>(16, end - i));
    for (int k = 0; k < 16; ++k) {
      valid[k] = k < n ? -1 : 0;
      const float* db = c.directions + 3 * (i + (k < n ? k : 0));
      const float dx = m[0][0] * db[0] + m[0][1] * db[1] + m[0][2] * db[2];
      const float dy = m[1][0] * db[0] + m[1][1] * db[1] + m[1][2] * db[2];
      const float dz = m[2][0] * db[0] + m[2][1] * db[1] + m[2][2] * db[2];
      rh.ray.org_x[k] = ox;
      rh.ray.org_y[k] = oy;
      rh.ray.org_z[k] = oz;
      rh.ray.dir_x[k] = dx;
      rh.ray.dir_y[k] = dy;
      rh.ray.dir_z[k] = dz;
      rh.ray.tnear[k] = c.carrier.active() ? c.carrier.exit({dx, dy, dz}) : 0.0f;
      rh.ray.tfar[k] = far;
      rh.ray.mask[k] = 0xFFFFFFFFu;
      rh.ray.flags[k] = 0;
      rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
      rh.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
    }
    rtcIntersect16(valid, c.scene->top, &context, &rh);
    for (int k = 0; k < n; ++k) {
      if (rh.hit.geomID[k] != RTC_INVALID_GEOMETRY_ID) {
        LidarPoint& p = out[written];
        if (model.make(rh, k, c.directions + 3 * (i + k), p)) {
          p.ring = static_cast<uint16_t>(ring);
          p.azimuth_index = static_cast<uint16_t>(step);
          ++written;
        }
      }
      if (++ring == c.channels) {
        ring = 0;
        ++step;
      }
    }
  }
  return written;
}

}  // namespace

double lidar_reflectivity(SemanticClass c) {
  switch (c) {
    case SemanticClass::kRoad:
    case SemanticClass::kParking:
    case SemanticClass::kBikeLane:
      return 0.18;  // asphalt
    case SemanticClass::kLaneMarking:
      return 0.65;  // retro-reflective paint
    case SemanticClass::kSidewalk:
      return 0.3;
    case SemanticClass::kRoadside:
      return 0.25;
    case SemanticClass::kBuilding:
      return 0.4;
    case SemanticClass::kPedestrian:
    case SemanticClass::kAnimal:
      return 0.35;
    case SemanticClass::kCar:
    case SemanticClass::kTruck:
    case SemanticClass::kBus:
    case SemanticClass::kTrain:
      return 0.5;
    default:
      return 0.3;
  }
}

LidarSimulator::LidarSimulator(const LidarOptions& options) : options_(options) {
  steps_ = options.azimuth_steps();
  const int channels = options.channels;
  directions_.resize(static_cast<size_t>(steps_) * channels * 3);
  for (int a = 0; a < steps_; ++a) {
    const double az = azimuth(a);
    for (int ch = 0; ch < channels; ++ch) {
      const double el = elevation(ch);
      float* d = &directions_[3 * (static_cast<size_t>(a) * channels + ch)];
      d[0] = static_cast<float>(std::cos(el) * std::cos(az));
      d[1] = static_cast<float>(std::cos(el) * std::sin(az));
      d[2] = static_cast<float>(std::sin(el));
    }
  }
}

double LidarSimulator::elevation(int channel) const {
  const double lo = options_.lower_fov_deg;
  const double hi = options_.upper_fov_deg;
  if (options_.channels == 1) {
    return 0.5 * (lo + hi) * kDeg;
  }
  return (lo + (hi - lo) * channel / (options_.channels - 1)) * kDeg;
}

double LidarSimulator::azimuth(int step) const {
  const double h = options_.horizontal_fov_deg;
  return (-0.5 * h + h * (step + 0.5) / steps_) * kDeg;
}

PointCloud LidarSimulator::scan(const Scene& scene, const Rigid& world_from_sensor,
                                double weather_extinction, uint64_t frame_seed,
                                const std::optional<Box3>& carrier) const {
  ScanContext c;
  c.scene = &scene.data();
  c.options = &options_;
  c.directions = directions_.data();
  for (int r = 0; r < 3; ++r) {
    for (int k = 0; k < 3; ++k) {
      c.rotation[r][k] = static_cast<float>(world_from_sensor.rotation.m[r][k]);
    }
  }
  c.origin = scene.data().to_local(world_from_sensor.translation);
  c.weather = weather_extinction;
  c.frame_seed = frame_seed;
  c.channels = options_.channels;
  c.carrier = detail::CarrierExit(carrier, world_from_sensor.translation);
  for (int k = 0; k < kSemanticClassCount; ++k) {
    c.reflectivity[k] = lidar_reflectivity(static_cast<SemanticClass>(k));
  }

  // Every block writes into its own slice of one buffer (at most one point per beam); the
  // slices are then closed up in block order, so the cloud is the same for any thread count.
  const int blocks = (steps_ + kColumnsPerBlock - 1) / kColumnsPerBlock;
  const size_t per_block = static_cast<size_t>(kColumnsPerBlock) * c.channels;
  PointCloud cloud;
  cloud.channels = options_.channels;
  cloud.azimuth_steps = steps_;
  cloud.rays = static_cast<uint64_t>(steps_) * options_.channels;
  cloud.points.resize(cloud.rays);
  std::vector<size_t> counts(blocks);
  tbb::parallel_for(tbb::blocked_range<int>(0, blocks), [&](const tbb::blocked_range<int>& r) {
    for (int b = r.begin(); b != r.end(); ++b) {
      counts[b] = scan_block(c, b * kColumnsPerBlock, std::min(steps_, (b + 1) * kColumnsPerBlock),
                             static_cast<uint64_t>(b), cloud.points.data() + b * per_block);
    }
  });
  size_t total = 0;
  for (int b = 0; b < blocks; ++b) {
    const LidarPoint* from = cloud.points.data() + b * per_block;
    if (from != cloud.points.data() + total) {
      std::memmove(cloud.points.data() + total, from, counts[b] * sizeof(LidarPoint));
    }
    total += counts[b];
  }
  cloud.points.resize(total);
  return cloud;
}

}  // namespace corsa::sensors
