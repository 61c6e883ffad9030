#include "corsa/sensors/world.h"

#include <cmath>

#include "corsa/core/strings.h"
#include "world_build.h"

namespace corsa::sensors {
namespace detail {
namespace {

int64_t cell_key(double x, double y) {
  const auto i = static_cast<int64_t>(std::floor(x / 4.0));
  const auto j = static_cast<int64_t>(std::floor(y / 4.0));
  return i * 1000003 + j;
}

}  // namespace

Edge edge_at(const xodr::Map& map, size_t road, double s, int side,
             std::vector<xodr::LaneSpan>& spans) {
  map.lane_spans(road, s, spans);
  Edge e;
  const size_t section = map.section_index(road, s);
  const auto& lanes = map.road(road).lane_sections[section].lanes;
  const xodr::LaneSpan* outer = nullptr;
  for (const auto& span : spans) {
    if ((side > 0 && span.id > 0) || (side < 0 && span.id < 0)) {
      if (outer == nullptr || std::abs(span.id) > std::abs(outer->id)) {
        outer = &span;
      }
    }
  }
  if (outer == nullptr) {
    return e;
  }
  e.valid = true;
  e.t_outer = outer->t_outer;
  for (const auto& lane : lanes) {
    if (lane.id == outer->id) {
      e.sidewalk = lane.type == xodr::LaneType::kSidewalk || lane.type == xodr::LaneType::kWalking;
    }
  }
  e.kerb = outer->t_inner;
  return e;
}

bool next_to_junction(const xodr::Map& map, size_t road, double s, double margin) {
  const xodr::Road& r = map.road(road);
  return (s < margin && r.predecessor.element_type == xodr::LinkElement::kJunction) ||
         (s > r.length - margin && r.successor.element_type == xodr::LinkElement::kJunction);
}

bool motorway_at(const xodr::Road& road, double s) {
  const xodr::RoadType* type = nullptr;
  for (const auto& t : road.types) {
    if (t.s <= s + 1e-9) {
      type = &t;
    }
  }
  if (type == nullptr) {
    return false;
  }
  return to_lower(type->type) == "motorway" ||
         (type->max_speed && *type->max_speed >= 80.0 / 3.6 - 1e-6);
}

uint32_t WorldBuild::place(const ArticulatedMesh& mesh, const Rigid& pose, const std::string& name,
                           const ObjectInfo& info, const std::string& signal_id) {
  StaticMesh m = to_static_mesh(mesh, pose, name);
  m.object = info;
  m.signal_id = signal_id;
  return scene.add_static_mesh(std::move(m));
}

uint32_t WorldBuild::place_paint(const ArticulatedMesh& mesh, const Rigid& pose,
                                 const std::string& name, const ObjectInfo& info) {
  StaticMesh m = to_static_mesh(mesh, pose, name);
  m.object = info;
  // Paint is stuff and gets no instance id by its class; painted objects take the next static id.
  m.instance_id = kStaticInstanceBase + static_cast<uint32_t>(scene.static_mesh_count());
  return scene.add_static_mesh(std::move(m));
}

std::optional<double> GroundField::height_at(double x, double y) const {
  const double fx = (x - x0) / cell;
  const double fy = (y - y0) / cell;
  if (nx < 2 || ny < 2 || !(fx >= 0.0) || !(fy >= 0.0) || fx >= nx - 1 || fy >= ny - 1) {
    return std::nullopt;
  }
  const int i = static_cast<int>(fx);
  const int j = static_cast<int>(fy);
  const double u = fx - i;
  const double v = fy - j;
  const size_t a = static_cast<size_t>(j) * nx + i;
  const double ha = h[a], hb = h[a + 1], hc = h[a + nx + 1], hd = h[a + nx];
  // The triangles (a, b, c) and (a, c, d) of the ground mesh.
  return u >= v ? ha + u * (hb - ha) + v * (hc - hb) : ha + v * (hd - ha) + u * (hc - hd);
}

bool WorldBuild::clear_of_props(double x, double y, double radius) const {
  for (int di = -2; di <= 2; ++di) {
    for (int dj = -2; dj <= 2; ++dj) {
      const auto it = placed.find(cell_key(x + 4.0 * di, y + 4.0 * dj));
      if (it == placed.end()) {
        continue;
      }
      for (const auto& p : it->second) {
        if (std::hypot(p[0] - x, p[1] - y) < radius + p[2]) {
          return false;
        }
      }
    }
  }
  return true;
}

void WorldBuild::remember(double x, double y, double radius) {
  placed[cell_key(x, y)].push_back({x, y, radius});
}

std::vector<Clearance> WorldBuild::lamp_clearances(const Rigid& pose, double reach) const {
  // 1.5 m about the head: its light and the view of it stay free.
  constexpr double kRoom = 1.5;
  std::vector<Clearance> out;
  const Rigid back = pose.inverse();
  for (const Vec3& head : lamp_heads) {
    if (std::hypot(head.x - pose.translation.x, head.y - pose.translation.y) < reach + kRoom) {
      out.push_back({back.apply(head), kRoom});
    }
  }
  return out;
}

bool WorldBuild::near_drivable(double x, double y, double margin) const {
  xodr::LocateOptions o;
  o.max_distance = margin;
  o.drivable_only = true;
  return map.locate(x, y, o).has_value();
}

bool WorldBuild::under_building(double x, double y, double z) const {
  const auto hit = scene.intersect({x, y, z + 150.0}, {0.0, 0.0, -1.0}, 155.0);
  return hit &&
         (hit->semantic == SemanticClass::kBuilding || hit->semantic == SemanticClass::kWall);
}

}  // namespace detail

WorldReport build_world(const xodr::Map& map, Scene& scene, const WorldOptions& options,
                        Diagnostics& diagnostics) {
  detail::WorldBuild w{map, scene, options, diagnostics, {}, {}, {}, {}};
  if (options.ground) {
    const xodr::RoadMesh road = xodr::build_road_mesh(map, xodr::MeshOptions{.road_marks = false});
    detail::build_ground(w, road);
    detail::build_verges(w);
    detail::build_seams(w);
    detail::build_junction_paving(w, road);
  }
  if (options.signals) {
    detail::build_signals(w);
  }
  if (options.objects) {
    detail::build_objects(w);
  }
  if (options.guard_rails) {
    detail::build_rails(w);
  }
  if (options.buildings) {
    // Plants and street lights keep clear of buildings found by rays: commit them first.
    detail::build_buildings(w);
    scene.commit();
  }
  if (options.vegetation || options.street_lights) {
    detail::build_roadside(w);
  }
  if (options.street_furniture) {
    // After the trees and lights, which have the kerb first; after the signals and objects,
    // whose crosswalks it keeps clear of.
    detail::build_furniture(w);
  }
  if (options.parked != ParkedVehicles::kNone) {
    // Last: cars keep clear of the props, hydrants, bus stops and crosswalks placed before.
    detail::build_parked_vehicles(w);
  }
  return w.report;
}

}  // namespace corsa::sensors
