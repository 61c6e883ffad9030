#include "corsa/sensors/lidar.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
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
  Mat3 rotation;            // body to map
  Vec3 origin;              // sensor position, tracer-local
  double weather;           // 1/m
  uint64_t frame_seed;
  int channels;
  detail::CarrierExit carrier;
};

/// Decides whether a hit becomes a point and where; appends it.
class ReturnModel {
 public:
  ReturnModel(const ScanContext& c, uint64_t seed) : c_(c), rng_(seed) {}

  void add(const RTCRayHit16& rh, int lane, const float* dir_body, int ring, int step,
           std::vector<LidarPoint>& out) {
    if (rh.hit.geomID[lane] == RTC_INVALID_GEOMETRY_ID) {
      return;
    }
    const double r = rh.ray.tfar[lane];
    const LidarOptions& o = *c_.options;
    const auto label =
        c_.scene->label(rh.hit.instID[0][lane], rh.hit.geomID[lane], rh.hit.primID[lane]);
    const Vec3 n = c_.scene->world_normal(
        rh.hit.instID[0][lane], {rh.hit.Ng_x[lane], rh.hit.Ng_y[lane], rh.hit.Ng_z[lane]});
    const Vec3 d{rh.ray.dir_x[lane], rh.ray.dir_y[lane], rh.ray.dir_z[lane]};
    const double cos_inc = std::fabs(dot(n, d));
    double intensity =
        lidar_reflectivity(label.semantic) * cos_inc * std::exp(-o.atmosphere_attenuation_rate * r);
    if (c_.weather > 0.0) {
      const double transmission = std::exp(-2.0 * c_.weather * r);
      if (rng_.uniform01() >= transmission) {
        return;
      }
      intensity *= transmission;
    }
    if (o.dropoff_general_rate > 0.0 && rng_.uniform01() < o.dropoff_general_rate) {
      return;
    }
    if (intensity < o.dropoff_intensity_limit && o.dropoff_zero_intensity > 0.0 &&
        rng_.uniform01() < o.dropoff_zero_intensity) {
      return;
    }
    const double range = o.noise_stddev_m > 0.0 ? r + o.noise_stddev_m * normal_.next(rng_) : r;
    LidarPoint p;
    p.x = static_cast<float>(dir_body[0] * range);
    p.y = static_cast<float>(dir_body[1] * range);
    p.z = static_cast<float>(dir_body[2] * range);
    p.intensity = static_cast<float>(intensity);
    p.ring = static_cast<uint16_t>(ring);
    p.azimuth_index = static_cast<uint16_t>(step);
    p.semantic = label.semantic;
    p.instance_id = label.instance_id;
    out.push_back(p);
  }

 private:
  const ScanContext& c_;
  RandomStream rng_;
  detail::NormalPairs normal_;
};

/// Fires the beams of azimuth columns [first, last) in packets of 16.
void scan_block(const ScanContext& c, int first, int last, uint64_t block,
                std::vector<LidarPoint>& out) {
  ReturnModel model(c, detail::block_seed(c.frame_seed, block));
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  const size_t begin = static_cast<size_t>(first) * c.channels;
  const size_t end = static_cast<size_t>(last) * c.channels;
  alignas(64) RTCRayHit16 rh;
  alignas(64) int valid[16];
  const float far = static_cast<float>(c.options->range_m);
  for (size_t i = begin; i < end; i += 16) {
    const int n = static_cast<int>(std::min<size_t>(16, end - i));
    for (int k = 0; k < 16; ++k) {
      valid[k] = k < n ? -1 : 0;
      const float* db = c.directions + 3 * (i + (k < n ? k : 0));
      const Vec3 d = c.rotation * Vec3{db[0], db[1], db[2]};
      rh.ray.org_x[k] = static_cast<float>(c.origin.x);
      rh.ray.org_y[k] = static_cast<float>(c.origin.y);
      rh.ray.org_z[k] = static_cast<float>(c.origin.z);
      rh.ray.dir_x[k] = static_cast<float>(d.x);
      rh.ray.dir_y[k] = static_cast<float>(d.y);
      rh.ray.dir_z[k] = static_cast<float>(d.z);
      rh.ray.tnear[k] = c.carrier.exit(d);
      rh.ray.tfar[k] = far;
      rh.ray.mask[k] = 0xFFFFFFFFu;
      rh.ray.flags[k] = 0;
      rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
      rh.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
    }
    rtcIntersect16(valid, c.scene->top, &context, &rh);
    for (int k = 0; k < n; ++k) {
      const size_t ray = i + k;
      model.add(rh, k, c.directions + 3 * ray, static_cast<int>(ray % c.channels),
                static_cast<int>(ray / c.channels), out);
    }
  }
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
  c.rotation = world_from_sensor.rotation;
  c.origin = scene.data().to_local(world_from_sensor.translation);
  c.weather = weather_extinction;
  c.frame_seed = frame_seed;
  c.channels = options_.channels;
  c.carrier = detail::CarrierExit(carrier, world_from_sensor.translation);

  const int blocks = (steps_ + kColumnsPerBlock - 1) / kColumnsPerBlock;
  std::vector<std::vector<LidarPoint>> parts(blocks);
  tbb::parallel_for(tbb::blocked_range<int>(0, blocks), [&](const tbb::blocked_range<int>& r) {
    for (int b = r.begin(); b != r.end(); ++b) {
      parts[b].reserve(static_cast<size_t>(kColumnsPerBlock) * c.channels);
      scan_block(c, b * kColumnsPerBlock, std::min(steps_, (b + 1) * kColumnsPerBlock),
                 static_cast<uint64_t>(b), parts[b]);
    }
  });
  PointCloud cloud;
  cloud.channels = options_.channels;
  cloud.azimuth_steps = steps_;
  cloud.rays = static_cast<uint64_t>(steps_) * options_.channels;
  size_t total = 0;
  for (const auto& p : parts) {
    total += p.size();
  }
  cloud.points.reserve(total);
  for (const auto& p : parts) {
    cloud.points.insert(cloud.points.end(), p.begin(), p.end());
  }
  return cloud;
}

}  // namespace corsa::sensors
