#include "lidar_scan.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>

#include "lidar_random.h"
#include "lidar_weather.h"

namespace corsa::sensors::detail {
namespace {

/// Writes `p` into uninitialised storage through a zeroed image of the struct, so that its
/// padding bytes (after `semantic`) are zero too: equal clouds are equal bytes.
inline void store_point(LidarPoint* slot, const LidarPoint& p) {
  unsigned char image[sizeof(LidarPoint)] = {};
  auto put = [&image](size_t offset, const auto& field) {
    std::memcpy(image + offset, &field, sizeof(field));
  };
  put(offsetof(LidarPoint, x), p.x);
  put(offsetof(LidarPoint, y), p.y);
  put(offsetof(LidarPoint, z), p.z);
  put(offsetof(LidarPoint, intensity), p.intensity);
  put(offsetof(LidarPoint, ring), p.ring);
  put(offsetof(LidarPoint, azimuth_index), p.azimuth_index);
  put(offsetof(LidarPoint, semantic), p.semantic);
  put(offsetof(LidarPoint, instance_id), p.instance_id);
  put(offsetof(LidarPoint, time), p.time);
  std::memcpy(static_cast<void*>(slot), image, sizeof(image));
}

/// Decides whether a beam gives a point and where (the return model of lidar.h).
class ReturnModel {
 public:
  explicit ReturnModel(const LidarScanContext& c)
      : c_(c), o_(*c.options), normal_(Ziggurat::get()) {}

  /// Fills `out` (all but ring, azimuth index and time) for beam `beam`, whose body-frame
  /// direction is (bx, by, bz) and whose hit (if any: `hit`) is in lane `lane`; false when the
  /// beam gives no point.
  bool make(const RTCRayHit16& rh, int lane, bool hit, uint64_t beam, float bx, float by, float bz,
            LidarPoint& out) const {
    // Draws are taken only when a decision needs them, in this order, from the beam's own
    // counter-based stream.
    BeamRandom random(c_.frame_key, beam);
    double r = hit ? static_cast<double>(rh.ray.tfar[lane]) : 0.0;
    double intensity = 0.0;
    SceneData::Label label{SemanticClass::kUnlabeled, 0, -1};
    bool target = hit;
    if (hit) {
      const unsigned inst = rh.hit.instID[0][lane];
      label = c_.scene->label(inst, rh.hit.geomID[lane], rh.hit.primID[lane]);
      if (c_.self_instance != 0 && label.instance_id == c_.self_instance) {
        return false;  // the carrier's own body: masked, as a driver's self-filter does
      }
      Vec3 n{rh.hit.Ng_x[lane], rh.hit.Ng_y[lane], rh.hit.Ng_z[lane]};
      if (inst != 0) {
        n = c_.scene->instances[inst - 1].normal_matrix * n;  // object to world normal
      }
      const Vec3 d{rh.ray.dir_x[lane], rh.ray.dir_y[lane], rh.ray.dir_z[lane]};
      const double cos_inc = std::fabs(dot(n, d)) / std::sqrt(dot(n, n));
      intensity = c_.reflectivity[static_cast<size_t>(label.semantic)] * cos_inc;
      if (c_.weather > 0.0) {
        const double transmission = exp_nonpositive(-2.0 * c_.weather * r);
        target = random.uniform01() < transmission;
        intensity *= transmission;
      }
    }
    if (c_.weather_model != nullptr && weather_return(random, hit, target, intensity, r)) {
      label = {SemanticClass::kUnlabeled, 0, -1};  // the atmosphere answered first
      target = true;
    }
    if (!target) {
      return false;
    }
    intensity *= exp_nonpositive(-o_.atmosphere_attenuation_rate * r);
    if (o_.dropoff_general_rate > 0.0 && random.uniform01() < o_.dropoff_general_rate) {
      return false;
    }
    if (intensity < o_.dropoff_intensity_limit && o_.dropoff_zero_intensity > 0.0 &&
        random.uniform01() < o_.dropoff_zero_intensity) {
      return false;
    }
    const double range = o_.noise_stddev_m > 0.0 ? r + o_.noise_stddev_m * normal_(random) : r;
    out.x = static_cast<float>(bx * range);
    out.y = static_cast<float>(by * range);
    out.z = static_cast<float>(bz * range);
    out.intensity = static_cast<float>(intensity);
    out.semantic = label.semantic;
    out.instance_id = label.instance_id;
    return true;
  }

 private:
  /// The strongest of the target's return (when it got through: `target`, with intensity
  /// rho |cos| T at range r), the fog's echo and the first detectable rain drop or snowflake;
  /// true when an early return wins, with `r` and `intensity` set to it.
  bool weather_return(BeamRandom& random, bool hit, bool target, double& intensity,
                      double& r) const {
    const LidarWeatherModel& w = *c_.weather_model;
    const double limit = hit ? r : static_cast<double>(c_.range);
    // Received powers in LISA's units (rho / r^2); intensities are range-compensated (rho).
    double best = target ? intensity / (r * r) : 0.0;
    WeatherReturn early;
    bool from_fog = false;
    const WeatherReturn fog = w.fog_echo(hit ? r : 1e30);
    if (fog.power > best && fog.power >= w.threshold() && fog.range < limit) {
      early = fog;
      best = fog.power;
      from_fog = true;
    }
    if (w.has_particles()) {
      const WeatherReturn particle = w.particle(random, limit);
      if (particle.power > best && particle.power >= w.threshold()) {
        early = particle;
        best = particle.power;
        from_fog = false;
      }
    }
    if (early.power <= 0.0) {
      return false;
    }
    if (from_fog) {
      // The fog echo's range spreads over the pulse (Hahner et al. add a spread of mean 0.9 m):
      // a half-normal of the same mean.
      early.range += 1.128 * std::fabs(normal_(random));
    }
    r = early.range;
    intensity = early.power * r * r;
    return true;
  }

  const LidarScanContext& c_;
  const LidarOptions& o_;
  const Ziggurat& normal_;
};

/// Sets the rays of packet `p`: directions rotated to the map frame (16 lanes at a time, which
/// the compiler vectorises), the origin and range, and cleared hits. A moving scan takes each
/// lane's pose (and Embree time) from its azimuth step.
void set_packet(const LidarScanContext& c, uint64_t p, RTCRayHit16& rh) {
  const float* bx = c.packet_directions + 3 * kPacketSize * p;
  const float* by = bx + kPacketSize;
  const float* bz = by + kPacketSize;
  if (c.step_poses.empty()) {
    const auto& m = c.rotation;
    const auto ox = static_cast<float>(c.origin.x);
    const auto oy = static_cast<float>(c.origin.y);
    const auto oz = static_cast<float>(c.origin.z);
    for (int k = 0; k < kPacketSize; ++k) {
      rh.ray.org_x[k] = ox;
      rh.ray.org_y[k] = oy;
      rh.ray.org_z[k] = oz;
      rh.ray.dir_x[k] = m[0][0] * bx[k] + m[0][1] * by[k] + m[0][2] * bz[k];
      rh.ray.dir_y[k] = m[1][0] * bx[k] + m[1][1] * by[k] + m[1][2] * bz[k];
      rh.ray.dir_z[k] = m[2][0] * bx[k] + m[2][1] * by[k] + m[2][2] * bz[k];
      rh.ray.time[k] = 0.0f;
    }
  } else {
    const uint64_t first = p * kPacketSize;
    for (int k = 0; k < kPacketSize; ++k) {
      const uint64_t beam = std::min(first + static_cast<uint64_t>(k), c.rays - 1);
      const float* pose = c.step_poses.data() + LidarScanContext::kPoseFloats *
                                                    (beam / static_cast<uint64_t>(c.channels));
      rh.ray.org_x[k] = pose[9];
      rh.ray.org_y[k] = pose[10];
      rh.ray.org_z[k] = pose[11];
      rh.ray.dir_x[k] = pose[0] * bx[k] + pose[1] * by[k] + pose[2] * bz[k];
      rh.ray.dir_y[k] = pose[3] * bx[k] + pose[4] * by[k] + pose[5] * bz[k];
      rh.ray.dir_z[k] = pose[6] * bx[k] + pose[7] * by[k] + pose[8] * bz[k];
      rh.ray.time[k] = pose[12];
    }
  }
  for (int k = 0; k < kPacketSize; ++k) {
    rh.ray.tnear[k] = 0.0f;
    rh.ray.tfar[k] = c.range;
    rh.ray.mask[k] = 0xFFFFFFFFu;
    rh.ray.flags[k] = 0;
    rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
  }
  if (c.carrier.active()) {
    // The carrier moves with the sensor: the beam leaves its box where it does at the capture.
    const auto& m = c.rotation;
    for (int k = 0; k < kPacketSize; ++k) {
      rh.ray.tnear[k] = c.carrier.exit({m[0][0] * bx[k] + m[0][1] * by[k] + m[0][2] * bz[k],
                                        m[1][0] * bx[k] + m[1][1] * by[k] + m[1][2] * bz[k],
                                        m[2][0] * bx[k] + m[2][1] * by[k] + m[2][2] * bz[k]});
    }
  }
}

/// The point in the sensor frame at the capture time (deskew) from the one at firing time.
void deskew(const float* t, LidarPoint& p) {
  const float x = p.x, y = p.y, z = p.z;
  p.x = t[0] * x + t[1] * y + t[2] * z + t[9];
  p.y = t[3] * x + t[4] * y + t[5] * z + t[10];
  p.z = t[6] * x + t[7] * y + t[8] * z + t[11];
}

}  // namespace

size_t scan_packets(const LidarScanContext& c, uint64_t first, uint64_t last, LidarPoint* out) {
  const ReturnModel model(c);
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  alignas(64) RTCRayHit16 rh;
  // Lanes past the last beam of the revolution stay off (only the last packet has any).
  const uint64_t packets = (c.rays + kPacketSize - 1) / kPacketSize;
  const auto last_lanes = static_cast<int>(c.rays - (packets - 1) * kPacketSize);
  alignas(64) int full[kPacketSize];
  alignas(64) int partial[kPacketSize];
  for (int k = 0; k < kPacketSize; ++k) {
    full[k] = -1;
    partial[k] = k < last_lanes ? -1 : 0;
  }
  // Beams that hit nothing can still meet the weather.
  const bool misses_count = c.weather_model != nullptr;
  uint64_t beam = first * kPacketSize;
  auto ring = static_cast<int>(beam % static_cast<uint64_t>(c.channels));
  auto step = static_cast<int>(beam / static_cast<uint64_t>(c.channels));
  size_t written = 0;
  for (uint64_t p = first; p < last; ++p) {
    set_packet(c, p, rh);
    const bool is_last = p + 1 == packets;
    rtcIntersect16(is_last ? partial : full, c.top, &context, &rh);
    const float* bx = c.packet_directions + 3 * kPacketSize * p;
    const int lanes = is_last ? last_lanes : kPacketSize;
    for (int k = 0; k < lanes; ++k, ++beam) {
      const bool hit = rh.hit.geomID[k] != RTC_INVALID_GEOMETRY_ID;
      if (hit || misses_count) {
        LidarPoint point;
        if (model.make(rh, k, hit, beam, bx[k], bx[kPacketSize + k], bx[2 * kPacketSize + k],
                       point)) {
          point.ring = static_cast<uint16_t>(ring);
          point.azimuth_index = static_cast<uint16_t>(step);
          point.time = c.step_times[static_cast<size_t>(step)];
          if (!c.step_deskew.empty()) {
            deskew(c.step_deskew.data() + 12 * static_cast<size_t>(step), point);
          }
          store_point(out + written, point);
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

}  // namespace corsa::sensors::detail
