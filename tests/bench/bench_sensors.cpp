// Sensor speed, on a street scene: the bundled 26-building district, a 400 m road
// with sidewalks and marks, and 30 cars and 10 pedestrians as instances.
//   1. raw Embree: the 64-channel LiDAR pattern traced with rtcIntersect16 only, one thread: the
//      same beams in the same order and the same 16-beam packets (one azimuth step's 64 beams
//      are four packets), same origin, range and scene; it includes only filling each packet from
//      map-frame directions precomputed outside the timing (origin, direction, tnear, tfar,
//      mask, flags, cleared geomID and instID as Embree requires with instancing), the
//      rtcIntersect16 call and counting the hits;
//   2. the whole LiDAR path (LidarSimulator::scan: per-revolution setup, rays rotated from the
//      sensor frame, carrier skip, intensity from the hit normal, weather, dropoff and range
//      noise draws, class and instance per point, the returned PointCloud), one thread, as a
//      share of (1); both CPU time of the process, alternated, median of RUNS;
//   3. real-time factor of a 64-channel, 1.3 M points/s, 10 Hz LiDAR on one core;
//   4. a 1280x720 RGB + depth + semantic frame (one shared pass, shadows, motion blur, noise,
//      labels) through SensorSystem, on 2 threads.
// A small timing program (median of several runs; the machine is shared and noisy).
// Usage: corsa_bench_sensors [RUNS] [lidar|camera|both] [fast|default|high] [RGB_PNG]
// (default: both, at the camera quality `default`); RGB_PNG: where to write the camera frame, to
// look at it and to compare it with another build's.

#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <functional>
#include <string>
#include <vector>

#include "corsa/sensors/lidar.h"
#include "corsa/sensors/model_io.h"
#include "corsa/sensors/sensor_system.h"
#include "corsa/sensors/writers.h"
#include "scene_data.h"  // the raw Embree scene, for the baseline
#include "street_mesh.h"

using namespace corsa::sensors;
using corsa::engine::EntityCategory;
using corsa::engine::EntitySnapshot;

namespace {

double now(clockid_t clock) {
  timespec t{};
  clock_gettime(clock, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

struct Timing {
  double wall = 0.0;  ///< median seconds of wall time
  double cpu = 0.0;   ///< median seconds of CPU time of the process (all threads)
};

/// Runs the jobs alternately (so that load from other processes hits them alike), `runs` times
/// each after one warm-up, and returns their median wall and CPU times.
std::vector<Timing> measure(int runs, const std::vector<std::function<void()>>& jobs) {
  for (const auto& job : jobs) {
    job();
  }
  std::vector<std::vector<double>> wall(jobs.size()), cpu(jobs.size());
  for (int i = 0; i < runs; ++i) {
    for (size_t j = 0; j < jobs.size(); ++j) {
      const double w0 = now(CLOCK_MONOTONIC), c0 = now(CLOCK_PROCESS_CPUTIME_ID);
      jobs[j]();
      wall[j].push_back(now(CLOCK_MONOTONIC) - w0);
      cpu[j].push_back(now(CLOCK_PROCESS_CPUTIME_ID) - c0);
    }
  }
  std::vector<Timing> out;
  for (size_t j = 0; j < jobs.size(); ++j) {
    std::sort(wall[j].begin(), wall[j].end());
    std::sort(cpu[j].begin(), cpu[j].end());
    out.push_back({wall[j][wall[j].size() / 2], cpu[j][cpu[j].size() / 2]});
  }
  return out;
}

corsa::engine::WorldSnapshot traffic() {
  corsa::engine::WorldSnapshot w;
  w.environment.time_of_day = 15.0 * 3600.0;
  w.environment.utc_offset_hours = 9.0;
  uint32_t id = 1;
  auto add = [&](const char* name, EntityCategory c, double x, double y, double h, double v,
                 double l, double wd, double ht) {
    EntitySnapshot e;
    e.instance_id = id++;
    e.name = name + std::to_string(e.instance_id);
    e.category = c;
    e.pose = {x, y, c == EntityCategory::kPedestrian ? 0.15 : 0.0, h, 0.0, 0.0};
    e.box = {c == EntityCategory::kPedestrian ? 0.0 : 1.4, 0.0, ht / 2.0, l, wd, ht};
    e.vx = v * std::cos(h);
    e.vy = v * std::sin(h);
    w.entities.push_back(e);
  };
  add("Ego", EntityCategory::kCar, 40.0, -3.0, 0.0, 12.0, 4.6, 1.9, 1.5);
  for (int i = 0; i < 30; ++i) {
    const bool east = i % 2 == 0;
    add("car", i % 7 == 0 ? EntityCategory::kTruck : EntityCategory::kCar, 10.0 + 8.5 * i,
        east ? -6.5 + 3.5 * (i % 3 == 0) : 3.5 + 3.0 * (i % 3 == 1), east ? 0.0 : M_PI, 8.0 + i % 5,
        i % 7 == 0 ? 9.0 : 4.5, i % 7 == 0 ? 2.5 : 1.85, i % 7 == 0 ? 3.2 : 1.5);
  }
  for (int i = 0; i < 10; ++i) {
    add("walker", EntityCategory::kPedestrian, 20.0 + 17.0 * i, i % 2 ? 11.5 : -12.0,
        i % 2 ? 0.0 : M_PI, 1.3, 0.5, 0.6, 1.8);
  }
  return w;
}

}  // namespace

int main(int argc, char** argv) {
  const int runs = argc > 1 ? std::max(3, std::atoi(argv[1])) : 9;
  const std::string only = argc > 2 ? argv[2] : "";
  const std::string quality = argc > 3 ? argv[3] : "default";
  if (quality != "fast" && quality != "default" && quality != "high") {
    std::fprintf(stderr, "corsa_bench_sensors: quality is fast, default or high, not '%s'\n",
                 quality.c_str());
    return 2;
  }
  Scene scene(SceneOptions{{100.0, 0.0, 0.0}});
  scene.add_road_mesh(corsa::bench::street_mesh(10.0, corsa::xodr::LaneType::kShoulder));
  for (auto& m :
       load_model(std::string(CORSA_SOURCE_DIR) + "/scenarios/models/street_district.glb", {})) {
    scene.add_static_mesh(std::move(m));
  }
  scene.commit();
  const corsa::engine::WorldSnapshot world = traffic();
  scene.set_entities(world.entities);
  const EntitySnapshot& ego = world.entities.front();
  const Rigid lidar_pose =
      rigid_from_pose(ego.pose.x, ego.pose.y, ego.pose.z, ego.pose.h, 0.0, 0.0) *
      rigid_from_pose(0.8, 0.0, 1.85, 0.0, 0.0, 0.0);

  LidarOptions o;
  o.channels = 64;
  o.points_per_second = 1.3e6;
  o.rotation_frequency_hz = 10.0;
  o.upper_fov_deg = 2.0;
  o.lower_fov_deg = -24.8;
  o.range_m = 120.0;
  o.noise_stddev_m = 0.02;
  o.dropoff_general_rate = 0.05;
  const LidarSimulator lidar(o);
  const size_t rays = lidar.directions().size() / 3;

  // 1. Raw Embree on the same scene and ray pattern.
  const auto& d = scene.data();
  std::vector<float> world_dirs(lidar.directions().size());
  for (size_t i = 0; i < rays; ++i) {
    const float* b = &lidar.directions()[3 * i];
    const Vec3 w = lidar_pose.rotation * Vec3{b[0], b[1], b[2]};
    world_dirs[3 * i] = static_cast<float>(w.x);
    world_dirs[3 * i + 1] = static_cast<float>(w.y);
    world_dirs[3 * i + 2] = static_cast<float>(w.z);
  }
  const Vec3 origin = d.to_local(lidar_pose.translation);
  size_t raw_hits = 0;
  auto raw = [&] {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    alignas(64) RTCRayHit16 rh;
    alignas(64) int valid[16];
    size_t hits = 0;
    for (size_t i = 0; i < rays; i += 16) {
      for (int k = 0; k < 16; ++k) {
        const size_t r = std::min(i + k, rays - 1);
        valid[k] = i + k < rays ? -1 : 0;
        rh.ray.org_x[k] = static_cast<float>(origin.x);
        rh.ray.org_y[k] = static_cast<float>(origin.y);
        rh.ray.org_z[k] = static_cast<float>(origin.z);
        rh.ray.dir_x[k] = world_dirs[3 * r];
        rh.ray.dir_y[k] = world_dirs[3 * r + 1];
        rh.ray.dir_z[k] = world_dirs[3 * r + 2];
        rh.ray.tnear[k] = 0.0f;
        rh.ray.tfar[k] = 120.0f;
        rh.ray.mask[k] = 0xFFFFFFFFu;
        rh.ray.flags[k] = 0;
        rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
      }
      rtcIntersect16(valid, d.top, &context, &rh);
      for (int k = 0; k < 16; ++k) {
        hits += valid[k] && rh.hit.geomID[k] != RTC_INVALID_GEOMETRY_ID;
      }
    }
    raw_hits = hits;
  };
  size_t points = 0, fog_points = 0;
  const Box3 carrier = entity_box(ego);
  uint64_t seed = 1;
  auto whole = [&] {
    // Clear air; fog is measured separately below.
    points = lidar.scan(scene, lidar_pose, 0.0, seed++, carrier).points.size();
  };
  if (only != "camera") {
    // One thread: CPU time is the honest figure on a loaded machine (wall time shown too).
    tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    auto fog = [&] {
      fog_points =
          lidar.scan(scene, lidar_pose, fog_extinction(200.0), seed++, carrier).points.size();
    };
    const auto t = measure(runs, {raw, whole, fog});
    const double raw_rate = rays / t[0].cpu;
    const double whole_rate = rays / t[1].cpu;
    std::printf("scene: %zu static triangles in %zu meshes, %zu entities\n",
                scene.static_triangle_count(), scene.static_mesh_count(), world.entities.size());
    std::printf(
        "LiDAR 64 ch x %d azimuths = %zu rays per revolution (%zu hits; %zu points in clear "
        "air, %zu in 200 m fog)\n",
        lidar.azimuth_steps(), rays, raw_hits, points, fog_points);
    std::printf(
        "raw rtcIntersect16, 1 thread:   %6.2f Mrays/s (%.2f ms CPU, %.2f ms wall per rev)\n",
        raw_rate / 1e6, t[0].cpu * 1e3, t[0].wall * 1e3);
    std::printf(
        "whole LiDAR path, 1 thread:     %6.2f Mrays/s (%.2f ms CPU, %.2f ms wall per rev)\n",
        whole_rate / 1e6, t[1].cpu * 1e3, t[1].wall * 1e3);
    std::printf("whole path / raw:               %6.1f %%  (target >= 70 %%)\n",
                100.0 * whole_rate / raw_rate);
    std::printf("whole path in 200 m fog:        %6.1f %% of raw\n", 100.0 * t[0].cpu / t[2].cpu);
    std::printf(
        "64 ch 1.3 Mpts/s LiDAR, 1 core: %6.1f x real time (target > 1; %.1f x by wall "
        "time)\n",
        (1.0 / o.rotation_frequency_hz) / t[1].cpu, (1.0 / o.rotation_frequency_hz) / t[1].wall);
  }
  if (only == "lidar") {
    return 0;
  }
  // 4. Camera frame through the sensor system, 2 threads.
  const std::string rig_text = R"(<SensorRig version="1" quality=")" + quality + R"(">
    <RgbCamera name="rgb" entity="Ego1" width="1280" height="720" fov="90" k1="-0.05" k2="0.01"
               shutterSpeed="0.01"><Mount x="1.6" z="1.45"/></RgbCamera>
    <DepthCamera name="depth" entity="Ego1" width="1280" height="720" fov="90" k1="-0.05"
                 k2="0.01"><Mount x="1.6" z="1.45"/></DepthCamera>
    <SemanticCamera name="semantic" entity="Ego1" width="1280" height="720" fov="90" k1="-0.05"
                    k2="0.01"><Mount x="1.6" z="1.45"/></SemanticCamera>
  </SensorRig>)";
  SensorSystem system(parse_rig(rig_text, "bench"), scene, {});
  size_t labelled = 0;
  CameraImages image;
  tbb::global_control two(tbb::global_control::max_allowed_parallelism, 2);
  const auto t = measure(runs, {[&] {
                           auto frames = system.capture(world, {});
                           labelled = frames.front().labels.size();
                           image = std::move(frames.front().camera);
                         }});
  if (argc > 4) {
    write_png_rgb8(argv[4], image.width, image.height, image.rgb);
  }
  std::printf(
      "1280x720 RGB+depth+semantic frame at quality %s, 2 threads: %.1f ms wall, %.1f ms CPU "
      "(%.1f ms per core; target %s; %zu labelled objects)\n",
      quality.c_str(), t[0].wall * 1e3, t[0].cpu * 1e3, t[0].cpu * 1e3 / 2.0,
      quality == "fast"      ? "<= 120 ms wall"
      : quality == "default" ? "<= 500 ms wall"
                             : "none",
      labelled);
  return 0;
}
