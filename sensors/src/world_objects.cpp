// OpenDRIVE objects (OpenDRIVE 1.8 §13): crosswalks (zebra stripes within the outline or box),
// parking spaces (their outline painted), stop lines, poles, street lamps, trees and vegetation,
// barriers, guard rails and railings, buildings (outline extruded, or the box), obstacles;
// repeats place a copy every `distance` metres or stretch rails along the road. CARLA's maps
// name some objects instead of typing them: "StopLine", "Speed_NN" (a speed-limit sign) and
// the RoadRunner stencils "Stencil_ArrowType4L/R" (turn arrows), "Stencil_ArrowType1*"
// (straight arrows) and "Stencil_STOP" (the word) are drawn, and "DashedShortSingleWhite" and
// "DashedSingleYellow" (RoadRunner lane-marking styles CARLA exports as objects: a line of white
// short dashes or yellow dashes along the outline, which is the line itself, not a ring); other
// untyped objects (its duplicated lane lines, other stencils) are left out with one warning per
// name.

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>

#include "corsa/core/diagnostic.h"
#include "corsa/core/strings.h"
#include "road_symbols.h"
#include "scalar_math.h"
#include "world_build.h"
#include "world_props.h"

namespace corsa::sensors::detail {
namespace {

/// A RoadRunner dashed marking style that CARLA exports as an untyped object named after it.
struct RoadRunnerDashStyle {
  const char* name;
  const char* subtype;  ///< the label's subtype
  double dash;          ///< m of paint
  double gap;           ///< m bare between dashes
  double width;         ///< m
  bool yellow;
};

// RoadRunner's own dash sizes are not published; these are the US markings the styles name
// (Town04 is a US town, signed in mph).
constexpr RoadRunnerDashStyle kRoadRunnerDashes[] = {
    // Dotted line extension through a junction: 2 ft dashes, 4 ft gaps (the middle of the
    // MUTCD's 2-6 ft, 2009 §3A.06), 6 in wide.
    {"DashedShortSingleWhite", "dashed_short", 0.61, 1.22, 0.15, false},
    // Normal broken yellow centre line (MUTCD 2009 §3A.06 broken line: 10 ft segments, 30 ft
    // gaps; §3B.01 yellow centre line), as wide as Town04's own broken yellow roadMarks (0.125 m,
    // within the MUTCD's 4-6 in normal width).
    {"DashedSingleYellow", "dashed", 3.05, 9.14, 0.125, true},
};

const RoadRunnerDashStyle* roadrunner_dash_style(const std::string& name) {
  for (const RoadRunnerDashStyle& style : kRoadRunnerDashes) {
    if (name == style.name) {
      return &style;
    }
  }
  return nullptr;
}

ObjectInfo kind_info(std::string kind) {
  ObjectInfo info;
  info.kind = std::move(kind);
  return info;
}

/// An object's frame: road position, zOffset, heading relative to the road (§13.2).
Rigid object_frame(const xodr::Map& map, size_t road, double s, double t, double z_offset,
                   double hdg) {
  const xodr::WorldPose p = map.world_pose(road, std::clamp(s, 0.0, map.road(road).length), t);
  return rigid_from_pose(p.x, p.y, p.z + z_offset, p.h + hdg, 0.0, 0.0);
}

/// Flat paint rectangles (x0..x1, y0..y1 in the frame, 1 cm up), class lane marking.
void paint_rect(MeshBuilder& b, double x0, double x1, double y0, double y1) {
  b.polygon({{x0, y0, 0.012}, {x1, y0, 0.012}, {x1, y1, 0.012}, {x0, y1, 0.012}}, {});
}

}  // namespace

std::vector<Vec3> outline_points(const xodr::Map& map, size_t road, const xodr::Outline& o,
                                 const Rigid& frame) {
  std::vector<Vec3> out;
  const Rigid back = frame.inverse();
  for (const auto& c : o.corners) {
    if (c.road) {
      const xodr::WorldPose p = map.world_pose(road, c.u, c.v);
      out.push_back(back.apply({p.x, p.y, p.z + c.z}));
    } else {
      out.push_back({c.u, c.v, c.z});
    }
  }
  return out;
}

void object_extent(const xodr::Object& o, const std::vector<Vec3>& outline, double& x0, double& x1,
                   double& y0, double& y1) {
  if (outline.size() >= 3) {
    x0 = y0 = 1e300;
    x1 = y1 = -1e300;
    for (const Vec3& p : outline) {
      x0 = std::min(x0, p.x), x1 = std::max(x1, p.x), y0 = std::min(y0, p.y),
      y1 = std::max(y1, p.y);
    }
    return;
  }
  const double l = o.length > 0.0 ? o.length : 2.0 * std::max(o.radius, 0.5);
  const double wd = o.width > 0.0 ? o.width : 2.0 * std::max(o.radius, 0.5);
  x0 = -0.5 * l, x1 = 0.5 * l, y0 = -0.5 * wd, y1 = 0.5 * wd;
}

void object_frames(const xodr::Map& map, size_t r, const xodr::Object& o,
                   std::vector<Rigid>& frames, std::vector<double>& lengths) {
  if (o.repeats.empty()) {
    frames.push_back(object_frame(map, r, o.s, o.t, o.z_offset, o.hdg));
    lengths.push_back(0.0);
  }
  for (const auto& rep : o.repeats) {
    if (rep.distance > 0.0) {
      const int n = std::min(2000, static_cast<int>(rep.length / rep.distance) + 1);
      for (int i = 0; i < n; ++i) {
        const double f = rep.length > 0.0 ? i * rep.distance / rep.length : 0.0;
        frames.push_back(object_frame(map, r, rep.s + i * rep.distance,
                                      rep.t_start + f * (rep.t_end - rep.t_start),
                                      rep.z_offset_start, o.hdg));
        lengths.push_back(0.0);
      }
    } else {
      for (double s = rep.s; s < rep.s + rep.length - 0.05; s += 10.0) {
        const double l = std::min(10.0, rep.s + rep.length - s);
        const double f = rep.length > 0.0 ? (s - rep.s) / rep.length : 0.0;
        frames.push_back(object_frame(map, r, s, rep.t_start + f * (rep.t_end - rep.t_start),
                                      rep.z_offset_start, 0.0));
        lengths.push_back(l);
      }
    }
  }
}

namespace {

/// The paint of a RoadRunner stencil (CARLA's maps), laid along the object's heading (the way
/// its traffic reads it); `subtype` names the symbol. False for a stencil it does not know.
bool stencil_paint(const std::string& name, double length, double width,
                   std::vector<PaintPolygon>& out, std::string& subtype) {
  // CARLA's exporter writes the stencil's box with length and width swapped on some roads
  // (Town04: 1.96 x 2.58 m and 2.56 x 1.95 m for the same arrow), so the longer side is taken
  // along the heading, and a missing size falls back to a 2.5 x 1.5 m stencil.
  const double along = std::max(length, width) > 0.1 ? std::max(length, width) : 2.5;
  const double across = std::min(length, width) > 0.1 ? std::min(length, width) : 1.5;
  if (name == "Stencil_ArrowType4L" || name == "Stencil_ArrowType4R") {
    const bool left = name.back() == 'L';
    // The box holds the lane's whole width on some roads (3.06 x 3.15 m); a turn arrow's bend
    // reaches at most 0.6 of its length across, as the stencil's own drawing does.
    out = arrow_symbol(left ? ArrowShape::kLeft : ArrowShape::kRight, along,
                       std::min(across, 0.6 * along));
    subtype = left ? "arrow_left" : "arrow_right";
    return true;
  }
  if (name.rfind("Stencil_ArrowType1", 0) == 0) {
    out = arrow_symbol(ArrowShape::kStraight, along, across);
    subtype = "arrow_straight";
    return true;
  }
  if (name == "Stencil_STOP") {
    subtype = "text";
    return text_symbol("STOP", along, across, out);
  }
  return false;
}

/// A line of short dashes along `line` (points in the object frame, in order): dashes
/// `dash` metres long every `dash + gap` metres of the line's length, `width` wide, 1.2 cm above
/// it; each dash follows the line's bends (sizes per style: kRoadRunnerDashes).
void dash_line(MeshBuilder& b, const std::vector<Vec3>& line, double dash, double gap,
               double width) {
  std::vector<double> at(line.size(), 0.0);  // length along the line at each point
  for (size_t i = 1; i < line.size(); ++i) {
    at[i] = at[i - 1] + std::hypot(line[i].x - line[i - 1].x, line[i].y - line[i - 1].y);
  }
  auto point_at = [&](size_t i, double d) {
    const double f = at[i + 1] > at[i] ? (d - at[i]) / (at[i + 1] - at[i]) : 0.0;
    return line[i] + (line[i + 1] - line[i]) * f;
  };
  const double total = line.empty() ? 0.0 : at.back();
  // Centred on the line's length, so both ends keep the same margin.
  const int count = static_cast<int>((total + gap) / (dash + gap));
  const double start = 0.5 * (total - (count * (dash + gap) - gap));
  const Vec3 lift{0.0, 0.0, 0.012};
  for (int k = 0; k < count; ++k) {
    const double d0 = start + k * (dash + gap), d1 = d0 + dash;
    for (size_t i = 0; i + 1 < line.size(); ++i) {
      const double a = std::max(d0, at[i]), c = std::min(d1, at[i + 1]);
      if (c <= a) {
        continue;
      }
      const Vec3 p = point_at(i, a), q = point_at(i, c);
      const Vec3 along = normalized(line[i + 1] - line[i]);
      const Vec3 n{-along.y * 0.5 * width, along.x * 0.5 * width, 0.0};
      b.polygon({p - n + lift, q - n + lift, q + n + lift, p + n + lift}, {});
    }
  }
}

/// The error for an object `size` metres long (a repeat's length, an outline's or box's extent)
/// that no road holds, or none: crosswalk stripes every metre and stretched repeats every 10 m
/// were laid out along it (a crosswalk or repeat 1e17 m long ran out of memory, exit 3). Longer
/// than the longest road OpenDRIVE input may have (1,000 km) is an error at the object.
std::optional<Diagnostic> object_beyond_sensor_world(const std::string& file, const xodr::Object& o,
                                                     const char* what, double size) {
  constexpr double kMaxObjectSize = 1e6;
  if (size <= kMaxObjectSize) {
    return std::nullopt;
  }
  return make_error(file, o.line,
                    "object '" + clip(o.id) + "': " + what + " is " + format_significant(size, 4) +
                        " m long; no road holds an object longer than 1,000 km");
}

/// The error for an object whose repeat, outline or box is longer than any road (see
/// object_beyond_sensor_world), checked before any of it is laid out.
std::optional<Diagnostic> oversized_object(const xodr::Map& map, size_t road,
                                           const xodr::Object& o) {
  const std::string& file = map.data().source_file;
  for (const xodr::ObjectRepeat& rep : o.repeats) {
    if (auto oversized = object_beyond_sensor_world(file, o, "a repeat", rep.length)) {
      return oversized;
    }
  }
  if (o.outlines.empty()) {
    return object_beyond_sensor_world(file, o, "its box", std::max(o.length, o.width));
  }
  const std::vector<Vec3> outline = outline_points(
      map, road, o.outlines.front(), object_frame(map, road, o.s, o.t, o.z_offset, o.hdg));
  double x0, x1, y0, y1;
  object_extent(o, outline, x0, x1, y0, y1);
  return object_beyond_sensor_world(file, o, "its outline", std::max(x1 - x0, y1 - y0));
}

/// One copy of an object (one per repeat step; one without repeats) in its own frame.
struct ObjectCopy {
  const xodr::Object& object;
  std::string type;  ///< the object's type in lower case
  size_t index = 0;  ///< which copy: the random stream of a plant
  Rigid frame;
  double stretch = 0.0;       ///< m along the road of a stretched repeat's copy; 0 for the others
  std::vector<Vec3> outline;  ///< the first outline in the frame; empty without one
  /// The outline's or the box's extent in the frame, m.
  double x0 = 0.0;
  double x1 = 0.0;
  double y0 = 0.0;
  double y1 = 0.0;
  double height = 0.0;  ///< m; 0 when the object gives none

  std::string name() const { return "object " + object.id; }
};

ObjectCopy object_copy(const xodr::Map& map, size_t road, const xodr::Object& o, size_t index,
                       const Rigid& frame, double stretch) {
  std::vector<Vec3> outline;
  if (!o.outlines.empty()) {
    outline = outline_points(map, road, o.outlines.front(), frame);
  }
  double x0, x1, y0, y1;
  object_extent(o, outline, x0, x1, y0, y1);
  return {.object = o,
          .type = to_lower(o.type),
          .index = index,
          .frame = frame,
          .stretch = stretch,
          .outline = std::move(outline),
          .x0 = x0,
          .x1 = x1,
          .y0 = y0,
          .y1 = y1,
          .height = o.height > 0.0 ? o.height : 0.0};
}

/// Zebra stripes 0.5 m wide, 0.5 m apart, across the walking direction (the long side).
void paint_crosswalk(MeshBuilder& b, const ObjectCopy& c) {
  b.semantic(SemanticClass::kLaneMarking).material(road_paint());
  const bool along_x = (c.x1 - c.x0) >= (c.y1 - c.y0);
  const double a0 = along_x ? c.x0 : c.y0, a1 = along_x ? c.x1 : c.y1;
  for (double a = a0 + 0.25; a + 0.5 <= a1 - 0.1; a += 1.0) {
    if (along_x) {
      paint_rect(b, a, a + 0.5, c.y0 + 0.1, c.y1 - 0.1);
    } else {
      paint_rect(b, c.x0 + 0.1, c.x1 - 0.1, a, a + 0.5);
    }
  }
}

/// A parking space's outline (or box) painted as a 12 cm line.
void paint_parking_space(MeshBuilder& b, const ObjectCopy& c) {
  b.semantic(SemanticClass::kLaneMarking).material(road_paint());
  const std::vector<Vec3> ring =
      c.outline.size() >= 3
          ? c.outline
          : std::vector<Vec3>{{c.x0, c.y0, 0}, {c.x1, c.y0, 0}, {c.x1, c.y1, 0}, {c.x0, c.y1, 0}};
  for (size_t i = 0; i < ring.size(); ++i) {
    const Vec3 a = ring[i];
    const Vec3 e = ring[(i + 1) % ring.size()];
    const Vec3 d = normalized(e - a);
    const Vec3 n{-d.y * 0.06, d.x * 0.06, 0.0};
    b.polygon({a - n + Vec3{0, 0, 0.012}, e - n + Vec3{0, 0, 0.012}, e + n + Vec3{0, 0, 0.012},
               a + n + Vec3{0, 0, 0.012}},
              {});
  }
}

/// Paint whose outline is its shape (§13.3: stop lines, arrows, symbols; the NGII import writes
/// B2 stop lines and B3 arrows so), or else the object's box; labelled by its subtype.
void paint_road_mark(WorldBuild& w, MeshBuilder& b, const ObjectCopy& c, ObjectInfo& info) {
  const xodr::Object& o = c.object;
  b.semantic(SemanticClass::kLaneMarking).material(road_paint());
  std::vector<Vec3> ring = c.outline;
  for (Vec3& p : ring) {
    p.z += 0.012;  // 1.2 cm above the surface, as lane marks
  }
  if (ring.size() < 3 || !b.filled_ring(ring)) {
    if (ring.size() >= 3) {
      w.diagnostics.add_once(
          "object-roadmark-outline",
          make_warning(w.map.data().source_file, o.line,
                       "road mark object " + o.id +
                           ": its outline crosses itself; its bounding box is painted"));
    }
    paint_rect(b, c.x0, c.x1, c.y0, c.y1);
  }
  info.kind = to_lower(o.subtype) == "stopline" ? "stop_line" : "road_mark";
  info.type = o.subtype;
}

/// A stop line across the lanes: CARLA gives the line's length across them and no width, so it
/// is 0.4 m wide.
void paint_stop_line(MeshBuilder& b, const ObjectCopy& c) {
  b.semantic(SemanticClass::kLaneMarking).material(road_paint());
  const double half = std::max(0.2, 0.5 * (c.y1 - c.y0));
  const double across = std::max(c.x1 - c.x0, 1.0);
  paint_rect(b, -0.5 * across, 0.5 * across, -std::min(half, 0.2), std::min(half, 0.2));
}

/// A galvanised pole of the object's radius (4-15 cm, 6 cm when none) and height (3 m when
/// none).
void build_pole(MeshBuilder& b, const ObjectCopy& c) {
  b.semantic(SemanticClass::kPole)
      .material(materials::metal("galvanised steel", linear_rgb(150, 152, 150), 0.45));
  const double r0 = std::max(0.04, std::min(0.15, c.object.radius > 0.0 ? c.object.radius : 0.06));
  b.tube({0, 0, 0}, {0, 0, c.height > 0.2 ? c.height : 3.0}, r0, r0 * 0.8, 8, true);
}

/// A street light of the object's height (7.5 m when it gives none or a low one).
void place_street_lamp(WorldBuild& w, const ObjectCopy& c) {
  const double height = c.height > 2.0 ? c.height : 7.5;
  w.place(make_street_light(height, 1.5), c.frame, c.name(), kind_info("street_light"));
  w.lamp_heads.push_back(c.frame.apply(street_lamp_head(height, 1.5)));
  ++w.report.objects;
}

/// A tree (8 m when no height is given) or a bush as wide as the object, its look drawn from
/// the copy's own stream.
void place_plant(WorldBuild& w, const ObjectCopy& c) {
  RandomStream rng(
      derive_seed(w.options.seed, "object " + c.object.id + "#" + std::to_string(c.index)));
  const ArticulatedMesh m = c.type == "tree" ? make_tree(rng, c.height > 1.0 ? c.height : 8.0, true,
                                                         w.lamp_clearances(c.frame, 5.0))
                                             : make_bush(rng, std::max(0.8, c.x1 - c.x0));
  w.place(m, c.frame, c.name(), kind_info(c.type));
  ++w.report.objects;
}

/// The copy's length along its frame's x: a stretched repeat's step, or the object's extent
/// (at least 0.3 m).
double rail_length(const ObjectCopy& c) {
  return c.stretch > 0.0 ? c.stretch : std::max(c.x1 - c.x0, 0.3);
}

/// A noise barrier: a 20 cm wall, 3 m high when no height is given.
void build_sound_barrier(MeshBuilder& b, const ObjectCopy& c) {
  b.semantic(SemanticClass::kWall)
      .material(materials::plain("noise barrier", linear_rgb(120, 130, 125), 0.8));
  b.box({0, -0.1, 0}, {rail_length(c), 0.1, c.height > 0.5 ? c.height : 3.0});
}

/// A guard rail, railing or barrier (or a fence) from the copy's start along its length.
void place_rail(WorldBuild& w, const ObjectCopy& c) {
  const ArticulatedMesh m = make_rail(rail_length(c), c.type == "fence");
  const Rigid start = c.frame * rigid_from_pose(c.stretch > 0.0 ? 0.0 : c.x0, 0, 0, 0, 0, 0);
  w.place(m, start, c.name(), kind_info(c.type == "fence" ? "fence" : "guard_rail"));
  ++w.report.objects;
}

/// A building (a facade pattern drawn from its id; 10 m high when no height is given) or a
/// concrete obstacle, island or gantry (1 m): the outline extruded, or the box.
void build_block(MeshBuilder& b, const ObjectCopy& c) {
  const bool building = c.type == "building";
  b.semantic(building ? SemanticClass::kBuilding : SemanticClass::kStatic);
  Material m = building ? materials::plain("facade", linear_rgb(180, 170, 150), 0.85)
                        : materials::plain("obstacle concrete", linear_rgb(150, 148, 140), 0.9);
  if (building) {
    m.pattern = Pattern::kFacade;
    m.pattern_scale = 3.2;
    m.params = {3.0, 0.5, 0.45, 4.0};
    m.seed = static_cast<uint32_t>(stable_hash(c.object.id));
  }
  b.material(m);
  const double h = c.height > 0.0 ? c.height : (building ? 10.0 : 1.0);
  if (c.outline.size() >= 3) {
    std::vector<std::vector<Vec3>> rings(2);
    for (const Vec3& p : c.outline) {
      rings[0].push_back(p);
      rings[1].push_back(p + Vec3{0, 0, h});
    }
    b.loft(rings, true);
  } else {
    b.box({c.x0, c.y0, 0}, {c.x1, c.y1, h});
  }
}

/// CARLA's "Speed_NN": a round speed-limit sign (German 274) beside the road, turned to face
/// the traffic of its lane.
void place_speed_sign(WorldBuild& w, const ObjectCopy& c) {
  const xodr::Object& o = c.object;
  const auto speed = parse_int(o.name.substr(6));
  SignFace f;
  f.shape = SignShape::kCircle;
  f.fill = linear_rgb(236, 236, 232);
  f.border = linear_rgb(196, 22, 28);
  f.border_width = 0.17;
  f.symbol = SignSymbol::kNumber;
  f.number = speed ? static_cast<int>(*speed) : 0;
  ObjectInfo sign = kind_info("traffic_sign");
  sign.type = "274";
  if (speed) {
    sign.value = static_cast<double>(*speed);
  }
  const Rigid turned = c.frame * rigid_from_pose(0, 0, 0, o.orientation == "-" ? 0.0 : kPi, 0, 0);
  w.place(make_sign(f, 0.6, 0.6, 2.0, "sign DE 274 " + std::to_string(f.number)), turned, c.name(),
          sign);
  ++w.report.signs;
}

/// A RoadRunner dashed line: the outline is the line (open, in order); without one, the
/// object's length along its heading. Nothing when not one dash fits.
void place_roadrunner_dashes(WorldBuild& w, const ObjectCopy& c, const RoadRunnerDashStyle& style) {
  MeshBuilder b;
  b.semantic(SemanticClass::kLaneMarking)
      .material(style.yellow ? yellow_road_paint() : road_paint());
  std::vector<Vec3> line = c.outline;
  if (line.size() < 2) {
    const double l = std::max(c.object.length, 0.0);
    line = {{-0.5 * l, 0.0, 0.0}, {0.5 * l, 0.0, 0.0}};
  }
  dash_line(b, line, style.dash, style.gap, style.width);
  if (b.triangle_count() == 0) {
    return;
  }
  ObjectInfo info = kind_info("road_mark");
  info.type = c.object.name;
  info.subtype = style.subtype;
  w.place_paint(b.take(), c.frame, c.name(), info);
  ++w.report.objects;
}

/// A RoadRunner stencil (CARLA's maps); false, placing nothing, for one it does not know.
bool place_stencil(WorldBuild& w, const ObjectCopy& c) {
  const xodr::Object& o = c.object;
  std::vector<PaintPolygon> symbol;
  ObjectInfo info = kind_info(c.type);
  if (!stencil_paint(o.name, o.length, o.width, symbol, info.subtype)) {
    return false;
  }
  MeshBuilder b;
  b.semantic(SemanticClass::kLaneMarking).material(road_paint());
  add_paint(b, symbol);
  info.kind = "road_mark";
  info.type = o.name;
  info.text = info.subtype == "text" ? "STOP" : "";
  w.place_paint(b.take(), c.frame, c.name(), info);
  ++w.report.objects;
  return true;
}

/// How the mesh a copy was built into goes into the world.
enum class ObjectMeshUse {
  kPaint,  ///< painted on the road (place_paint)
  kSolid,  ///< a solid (place)
  kDone,   ///< placed (or left out) already: nothing built
};

/// Builds one copy into `b` and `info` (kind: the type, until its kind says otherwise), or
/// places it whole, by its type (or, for CARLA's untyped objects, its name); warns once for a
/// kind it does not draw.
ObjectMeshUse build_object_copy(WorldBuild& w, const ObjectCopy& c, MeshBuilder& b,
                                ObjectInfo& info) {
  const std::string& type = c.type;
  const std::string& name = c.object.name;
  const bool untyped = c.object.type == "-1";
  if (type == "crosswalk") {
    paint_crosswalk(b, c);
    return ObjectMeshUse::kPaint;
  }
  if (type == "parkingspace") {
    paint_parking_space(b, c);
    return ObjectMeshUse::kPaint;
  }
  if (type == "roadmark") {
    paint_road_mark(w, b, c, info);
    return ObjectMeshUse::kPaint;
  }
  if (name == "StopLine" || type == "stopline") {
    paint_stop_line(b, c);
    info.kind = "stop_line";
    return ObjectMeshUse::kPaint;
  }
  if (type == "streetlamp") {
    place_street_lamp(w, c);
    return ObjectMeshUse::kDone;
  }
  if (type == "pole" || type == "guide-post" || type == "rail-pole") {
    build_pole(b, c);
    return ObjectMeshUse::kSolid;
  }
  if (type == "tree" || type == "vegetation") {
    place_plant(w, c);
    return ObjectMeshUse::kDone;
  }
  if (type == "soundbarrier") {
    build_sound_barrier(b, c);
    return ObjectMeshUse::kSolid;
  }
  if (type == "barrier" || type == "guardrail" || type == "railing" || type == "fence") {
    place_rail(w, c);
    return ObjectMeshUse::kDone;
  }
  if (type == "building" || type == "obstacle" || type == "trafficisland" || type == "gantry") {
    build_block(b, c);
    return ObjectMeshUse::kSolid;
  }
  if (name.rfind("Speed_", 0) == 0 || name.rfind("speed_", 0) == 0) {
    place_speed_sign(w, c);
    return ObjectMeshUse::kDone;
  }
  if (const RoadRunnerDashStyle* style = roadrunner_dash_style(name); untyped && style) {
    place_roadrunner_dashes(w, c, *style);
    return ObjectMeshUse::kDone;
  }
  if (untyped && place_stencil(w, c)) {
    return ObjectMeshUse::kDone;
  }
  w.diagnostics.add_once(
      "object-type:" + c.object.type + ":" + (untyped ? name : ""),
      make_warning(w.map.data().source_file, c.object.line,
                   "object type '" + c.object.type + "' (name '" + name + "') is not drawn"));
  return ObjectMeshUse::kDone;
}

/// Every copy of one object (its repeats), each placed as its kind says.
void draw_object(WorldBuild& w, size_t road, const xodr::Object& o) {
  std::vector<Rigid> frames;
  std::vector<double> lengths;  // stretched repeats: the length along the road
  object_frames(w.map, road, o, frames, lengths);
  for (size_t k = 0; k < frames.size(); ++k) {
    const ObjectCopy c = object_copy(w.map, road, o, k, frames[k], lengths[k]);
    MeshBuilder b;
    ObjectInfo info = kind_info(c.type);
    const ObjectMeshUse use = build_object_copy(w, c, b, info);
    if (use == ObjectMeshUse::kDone || b.triangle_count() == 0) {
      continue;
    }
    if (use == ObjectMeshUse::kPaint) {
      w.place_paint(b.take(), c.frame, c.name(), info);
    } else {
      w.place(b.take(), c.frame, c.name(), info);
    }
    ++w.report.objects;
  }
}

}  // namespace

void build_objects(WorldBuild& w) {
  std::vector<Diagnostic> refused;
  for (size_t r = 0; r < w.map.road_count(); ++r) {
    for (const xodr::Object& o : w.map.road(r).objects) {
      if (auto oversized = oversized_object(w.map, r, o)) {
        refused.push_back(*oversized);  // every such object named in one pass
        continue;
      }
      draw_object(w, r, o);
    }
  }
  if (!refused.empty()) {
    throw InputError(std::move(refused));
  }
}

}  // namespace corsa::sensors::detail
