#include "corsa/sensors/lidar.h"

#include <tbb/parallel_pipeline.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>

#include "lidar_random.h"
#include "lidar_scan.h"
#include "lidar_weather.h"
#include "scalar_math.h"

namespace corsa::sensors {

using detail::kDeg;
namespace {

/// Packets per work block (2,048 beams): big enough to amortise the task, small enough to
/// spread a revolution over the threads. Draws are per beam, so the size never changes a point.
constexpr uint64_t kPacketsPerBlock = 128;
constexpr uint64_t kBlockBeams = kPacketsPerBlock * detail::kPacketSize;

/// Uninitialised room for points: every point is written before it is read, so it is not
/// zero-filled first.
class PointScratch {
 public:
  explicit PointScratch(size_t n) : n_(n), data_(std::allocator<LidarPoint>().allocate(n)) {}
  ~PointScratch() { std::allocator<LidarPoint>().deallocate(data_, n_); }
  PointScratch(const PointScratch&) = delete;
  PointScratch& operator=(const PointScratch&) = delete;
  LidarPoint* data() const { return data_; }

 private:
  size_t n_;
  LidarPoint* data_;
};

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
    case SemanticClass::kWall:
      return 0.3;
    case SemanticClass::kTerrain:
    case SemanticClass::kGround:
      return 0.25;
    case SemanticClass::kVegetation:
      return 0.5;  // leaves reflect strongly in the near infrared
    case SemanticClass::kTrafficSign:
      return 0.9;  // retro-reflective sheeting
    case SemanticClass::kPole:
    case SemanticClass::kGuardRail:
      return 0.45;
    case SemanticClass::kBuilding:
      return 0.4;
    case SemanticClass::kPerson:
    case SemanticClass::kRider:
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
  const size_t rays = static_cast<size_t>(steps_) * channels;
  // Trigonometry once per channel and per step, not per beam.
  std::vector<double> cos_el(channels), sin_el(channels);
  for (int ch = 0; ch < channels; ++ch) {
    cos_el[ch] = std::cos(elevation(ch));
    sin_el[ch] = std::sin(elevation(ch));
  }
  directions_.resize(rays * 3);
  for (int a = 0; a < steps_; ++a) {
    const double az = azimuth(a);
    const double cos_az = std::cos(az);
    const double sin_az = std::sin(az);
    for (int ch = 0; ch < channels; ++ch) {
      float* d = &directions_[3 * (static_cast<size_t>(a) * channels + ch)];
      d[0] = static_cast<float>(cos_el[ch] * cos_az);
      d[1] = static_cast<float>(cos_el[ch] * sin_az);
      d[2] = static_cast<float>(sin_el[ch]);
    }
  }
  // The same directions laid out per packet of 16 (x, y, z planes), as the tracer reads them;
  // lanes past the last beam repeat it.
  constexpr size_t kLanes = detail::kPacketSize;
  const size_t packets = (rays + kLanes - 1) / kLanes;
  packet_directions_.resize(packets * 3 * kLanes);
  for (size_t p = 0; p < packets; ++p) {
    for (size_t k = 0; k < kLanes; ++k) {
      const size_t beam = std::min(p * kLanes + k, rays - 1);
      for (size_t axis = 0; axis < 3; ++axis) {
        packet_directions_[(3 * p + axis) * kLanes + k] = directions_[3 * beam + axis];
      }
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

double LidarSimulator::step_time(int step) const {
  // Counter-clockwise from behind; the forward beam (azimuth 0) fires at the capture time.
  return azimuth(step) / (2.0 * std::numbers::pi * options_.rotation_frequency_hz);
}

std::shared_ptr<const detail::LidarWeatherModel> LidarSimulator::weather_model(
    const LidarWeather& w) const {
  if (!w.any()) {
    return nullptr;
  }
  const std::lock_guard lock(weather_mutex_);
  const auto same = [&w](const LidarWeather& v) {
    return v.fog_extinction == w.fog_extinction && v.rain_rate == w.rain_rate &&
           v.snow_rate == w.snow_rate;
  };
  if (!weather_cache_ || !same(weather_cache_->weather())) {
    weather_cache_ = std::make_shared<const detail::LidarWeatherModel>(w, options_.range_m);
  }
  return weather_cache_;
}

PointCloud LidarSimulator::scan(const Scene& scene, const Rigid& world_from_sensor,
                                double fog_extinction, uint64_t frame_seed,
                                const std::optional<Box3>& carrier) const {
  LidarScanInput input;
  input.world_from_sensor = world_from_sensor;
  input.weather.fog_extinction = fog_extinction;
  input.frame_seed = frame_seed;
  input.carrier = carrier;
  return scan(scene, input);
}

namespace {

/// Sensor pose at time t (s from the capture) under the carrier's motion: turned by yaw_rate t
/// about the up axis through the pivot and moved by velocity t.
Rigid pose_at(const Rigid& at_capture, const SensorMotion& m, double t) {
  const double c = std::cos(m.yaw_rate * t);
  const double s = std::sin(m.yaw_rate * t);
  Mat3 turn;
  turn.m[0][0] = c;
  turn.m[0][1] = -s;
  turn.m[1][0] = s;
  turn.m[1][1] = c;
  turn.m[2][2] = 1.0;
  Rigid out;
  out.rotation = turn * at_capture.rotation;
  out.translation = m.pivot + m.velocity * t + turn * (at_capture.translation - m.pivot);
  return out;
}

}  // namespace

PointCloud LidarSimulator::scan(const Scene& scene, const LidarScanInput& input) const {
  const Rigid& world_from_sensor = input.world_from_sensor;
  detail::LidarScanContext c;
  c.scene = &scene.data();
  const bool moving_world = input.scene_motion_span > 0.0 && c.scene->moving_top != nullptr;
  c.top = moving_world ? c.scene->moving_top : c.scene->top;
  c.options = &options_;
  c.packet_directions = packet_directions_.data();
  c.rays = static_cast<uint64_t>(steps_) * static_cast<uint64_t>(options_.channels);
  c.channels = options_.channels;
  for (int r = 0; r < 3; ++r) {
    for (int k = 0; k < 3; ++k) {
      c.rotation[r][k] = static_cast<float>(world_from_sensor.rotation.m[r][k]);
    }
  }
  c.origin = scene.data().to_local(world_from_sensor.translation);
  c.range = static_cast<float>(options_.range_m);
  const std::shared_ptr<const detail::LidarWeatherModel> weather = weather_model(input.weather);
  c.weather_model = weather.get();
  c.weather = weather ? weather->extinction() : 0.0;
  c.self_instance = options_.keep_self_returns ? 0 : input.carrier_instance;
  c.frame_key = detail::BeamRandom::frame_key(input.frame_seed);
  c.carrier = detail::CarrierExit(input.carrier, world_from_sensor.translation);
  for (int k = 0; k < kSemanticClassCount; ++k) {
    c.reflectivity[k] = lidar_reflectivity(static_cast<SemanticClass>(k));
  }
  // The sweep: per azimuth step its time, and when anything moves, the sensor's pose then.
  const SensorMotion& m = input.motion;
  const bool moving_sensor = norm(m.velocity) > 0.0 || m.yaw_rate != 0.0;
  c.step_times.resize(static_cast<size_t>(steps_));
  if (moving_sensor || moving_world) {
    c.step_poses.resize(detail::LidarScanContext::kPoseFloats * static_cast<size_t>(steps_));
  }
  if (moving_sensor && options_.deskew) {
    c.step_deskew.resize(12 * static_cast<size_t>(steps_));
  }
  const Mat3 to_capture = world_from_sensor.rotation.transposed();
  for (int a = 0; a < steps_; ++a) {
    const double t = step_time(a);
    c.step_times[static_cast<size_t>(a)] = static_cast<float>(t);
    if (c.step_poses.empty()) {
      continue;
    }
    const Rigid pose = moving_sensor ? pose_at(world_from_sensor, m, t) : world_from_sensor;
    float* out = c.step_poses.data() + detail::LidarScanContext::kPoseFloats * a;
    for (int r = 0; r < 3; ++r) {
      for (int k = 0; k < 3; ++k) {
        out[3 * r + k] = static_cast<float>(pose.rotation.m[r][k]);
      }
    }
    const Vec3 origin = scene.data().to_local(pose.translation);
    out[9] = static_cast<float>(origin.x);
    out[10] = static_cast<float>(origin.y);
    out[11] = static_cast<float>(origin.z);
    out[12] = moving_world
                  ? static_cast<float>(std::clamp(0.5 + t / input.scene_motion_span, 0.0, 1.0))
                  : 0.0f;
    if (!c.step_deskew.empty()) {
      const Mat3 rotation = to_capture * pose.rotation;
      const Vec3 shift = to_capture * (pose.translation - world_from_sensor.translation);
      float* d = c.step_deskew.data() + 12 * static_cast<size_t>(a);
      for (int r = 0; r < 3; ++r) {
        for (int k = 0; k < 3; ++k) {
          d[3 * r + k] = static_cast<float>(rotation.m[r][k]);
        }
      }
      d[9] = static_cast<float>(shift.x);
      d[10] = static_cast<float>(shift.y);
      d[11] = static_cast<float>(shift.z);
    }
  }

  // Blocks are traced in parallel, each into one of a few small (cache-sized) slots, and
  // appended to the cloud in block order: the cloud is the same for any thread count, and the
  // points cross memory once instead of through a revolution-sized buffer. A block can only
  // enter when the block `tokens` before it has been appended, so it may reuse that one's slot.
  const uint64_t packets = (c.rays + detail::kPacketSize - 1) / detail::kPacketSize;
  const uint64_t blocks = (packets + kPacketsPerBlock - 1) / kPacketsPerBlock;
  const uint64_t tokens = std::min<uint64_t>(
      blocks, 2 * static_cast<uint64_t>(std::max(1, tbb::this_task_arena::max_concurrency())));
  PointScratch slots(tokens * kBlockBeams);
  PointCloud cloud;
  cloud.channels = options_.channels;
  cloud.azimuth_steps = steps_;
  cloud.rays = c.rays;
  cloud.points.reserve(c.rays);  // at most one point per beam: no reallocation
  struct Traced {
    uint64_t block = 0;
    size_t count = 0;
  };
  uint64_t next = 0;
  tbb::parallel_pipeline(
      tokens, tbb::make_filter<void, uint64_t>(tbb::filter_mode::serial_in_order,
                                               [&](tbb::flow_control& control) -> uint64_t {
                                                 if (next == blocks) {
                                                   control.stop();
                                                   return 0;
                                                 }
                                                 return next++;
                                               }) &
                  tbb::make_filter<uint64_t, Traced>(
                      tbb::filter_mode::parallel,
                      [&](uint64_t b) {
                        LidarPoint* slot = slots.data() + (b % tokens) * kBlockBeams;
                        const uint64_t last = std::min(packets, (b + 1) * kPacketsPerBlock);
                        return Traced{b, detail::scan_packets(c, b * kPacketsPerBlock, last, slot)};
                      }) &
                  tbb::make_filter<Traced, void>(tbb::filter_mode::serial_in_order, [&](Traced t) {
                    const LidarPoint* from = slots.data() + (t.block % tokens) * kBlockBeams;
                    cloud.points.insert(cloud.points.end(), from, from + t.count);
                  }));
  return cloud;
}

}  // namespace corsa::sensors
