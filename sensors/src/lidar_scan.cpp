#include "lidar_scan.h"

#include <cmath>
#include <cstddef>
#include <cstring>

#include "lidar_random.h"

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
  std::memcpy(static_cast<void*>(slot), image, sizeof(image));
}

/// Decides whether a hit becomes a point and where (the return model of lidar.h).
class ReturnModel {
 public:
  explicit ReturnModel(const LidarScanContext& c)
      : c_(c), o_(*c.options), normal_(Ziggurat::get()) {}

  /// Fills `out` (all but ring and azimuth index) for the hit in `lane` of beam `beam`, whose
  /// body-frame direction is (bx, by, bz); false when the return is lost.
  bool make(const RTCRayHit16& rh, int lane, uint64_t beam, float bx, float by, float bz,
            LidarPoint& out) const {
    const double r = rh.ray.tfar[lane];
    const unsigned inst = rh.hit.instID[0][lane];
    const auto label = c_.scene->label(inst, rh.hit.geomID[lane], rh.hit.primID[lane]);
    Vec3 n{rh.hit.Ng_x[lane], rh.hit.Ng_y[lane], rh.hit.Ng_z[lane]};
    if (inst != 0) {
      n = c_.scene->instances[inst - 1].normal_matrix * n;  // object to world normal
    }
    const Vec3 d{rh.ray.dir_x[lane], rh.ray.dir_y[lane], rh.ray.dir_z[lane]};
    const double cos_inc = std::fabs(dot(n, d)) / std::sqrt(dot(n, n));
    double intensity = c_.reflectivity[static_cast<size_t>(label.semantic)] * cos_inc *
                       exp_nonpositive(-o_.atmosphere_attenuation_rate * r);
    // Draws are taken only when a decision needs them, in this order, from the beam's own
    // counter-based stream.
    BeamRandom random(c_.frame_key, beam);
    if (c_.weather > 0.0) {
      const double transmission = exp_nonpositive(-2.0 * c_.weather * r);
      if (random.uniform01() >= transmission) {
        return false;
      }
      intensity *= transmission;
    }
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
  const LidarScanContext& c_;
  const LidarOptions& o_;
  const Ziggurat& normal_;
};

/// Sets the rays of packet `p`: directions rotated to the map frame (16 lanes at a time, which
/// the compiler vectorises), the common origin and range, and cleared hits.
void set_packet(const LidarScanContext& c, uint64_t p, RTCRayHit16& rh) {
  const float* bx = c.packet_directions + 3 * kPacketSize * p;
  const float* by = bx + kPacketSize;
  const float* bz = by + kPacketSize;
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
    rh.ray.tnear[k] = 0.0f;
    rh.ray.tfar[k] = c.range;
    rh.ray.mask[k] = 0xFFFFFFFFu;
    rh.ray.flags[k] = 0;
    rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
  }
  if (c.carrier.active()) {
    for (int k = 0; k < kPacketSize; ++k) {
      rh.ray.tnear[k] = c.carrier.exit({rh.ray.dir_x[k], rh.ray.dir_y[k], rh.ray.dir_z[k]});
    }
  }
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
  uint64_t beam = first * kPacketSize;
  auto ring = static_cast<int>(beam % static_cast<uint64_t>(c.channels));
  auto step = static_cast<int>(beam / static_cast<uint64_t>(c.channels));
  size_t written = 0;
  for (uint64_t p = first; p < last; ++p) {
    set_packet(c, p, rh);
    const bool is_last = p + 1 == packets;
    rtcIntersect16(is_last ? partial : full, c.scene->top, &context, &rh);
    const float* bx = c.packet_directions + 3 * kPacketSize * p;
    const int lanes = is_last ? last_lanes : kPacketSize;
    for (int k = 0; k < lanes; ++k, ++beam) {
      if (rh.hit.geomID[k] != RTC_INVALID_GEOMETRY_ID) {
        LidarPoint point;
        if (model.make(rh, k, beam, bx[k], bx[kPacketSize + k], bx[2 * kPacketSize + k], point)) {
          point.ring = static_cast<uint16_t>(ring);
          point.azimuth_index = static_cast<uint16_t>(step);
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
