// Parked vehicles, placed from the run seed and the road's or object's id (the same seed parks
// the same cars): in the lanes of type parking and the parkingSpace objects of the map, and, when
// the rig asks for kerb parking, along the kerb of streets that have no parking markup, on the
// strip of shoulder, border or stop lane between the outermost driving lane and the kerb where it
// is wide enough for a car (never on a driving lane). Each car is one of the generated cars
// (sedan, hatchback, SUV, van, pickup, in the fleet's shares, with the paint colours of moving
// cars), its lamps dark and its wheels straight, nudged a little along and across its slot and
// turned a degree or two; a share of the slots is left empty. Cars keep clear of junction mouths,
// crosswalks, bus stops, fire hydrants, props (trees, street lights, furniture), buildings and
// the scenario's entities.

#include <algorithm>
#include <cmath>

#include "corsa/core/strings.h"
#include "scalar_math.h"
#include "scene_data.h"
#include "vehicle_generators.h"
#include "world_build.h"

namespace corsa::sensors::detail {
namespace {

/// No parking this close to a junction's mouth (m along the road; 5 m is the common legal
/// minimum from an intersection, plus the corner's radius).
constexpr double kParkJunctionMargin = 8.0;
/// Metres kept free before and after a crosswalk's paint (5 m in most codes).
constexpr double kParkCrosswalkMargin = 5.0;
/// Metres kept free either side of a fire hydrant (5 m in most codes).
constexpr double kParkHydrantMargin = 5.0;
/// Metres kept free either side of a bus stop's shelter or sign (the bus pulls in and out).
constexpr double kParkBusStopMargin = 12.0;
/// Least width of a kerb-side strip (shoulder, border, stop lane) that holds a parked car.
constexpr double kParkStripWidth = 2.1;
/// Metres between a parked car's side and the kerb (parallel parking, 15-35 cm).
constexpr double kParkKerbGapMin = 0.15;
constexpr double kParkKerbGapMax = 0.35;

/// One parked car's model: body style, size (m) and the label's name of the style.
struct ParkedModel {
  CarStyle style = CarStyle::kSedan;
  double length = 4.7;
  double width = 1.85;
  double height = 1.45;
  const char* name = "sedan";
};

/// A car drawn in the shares of a city's parked fleet (European and Korean registrations:
/// about two in five saloons, a quarter hatchbacks, a quarter SUVs, a few vans and pickups),
/// its size varied by a few per cent.
ParkedModel draw_parked_model(RandomStream& rng) {
  const double u = rng.uniform01();
  ParkedModel m;
  if (u < 0.38) {
    m = {CarStyle::kSedan, 4.7, 1.84, 1.45, "sedan"};
  } else if (u < 0.62) {
    m = {CarStyle::kHatchback, 4.1, 1.78, 1.48, "hatchback"};
  } else if (u < 0.86) {
    m = {CarStyle::kSuv, 4.6, 1.88, 1.7, "suv"};
  } else if (u < 0.94) {
    m = {CarStyle::kVan, 5.0, 1.95, 1.98, "van"};
  } else {
    m = {CarStyle::kPickup, 5.3, 1.9, 1.8, "pickup"};
  }
  const double scale = rng.uniform(0.96, 1.04);
  m.length *= scale;
  m.width *= rng.uniform(0.98, 1.02);
  m.height *= rng.uniform(0.97, 1.03);
  return m;
}

/// A zone where no car parks: an axis-aligned box (map frame) and the distance kept from it (m).
struct NoParkingZone {
  Bounds box;
  double margin = 0.0;
};

/// A candidate place for a car: its box centre on the ground (map frame), heading and slope.
struct ParkingPlace {
  double x = 0.0;
  double y = 0.0;
  double z = 0.0;
  double heading = 0.0;
  double pitch = 0.0;
  double roll = 0.0;
};

class VehicleParker {
 public:
  explicit VehicleParker(WorldBuild& w) : w_(w) { collect_zones(); }

  /// Parks `model` centred at `place` when nothing is in the way; true when parked. `source`
  /// names what held the slot (parking_lane, parking_space, kerb) for the labels.
  bool park(const ParkedModel& model, const ParkingPlace& place, RandomStream& look,
            const std::string& name, const char* source) {
    if (!clear(model, place)) {
      return false;
    }
    // The reference point is the rear axle (OpenSCENARIO's vehicle frame), 22% of the length
    // ahead of the rear end.
    engine::Box box;
    box.length = model.length;
    box.width = model.width;
    box.height = model.height;
    box.center_x = 0.5 * model.length - 0.22 * model.length;
    box.center_z = 0.5 * model.height;
    const GeneratedVehicle v = generate_car(model.style, box, look);
    const Rigid ground =
        rigid_from_pose(place.x, place.y, place.z, place.heading, place.pitch, place.roll);
    const Rigid pose = ground * rigid_from_pose(-box.center_x, 0.0, 0.0, 0.0, 0.0, 0.0);
    ObjectInfo info;
    info.kind = "parked_vehicle";
    info.type = model.name;
    info.subtype = source;
    info.semantic = SemanticClass::kCar;
    Box3 label;
    label.center = ground.apply({0.0, 0.0, box.center_z});
    label.rotation = ground.rotation;
    label.length = model.length;
    label.width = model.width;
    label.height = model.height;
    info.box = label;
    // Lamps stay dark: the scene lights static lamps of street lights and signals only.
    w_.place(v.mesh, pose, name, info);
    cars_.push_back(
        {place.x, place.y, place.heading, 0.5 * (model.length - model.width), 0.5 * model.width});
    ++w_.report.parked_vehicles;
    return true;
  }

 private:
  /// Hydrants, bus stops and crosswalks drawn so far, and the scenario's entities.
  void collect_zones() {
    for (const auto& [id, record] : w_.scene.data().objects) {
      const std::string& kind = record.info.kind;
      const double margin = kind == "fire_hydrant"                             ? kParkHydrantMargin
                            : kind == "bus_shelter" || kind == "bus_stop_sign" ? kParkBusStopMargin
                            : kind == "crosswalk" ? kParkCrosswalkMargin
                                                  : -1.0;
      if (margin >= 0.0) {
        zones_.push_back({record.bounds, margin});
      }
    }
    for (const KeepClear& k : w_.options.keep_clear) {
      Bounds b;
      b.min = b.max = Vec3{k.x, k.y, 0.0};
      zones_.push_back({b, k.radius});
    }
  }

  /// True when the car's footprint keeps clear of the zones, other parked cars, and anything
  /// standing in the space the car would fill (props, poles, trunks, low branches, buildings).
  bool clear(const ParkedModel& model, const ParkingPlace& p) {
    const double c = std::cos(p.heading), s = std::sin(p.heading);
    const double half_l = 0.5 * model.length, half_w = 0.5 * model.width;
    for (const NoParkingZone& z : zones_) {
      const double dx = std::max({z.box.min.x - p.x, 0.0, p.x - z.box.max.x});
      const double dy = std::max({z.box.min.y - p.y, 0.0, p.y - z.box.max.y});
      if (std::hypot(dx, dy) < z.margin + half_l) {
        return false;
      }
    }
    for (const auto& q : cars_) {
      // Three circles along each car: conservative for cars side by side or end to end.
      for (const double k : {-1.0, 0.0, 1.0}) {
        const double x = p.x + k * (half_l - half_w) * c, y = p.y + k * (half_l - half_w) * s;
        for (const double m : {-1.0, 0.0, 1.0}) {
          const double qx = q[0] + m * q[3] * std::cos(q[2]), qy = q[1] + m * q[3] * std::sin(q[2]);
          if (std::hypot(qx - x, qy - y) < half_w + q[4] + 0.1) {
            return false;
          }
        }
      }
    }
    if (!committed_) {
      // The props placed since the last commit must be in the ray tracer's structure.
      w_.scene.commit();
      committed_ = true;
    }
    // Rays down over the footprint, every 0.4 m, from just above the roof to just above the
    // ground: anything but paving hit in between stands where the car would be.
    const int nu = static_cast<int>(std::ceil(model.length / 0.4));
    const int nv = static_cast<int>(std::ceil(model.width / 0.4));
    const double top = model.height + 0.1;
    for (int i = 0; i <= nu; ++i) {
      for (int j = 0; j <= nv; ++j) {
        const double u = -half_l + model.length * i / nu, v = -half_w + model.width * j / nv;
        const Vec3 from{p.x + u * c - v * s, p.y + u * s + v * c, p.z + top};
        const auto hit = w_.scene.intersect(from, {0.0, 0.0, -1.0}, top - 0.1);
        if (hit && !is_paving(hit->semantic)) {
          return false;
        }
      }
    }
    return true;
  }

  static bool is_paving(SemanticClass c) {
    return c == SemanticClass::kRoad || c == SemanticClass::kLaneMarking ||
           c == SemanticClass::kParking || c == SemanticClass::kSidewalk ||
           c == SemanticClass::kTerrain || c == SemanticClass::kGround;
  }

  WorldBuild& w_;
  std::vector<NoParkingZone> zones_;
  /// Cars parked so far: x, y, heading, half length less half width, half width.
  std::vector<std::array<double, 5>> cars_;
  bool committed_ = false;
};

/// The place of a car parallel-parked at s in the strip [t_near, t_far] of a road side (t_far
/// at the kerb), its side `kerb_gap` metres from the kerb, heading with the side's traffic.
ParkingPlace kerb_place(const xodr::Map& map, size_t r, int side, double s, double t_kerb,
                        double offset, double yaw) {
  const xodr::Road& road = map.road(r);
  const xodr::WorldPose p = map.world_pose(r, s, t_kerb - side * offset);
  // Right-hand traffic drives towards +s on the right (t < 0); left-hand on the left.
  const bool forward = (side < 0) == (road.rule != xodr::TrafficRule::kLeftHand);
  ParkingPlace place;
  place.x = p.x;
  place.y = p.y;
  place.z = p.z;
  place.heading = p.h + (forward ? 0.0 : kPi) + yaw;
  place.pitch = forward ? p.p : -p.p;
  place.roll = forward ? p.r : -p.r;
  return place;
}

bool is_kerb_strip_lane(xodr::LaneType type) {
  return type == xodr::LaneType::kShoulder || type == xodr::LaneType::kBorder ||
         type == xodr::LaneType::kStop;
}

/// The strip a car can park in at s on one side of a road: for `lane_id` != 0 that lane (a
/// parking lane), else the run of shoulder, border and stop lanes between the outermost
/// drivable lane and the kerb. Returns its kerb-side t and width (0 when there is none).
std::pair<double, double> strip_at(const xodr::Map& map, size_t r, double s, int side, int lane_id,
                                   std::vector<xodr::LaneSpan>& spans) {
  map.lane_spans(r, s, spans);
  const auto& lanes = map.road(r).lane_sections[map.section_index(r, s)].lanes;
  auto type_of = [&](int id) {
    for (const auto& lane : lanes) {
      if (lane.id == id) {
        return lane.type;
      }
    }
    return xodr::LaneType::kNone;
  };
  if (lane_id != 0) {
    for (const auto& span : spans) {
      if (span.id == lane_id) {
        return {span.t_outer, span.width()};
      }
    }
    return {0.0, 0.0};
  }
  std::vector<const xodr::LaneSpan*> side_spans;
  for (const auto& span : spans) {
    if ((side > 0) == (span.id > 0) && span.id != 0) {
      side_spans.push_back(&span);
    }
  }
  std::sort(side_spans.begin(), side_spans.end(),
            [](const auto* a, const auto* b) { return std::abs(a->id) < std::abs(b->id); });
  // Outwards from the outermost drivable lane: the run of strip lanes up to the kerb.
  size_t first = side_spans.size();
  for (size_t i = 0; i < side_spans.size(); ++i) {
    if (xodr::is_drivable(type_of(side_spans[i]->id))) {
      first = i + 1;
    }
  }
  if (first >= side_spans.size()) {
    return {0.0, 0.0};
  }
  double width = 0.0, t_kerb = 0.0;
  for (size_t i = first; i < side_spans.size() && is_kerb_strip_lane(type_of(side_spans[i]->id));
       ++i) {
    width += side_spans[i]->width();
    t_kerb = side_spans[i]->t_outer;
  }
  return {t_kerb, width};
}

/// Cars along one side of a road between s0 and s1, in slots of a car's length plus a gap,
/// `density` of them taken, in the strip `strip_at` finds (a parking lane when lane_id != 0).
void park_along(VehicleParker& parker, WorldBuild& w, RandomStream& rng, size_t r, int side,
                int lane_id, double s0, double s1, const char* source) {
  const xodr::Road& road = w.map.road(r);
  std::vector<xodr::LaneSpan> spans;
  double s = s0 + rng.uniform(0.0, 2.0);
  while (s < s1) {
    RandomStream look(rng.next_u64());
    const ParkedModel model = draw_parked_model(look);
    // A gap of 0.8-2.5 m to the next car (room to pull out); 15% of slots are a long gap.
    const double slot = model.length + look.uniform(0.8, 2.5);
    const bool taken = look.uniform01() < w.options.parked_density;
    const double mid = s + 0.5 * model.length + look.uniform(-0.3, 0.3);
    s += slot;
    if (!taken || mid + 0.5 * model.length > s1 ||
        next_to_junction(w.map, r, mid - 0.5 * model.length, kParkJunctionMargin) ||
        next_to_junction(w.map, r, mid + 0.5 * model.length, kParkJunctionMargin)) {
      continue;
    }
    // The strip must hold the car's width over its whole length.
    double t_kerb = 0.0;
    bool fits = true;
    for (const double at : {mid - 0.5 * model.length, mid, mid + 0.5 * model.length}) {
      const auto [t, width] = strip_at(w.map, r, at, side, lane_id, spans);
      fits = fits && width >= std::max(model.width + 0.2, lane_id != 0 ? 0.0 : kParkStripWidth);
      t_kerb = at == mid ? t : t_kerb;
    }
    if (!fits) {
      continue;
    }
    const double offset = 0.5 * model.width + look.uniform(kParkKerbGapMin, kParkKerbGapMax);
    const double yaw = look.uniform(-0.025, 0.025);  // ±1.4°
    const ParkingPlace place = kerb_place(w.map, r, side, mid, t_kerb, offset, yaw);
    parker.park(model, place, look, "parked " + road.id, source);
  }
}

/// The scenario's entities' lanes (road id, lane id) that kerb parking leaves empty.
bool lane_kept_clear(const WorldOptions& o, const std::string& road, int lane) {
  return std::any_of(o.keep_clear.begin(), o.keep_clear.end(),
                     [&](const KeepClear& k) { return k.road == road && k.lane == lane; });
}

/// Cars in the parking lanes of every road outside junctions.
void park_in_parking_lanes(VehicleParker& parker, WorldBuild& w) {
  const xodr::Map& map = w.map;
  for (size_t r = 0; r < map.road_count(); ++r) {
    const xodr::Road& road = map.road(r);
    if (road.in_junction()) {
      continue;
    }
    for (size_t k = 0; k < road.lane_sections.size(); ++k) {
      const double s0 = road.lane_sections[k].s;
      const double s1 =
          k + 1 < road.lane_sections.size() ? road.lane_sections[k + 1].s : road.length;
      for (const auto& lane : road.lane_sections[k].lanes) {
        if (lane.type != xodr::LaneType::kParking || lane.id == 0) {
          continue;
        }
        RandomStream rng(derive_seed(w.options.seed, "parked " + road.id + " lane " +
                                                         std::to_string(lane.id) + " section " +
                                                         std::to_string(k)));
        park_along(parker, w, rng, r, lane.id > 0 ? 1 : -1, lane.id, s0, s1, "parking_lane");
      }
    }
  }
}

/// True when a point lies inside a polygon (even-odd rule, x and y).
bool inside_outline(const std::vector<Vec3>& ring, const Vec3& p) {
  bool in = false;
  for (size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) {
    const Vec3& a = ring[i];
    const Vec3& b = ring[j];
    if ((a.y > p.y) != (b.y > p.y) && p.x < (b.x - a.x) * (p.y - a.y) / (b.y - a.y) + a.x) {
      in = !in;
    }
  }
  return in;
}

/// Cars in parkingSpace objects: one in a space of one car's size (nose in, or now and then
/// reversed in), rows of 2.5 x 5 m stalls along the long side of a larger lot (two rows back
/// to back between 6 m aisles), each stall inside the outline.
void park_in_spaces(VehicleParker& parker, WorldBuild& w) {
  const xodr::Map& map = w.map;
  for (size_t r = 0; r < map.road_count(); ++r) {
    for (const xodr::Object& o : map.road(r).objects) {
      if (to_lower(o.type) != "parkingspace") {
        continue;
      }
      std::vector<Rigid> frames;
      std::vector<double> lengths;
      object_frames(map, r, o, frames, lengths);
      for (size_t k = 0; k < frames.size(); ++k) {
        RandomStream rng(
            derive_seed(w.options.seed, "parked space " + o.id + "#" + std::to_string(k)));
        std::vector<Vec3> outline;
        if (!o.outlines.empty()) {
          outline = outline_points(map, r, o.outlines.front(), frames[k]);
        }
        double x0, x1, y0, y1;
        object_extent(o, outline, x0, x1, y0, y1);
        // Work in a frame whose u runs along the space's long side.
        const bool along_x = x1 - x0 >= y1 - y0;
        const double long_side = along_x ? x1 - x0 : y1 - y0;
        const double short_side = along_x ? y1 - y0 : x1 - x0;
        auto to_frame = [&](double u, double v) {  // (u along, v across) from the min corner
          return along_x ? Vec3{x0 + u, y0 + v, 0.0} : Vec3{x0 + v, y0 + u, 0.0};
        };
        const double frame_yaw = std::atan2(frames[k].rotation.m[1][0], frames[k].rotation.m[0][0]);
        auto place_at = [&](double u, double v, bool car_along_u, bool reversed) {
          const Vec3 p = frames[k].apply(to_frame(u, v));
          const double axis = along_x == car_along_u ? 0.0 : 0.5 * kPi;
          ParkingPlace place{p.x, p.y, p.z, frame_yaw + axis + (reversed ? kPi : 0.0), 0.0, 0.0};
          return place;
        };
        if (long_side < 7.5 && short_side < 4.5) {
          // One space: the car along its long side.
          RandomStream look(rng.next_u64());
          const ParkedModel model = draw_parked_model(look);
          if (look.uniform01() >= w.options.parked_density || model.length > long_side - 0.2 ||
              model.width > short_side - 0.3) {
            continue;
          }
          const double du = look.uniform(-0.15, 0.15), dv = look.uniform(-0.12, 0.12);
          ParkingPlace place =
              place_at(0.5 * long_side + du, 0.5 * short_side + dv, true, look.uniform01() < 0.3);
          place.heading += look.uniform(-0.03, 0.03);
          parker.park(model, place, look, "parked " + o.id, "parking_space");
          continue;
        }
        // A lot: stalls 2.5 m wide along u, 5 m deep along v; rows at v 0-5 (facing +v) and
        // 11-16 (facing -v), repeating every 16 m.
        for (double v = 0.0; v + 5.0 <= short_side + 1e-9; v += 16.0) {
          for (const double row : {0.0, 11.0}) {
            if (v + row + 5.0 > short_side + 1e-9) {
              continue;
            }
            for (double u = 0.0; u + 2.5 <= long_side + 1e-9; u += 2.5) {
              RandomStream look(rng.next_u64());
              const ParkedModel model = draw_parked_model(look);
              bool inside = true;
              for (const double du : {0.0, 2.5}) {
                for (const double dv : {0.0, 5.0}) {
                  inside = inside && (outline.size() < 3 ||
                                      inside_outline(outline, to_frame(u + du, v + row + dv)));
                }
              }
              if (look.uniform01() >= w.options.parked_density || model.length > 5.0 || !inside) {
                continue;
              }
              const bool faces_plus_v = row == 0.0;
              ParkingPlace place = place_at(u + 1.25 + look.uniform(-0.1, 0.1),
                                            v + row + 2.5 + look.uniform(-0.15, 0.15), false,
                                            !faces_plus_v != (look.uniform01() < 0.2));
              place.heading += look.uniform(-0.03, 0.03);
              parker.park(model, place, look, "parked " + o.id, "parking_space");
            }
          }
        }
      }
    }
  }
}

/// True when the road has parking markup: a parking lane or a parkingSpace object.
bool has_parking_markup(const xodr::Road& road) {
  for (const auto& section : road.lane_sections) {
    for (const auto& lane : section.lanes) {
      if (lane.type == xodr::LaneType::kParking) {
        return true;
      }
    }
  }
  return std::any_of(road.objects.begin(), road.objects.end(),
                     [](const xodr::Object& o) { return to_lower(o.type) == "parkingspace"; });
}

/// Cars along the kerbs of streets (not motorways, not in junctions) without parking markup,
/// on sides where no scenario entity starts in a kerb-side strip lane.
void park_along_kerbs(VehicleParker& parker, WorldBuild& w) {
  const xodr::Map& map = w.map;
  for (size_t r = 0; r < map.road_count(); ++r) {
    const xodr::Road& road = map.road(r);
    if (road.in_junction() || road.length < 2.0 * kParkJunctionMargin + 5.0 ||
        has_parking_markup(road) ||
        std::any_of(road.types.begin(), road.types.end(),
                    [&](const xodr::RoadType& t) { return motorway_at(road, t.s); }) ||
        motorway_at(road, 0.0)) {
      continue;
    }
    for (const int side : {-1, 1}) {
      bool entity_in_strip = false;
      for (const auto& section : road.lane_sections) {
        for (const auto& lane : section.lanes) {
          entity_in_strip = entity_in_strip || ((lane.id > 0) == (side > 0) && lane.id != 0 &&
                                                is_kerb_strip_lane(lane.type) &&
                                                lane_kept_clear(w.options, road.id, lane.id));
        }
      }
      if (entity_in_strip) {
        continue;
      }
      RandomStream rng(
          derive_seed(w.options.seed, "parked kerb " + road.id + " side " + std::to_string(side)));
      park_along(parker, w, rng, r, side, 0, 0.0, road.length, "kerb");
    }
  }
}

}  // namespace

void build_parked_vehicles(WorldBuild& w) {
  if (w.options.parked == ParkedVehicles::kNone || w.options.parked_density <= 0.0) {
    return;
  }
  VehicleParker parker(w);
  park_in_parking_lanes(parker, w);
  park_in_spaces(parker, w);
  if (w.options.parked == ParkedVehicles::kKerb) {
    park_along_kerbs(parker, w);
  }
}

}  // namespace corsa::sensors::detail
