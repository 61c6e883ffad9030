#include "corsa/sensors/sensor_system.h"

#include <tbb/task_group.h>

#include <algorithm>
#include <numbers>

#include "corsa/core/diagnostic.h"
#include "corsa/core/random.h"
#include "corsa/sensors/writers.h"

namespace corsa::sensors {
namespace {

bool is_camera(SensorKind k) {
  return k == SensorKind::kRgbCamera || k == SensorKind::kDepthCamera ||
         k == SensorKind::kSemanticCamera || k == SensorKind::kInstanceCamera;
}

bool same_optics(const SensorSpec& a, const SensorSpec& b) {
  const auto& i = a.camera;
  const auto& j = b.camera;
  const auto& m = a.mount;
  const auto& n = b.mount;
  return a.entity == b.entity && i.width == j.width && i.height == j.height &&
         i.fov_deg == j.fov_deg && i.k1 == j.k1 && i.k2 == j.k2 && i.p1 == j.p1 && i.p2 == j.p2 &&
         m.x == n.x && m.y == n.y && m.z == n.z && m.roll_deg == n.roll_deg &&
         m.pitch_deg == n.pitch_deg && m.yaw_deg == n.yaw_deg;
}

/// Camera sensors rendered by one pass (at most one RGB camera: it has its own exposure).
struct CameraGroup {
  std::vector<const SensorSpec*> members;
  const SensorSpec* rgb = nullptr;
  CameraOutputs outputs;
};

/// Renders one camera group and gives each member its own image and the group's labels.
void render_camera_group(const Scene& scene, const CameraRenderer& renderer,
                         const std::vector<const SensorSpec*>& members,
                         const engine::EntitySnapshot& carrier, const RenderSettings& settings,
                         const std::vector<SensorFrame*>& outputs, bool rgb_instances) {
  CameraMotion motion;
  motion.world_from_body = outputs.front()->world_from_sensor;
  motion.velocity = {carrier.vx, carrier.vy, carrier.vz};
  motion.yaw_rate = carrier.yaw_rate;
  motion.pivot = {carrier.pose.x, carrier.pose.y, carrier.pose.z};
  CameraImages images = renderer.render(scene, motion, settings);
  const auto labels = camera_labels(scene, renderer, motion.world_from_body, images.instance,
                                    carrier.instance_id, settings.lighting);
  const auto static_labels =
      static_object_labels(scene, images.instance, images.width, images.semantic);
  // Copied before an instance camera of the group takes the buffer.
  const std::vector<uint32_t> rgb_ids = rgb_instances ? images.instance : std::vector<uint32_t>{};
  for (size_t i = 0; i < members.size(); ++i) {
    const SensorSpec& m = *members[i];
    SensorFrame& f = *outputs[i];
    f.labels = labels;
    f.static_labels = static_labels;
    f.camera.width = images.width;
    f.camera.height = images.height;
    // The last member of a kind takes the image, earlier ones (e.g. two depth cameras sharing the
    // optics) copy it: no copy of a 1280x720 image in the usual rig.
    bool last = true;
    for (size_t j = i + 1; j < members.size(); ++j) {
      last = last && members[j]->kind != m.kind;
    }
    auto take = [last](auto& image) { return last ? std::move(image) : image; };
    if (m.kind == SensorKind::kRgbCamera) {
      f.camera.rgb = take(images.rgb);
      if (rgb_instances) {
        f.camera.instance = rgb_ids;
      }
    } else if (m.kind == SensorKind::kDepthCamera) {
      f.camera.depth = take(images.depth);
      for (float& z : f.camera.depth) {
        z = z <= m.depth.max_range_m ? z : 0.0f;
      }
    } else if (m.kind == SensorKind::kSemanticCamera) {
      f.camera.semantic = take(images.semantic);
    } else {
      f.camera.instance = take(images.instance);
    }
  }
}

/// The rig's sensors named in `names` (all of them when `names` is empty), in rig order.
std::vector<const SensorSpec*> due_sensors(const SensorRig& rig,
                                           std::span<const std::string> names) {
  std::vector<const SensorSpec*> due;
  for (const auto& s : rig.sensors) {
    if (names.empty() || std::find(names.begin(), names.end(), s.name) != names.end()) {
      due.push_back(&s);
    }
  }
  return due;
}

/// The longest LiDAR revolution (s) among `due`; 0 without a LiDAR.
double longest_sweep(const std::vector<const SensorSpec*>& due) {
  double sweep = 0.0;
  for (const SensorSpec* s : due) {
    if (s->kind == SensorKind::kLidar) {
      sweep = std::max(sweep, 1.0 / s->lidar.rotation_frequency_hz);
    }
  }
  return sweep;
}

/// The entity carrying `sensor` (the last of that name); InputError at the sensor's rig line
/// when it is not in the world.
const engine::EntitySnapshot& carrier_of(const SensorRig& rig, const SensorSpec& sensor,
                                         const engine::WorldSnapshot& world) {
  const engine::EntitySnapshot* carrier = nullptr;
  for (const auto& e : world.entities) {
    carrier = e.name == sensor.entity ? &e : carrier;
  }
  if (carrier == nullptr) {
    throw InputError(make_error(rig.file, sensor.line,
                                "sensor '" + sensor.name + "' is attached to entity '" +
                                    sensor.entity + "', which is not in the world at tick " +
                                    std::to_string(world.tick)));
  }
  return *carrier;
}

/// A frame of `sensor` numbered `frame`, posed on its carrier at the world's tick.
SensorFrame start_frame(const SensorSpec& sensor, const engine::EntitySnapshot& carrier,
                        const engine::WorldSnapshot& world, int64_t frame) {
  SensorFrame f;
  f.sensor = sensor.name;
  f.kind = sensor.kind;
  f.frame = frame;
  f.tick = world.tick;
  f.time = world.time;
  const auto& p = carrier.pose;
  f.world_from_sensor =
      rigid_from_pose(p.x, p.y, p.z, p.h, p.p, p.r) * entity_from_sensor(sensor.mount);
  return f;
}

/// The due cameras grouped by optics: one render pass per group.
std::vector<CameraGroup> camera_groups(const std::vector<const SensorSpec*>& due) {
  std::vector<CameraGroup> groups;
  for (const SensorSpec* s : due) {
    if (!is_camera(s->kind)) {
      continue;
    }
    CameraGroup* group = nullptr;
    for (auto& g : groups) {
      if (same_optics(*g.members.front(), *s) && !(s->kind == SensorKind::kRgbCamera && g.rgb)) {
        group = &g;
      }
    }
    if (group == nullptr) {
      groups.emplace_back();
      group = &groups.back();
    }
    group->members.push_back(s);
    group->rgb = s->kind == SensorKind::kRgbCamera ? s : group->rgb;
    group->outputs.rgb = group->outputs.rgb || s->kind == SensorKind::kRgbCamera;
    group->outputs.depth = group->outputs.depth || s->kind == SensorKind::kDepthCamera;
    group->outputs.semantic = group->outputs.semantic || s->kind == SensorKind::kSemanticCamera;
    group->outputs.instance = true;
  }
  return groups;
}

/// What one render pass of group `g` needs: its outputs, light, carrier box, the deepest range
/// any member keeps, the RGB member's settings and the frame's seed.
RenderSettings group_settings(const CameraGroup& g, const Lighting& lighting,
                              const engine::EntitySnapshot& carrier, uint64_t frame_seed) {
  RenderSettings settings;
  settings.outputs = g.outputs;
  settings.lighting = &lighting;
  settings.carrier = entity_box(carrier);
  double max_depth = 0.0;
  for (const SensorSpec* m : g.members) {
    max_depth =
        std::max(max_depth, m->kind == SensorKind::kDepthCamera ? m->depth.max_range_m : 1e9);
  }
  settings.max_depth_m = max_depth;
  if (g.rgb != nullptr) {
    settings.rgb = g.rgb->rgb;
  }
  settings.frame_seed = frame_seed;
  return settings;
}

/// A LiDAR scan's inputs: the pose of frame `f`, its carrier's motion over the revolution, the
/// weather and the seed.
LidarScanInput lidar_input(const SensorFrame& f, const engine::EntitySnapshot& carrier,
                           const Lighting& lighting, uint64_t seed, double sweep) {
  LidarScanInput input;
  input.world_from_sensor = f.world_from_sensor;
  input.motion.velocity = {carrier.vx, carrier.vy, carrier.vz};
  input.motion.yaw_rate = carrier.yaw_rate;
  input.motion.pivot = {carrier.pose.x, carrier.pose.y, carrier.pose.z};
  input.weather.fog_extinction = lighting.fog_extinction;
  input.weather.rain_rate = lighting.rain_intensity;
  input.weather.snow_rate = lighting.snow_intensity;
  input.frame_seed = seed;
  input.carrier = entity_box(carrier);
  input.carrier_instance = carrier.instance_id;
  input.scene_motion_span = sweep;
  return input;
}

/// The due sensors that see the same entities, with those entities: one pass of the scene each.
struct VisibilityPass {
  std::vector<engine::EntitySnapshot> own;  ///< the entities as this pass sees them (empty: the
                                            ///< world's own, when no entity names a sensor)
  std::vector<const SensorSpec*> sensors;
};

/// The due sensors grouped by what they see (VisibilityAction's SensorReferenceSet: an entity
/// with sensor_exceptions is seen by some sensors and not by others), in rig order of each
/// group's first sensor. Without exceptions, one pass over the world's entities as they are.
std::vector<VisibilityPass> visibility_passes(const engine::WorldSnapshot& world,
                                              const std::vector<const SensorSpec*>& due) {
  const bool any = std::any_of(world.entities.begin(), world.entities.end(),
                               [](const auto& e) { return !e.sensor_exceptions.empty(); });
  if (!any) {
    return {VisibilityPass{{}, due}};
  }
  std::vector<VisibilityPass> passes;
  std::vector<std::vector<bool>> seen_by_pass;
  for (const SensorSpec* s : due) {
    std::vector<bool> seen;
    for (const auto& e : world.entities) {
      seen.push_back(engine::visible_to(e, s->name));
    }
    size_t k = 0;
    while (k < passes.size() && seen_by_pass[k] != seen) {
      ++k;
    }
    if (k == passes.size()) {
      VisibilityPass pass;
      pass.own = world.entities;
      for (size_t i = 0; i < pass.own.size(); ++i) {
        pass.own[i].visible = seen[i];
        pass.own[i].sensor_exceptions.clear();
      }
      passes.push_back(std::move(pass));
      seen_by_pass.push_back(std::move(seen));
    }
    passes[k].sensors.push_back(s);
  }
  return passes;
}

}  // namespace

struct SensorSystem::Cache {
  std::vector<std::unique_ptr<CameraRenderer>> renderers;  // one per distinct intrinsics
  std::map<std::string, const CameraRenderer*> cameras;
  std::map<std::string, std::unique_ptr<LidarSimulator>> lidars;
};

SensorSystem::SensorSystem(SensorRig rig, Scene& scene, SensorSystemOptions options)
    : rig_(std::move(rig)), scene_(scene), options_(options), cache_(std::make_unique<Cache>()) {
  for (const auto& s : rig_.sensors) {
    if (is_camera(s.kind)) {
      const CameraRenderer* shared = nullptr;
      for (const auto& r : cache_->renderers) {
        const auto& k = r->model().intrinsics();
        if (k.width == s.camera.width && k.height == s.camera.height &&
            k.fov_deg == s.camera.fov_deg && k.k1 == s.camera.k1 && k.k2 == s.camera.k2 &&
            k.p1 == s.camera.p1 && k.p2 == s.camera.p2) {
          shared = r.get();
        }
      }
      if (shared == nullptr) {
        cache_->renderers.push_back(std::make_unique<CameraRenderer>(s.camera));
        shared = cache_->renderers.back().get();
      }
      cache_->cameras[s.name] = shared;
    } else if (s.kind == SensorKind::kLidar) {
      cache_->lidars[s.name] = std::make_unique<LidarSimulator>(s.lidar);
    }
  }
}

SensorSystem::~SensorSystem() = default;

const CameraModel* SensorSystem::camera_model(const std::string& sensor) const {
  const auto it = cache_->cameras.find(sensor);
  return it == cache_->cameras.end() ? nullptr : &it->second->model();
}

void SensorSystem::render_pass(
    const std::vector<const SensorSpec*>& due, const Lighting& lighting, double sweep,
    std::map<std::string, SensorFrame>& frames,
    const std::map<std::string, const engine::EntitySnapshot*>& carriers) {
  auto frame_seed = [&](const SensorSpec& s) {
    return derive_seed(options_.seed, s.name + "#" + std::to_string(frames.at(s.name).frame));
  };
  // Every camera group, LiDAR and bird's-eye view is one task: each writes only its own frames
  // and reads the scene, which does not change until the pass ends. Each is deterministic on
  // its own (fixed blocks, seeds by sensor and frame), so running them side by side keeps the
  // bytes; it fills the cores where one sensor's work runs out of parallelism (labels, the
  // bird's-eye view's rows, the end of a parallel loop).
  const std::vector<CameraGroup> groups = camera_groups(due);
  tbb::task_group tasks;
  for (const CameraGroup& g : groups) {
    const SensorSpec& lead = *g.members.front();
    const engine::EntitySnapshot& carrier = *carriers.at(lead.name);
    const RenderSettings settings =
        group_settings(g, lighting, carrier, frame_seed(g.rgb != nullptr ? *g.rgb : lead));
    std::vector<SensorFrame*> outputs;
    for (const SensorSpec* m : g.members) {
      outputs.push_back(&frames.at(m->name));
    }
    const CameraRenderer& renderer = *cache_->cameras.at(lead.name);
    tasks.run([this, &g, &renderer, &carrier, settings, outputs] {
      render_camera_group(scene_, renderer, g.members, carrier, settings, outputs,
                          options_.rgb_instances);
    });
  }
  for (const SensorSpec* s : due) {
    SensorFrame& f = frames.at(s->name);
    const engine::EntitySnapshot& carrier = *carriers.at(s->name);
    if (s->kind == SensorKind::kLidar) {
      const LidarScanInput input = lidar_input(f, carrier, lighting, frame_seed(*s), sweep);
      tasks.run([this, s, &f, &carrier, input] {
        f.cloud = cache_->lidars.at(s->name)->scan(scene_, input);
        f.labels = lidar_labels(scene_, f.world_from_sensor, f.cloud, s->lidar.range_m,
                                carrier.instance_id);
      });
    } else if (s->kind == SensorKind::kBirdsEyeCamera) {
      tasks.run([this, s, &f, &lighting] {
        f.birds_eye = render_birds_eye(scene_, s->birds_eye, f.world_from_sensor, &lighting);
      });
    }
  }
  tasks.wait();
}

std::vector<SensorFrame> SensorSystem::capture(const engine::WorldSnapshot& world,
                                               std::span<const std::string> sensors) {
  const Lighting lighting = compute_lighting(world.environment, options_.location);
  const std::vector<const SensorSpec*> due = due_sensors(rig_, sensors);
  const double sweep = longest_sweep(due);  // s: the entities move over a LiDAR revolution
  scene_.set_signals(world.signals);
  // Pose, carrier and frame number of each due sensor.
  std::map<std::string, SensorFrame> frames;
  std::map<std::string, const engine::EntitySnapshot*> carriers;
  for (const SensorSpec* s : due) {
    const engine::EntitySnapshot& carrier = carrier_of(rig_, *s, world);
    carriers[s->name] = &carrier;
    frames[s->name] = start_frame(*s, carrier, world, frames_[s->name]++);
  }
  // Sensors that see different entities (a SensorReferenceSet) render in passes, the scene's
  // entities placed for each; without one, a single pass over the world's entities.
  for (const VisibilityPass& pass : visibility_passes(world, due)) {
    scene_.set_entities(pass.own.empty() ? world.entities : pass.own, sweep);
    render_pass(pass.sensors, lighting, sweep, frames, carriers);
  }
  std::vector<SensorFrame> out;
  for (const SensorSpec* s : due) {
    out.push_back(std::move(frames[s->name]));
  }
  return out;
}

}  // namespace corsa::sensors
