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

}  // namespace

void build_objects(WorldBuild& w) {
  const xodr::Map& map = w.map;
  const std::string& file = map.data().source_file;
  std::vector<Diagnostic> refused;
  for (size_t r = 0; r < map.road_count(); ++r) {
    const xodr::Road& road = map.road(r);
    for (const xodr::Object& o : road.objects) {
      const std::string type = to_lower(o.type);
      const std::string name = o.name;
      std::optional<Diagnostic> oversized;
      for (const xodr::ObjectRepeat& rep : o.repeats) {
        oversized =
            oversized ? oversized : object_beyond_sensor_world(file, o, "a repeat", rep.length);
      }
      if (!oversized && !o.outlines.empty()) {
        const std::vector<Vec3> outline = outline_points(
            map, r, o.outlines.front(), object_frame(map, r, o.s, o.t, o.z_offset, o.hdg));
        double x0, x1, y0, y1;
        object_extent(o, outline, x0, x1, y0, y1);
        oversized = object_beyond_sensor_world(file, o, "its outline", std::max(x1 - x0, y1 - y0));
      } else if (!oversized) {
        oversized = object_beyond_sensor_world(file, o, "its box", std::max(o.length, o.width));
      }
      if (oversized) {
        refused.push_back(*oversized);  // every such object named in one pass
        continue;
      }
      std::vector<Rigid> frames;
      std::vector<double> lengths;  // stretched repeats: the length along the road
      object_frames(map, r, o, frames, lengths);
      for (size_t k = 0; k < frames.size(); ++k) {
        const Rigid& frame = frames[k];
        MeshBuilder b;
        ObjectInfo info;
        info.kind = type;
        std::vector<Vec3> outline;
        if (!o.outlines.empty()) {
          outline = outline_points(map, r, o.outlines.front(), frame);
        }
        double x0, x1, y0, y1;
        object_extent(o, outline, x0, x1, y0, y1);
        const double height = o.height > 0.0 ? o.height : 0.0;
        const bool paint = type == "crosswalk" || type == "parkingspace" || type == "roadmark" ||
                           type == "stopline" || name == "StopLine";
        if (type == "crosswalk") {
          // Zebra stripes 0.5 m wide, 0.5 m apart, across the walking direction (the long side).
          b.semantic(SemanticClass::kLaneMarking).material(road_paint());
          const bool along_x = (x1 - x0) >= (y1 - y0);
          const double a0 = along_x ? x0 : y0, a1 = along_x ? x1 : y1;
          for (double a = a0 + 0.25; a + 0.5 <= a1 - 0.1; a += 1.0) {
            if (along_x) {
              paint_rect(b, a, a + 0.5, y0 + 0.1, y1 - 0.1);
            } else {
              paint_rect(b, x0 + 0.1, x1 - 0.1, a, a + 0.5);
            }
          }
        } else if (type == "parkingspace") {
          b.semantic(SemanticClass::kLaneMarking).material(road_paint());
          std::vector<Vec3> ring =
              outline.size() >= 3
                  ? outline
                  : std::vector<Vec3>{{x0, y0, 0}, {x1, y0, 0}, {x1, y1, 0}, {x0, y1, 0}};
          for (size_t i = 0; i < ring.size(); ++i) {
            const Vec3 a = ring[i];
            const Vec3 c = ring[(i + 1) % ring.size()];
            const Vec3 d = normalized(c - a);
            const Vec3 n{-d.y * 0.06, d.x * 0.06, 0.0};
            b.polygon({a - n + Vec3{0, 0, 0.012}, c - n + Vec3{0, 0, 0.012},
                       c + n + Vec3{0, 0, 0.012}, a + n + Vec3{0, 0, 0.012}},
                      {});
          }
        } else if (type == "roadmark") {
          // Paint whose outline is its shape (§13.3: stop lines, arrows, symbols; the NGII
          // import writes B2 stop lines and B3 arrows so), or else the object's box.
          b.semantic(SemanticClass::kLaneMarking).material(road_paint());
          std::vector<Vec3> ring = outline;
          for (Vec3& p : ring) {
            p.z += 0.012;  // 1.2 cm above the surface, as lane marks
          }
          if (ring.size() < 3 || !b.filled_ring(ring)) {
            if (ring.size() >= 3) {
              w.diagnostics.add_once(
                  "object-roadmark-outline",
                  make_warning(file, o.line,
                               "road mark object " + o.id +
                                   ": its outline crosses itself; its bounding box is painted"));
            }
            paint_rect(b, x0, x1, y0, y1);
          }
          info.kind = to_lower(o.subtype) == "stopline" ? "stop_line" : "road_mark";
          info.type = o.subtype;
        } else if (name == "StopLine" || type == "stopline") {
          b.semantic(SemanticClass::kLaneMarking).material(road_paint());
          const double half = std::max(0.2, 0.5 * (y1 - y0));
          const double across = std::max(x1 - x0, 1.0);
          // CARLA gives the line's length across the lanes and no width: 0.4 m wide.
          paint_rect(b, -0.5 * across, 0.5 * across, -std::min(half, 0.2), std::min(half, 0.2));
          info.kind = "stop_line";
        } else if (type == "pole" || type == "streetlamp" || type == "guide-post" ||
                   type == "rail-pole") {
          if (type == "streetlamp") {
            const ArticulatedMesh m = make_street_light(height > 2.0 ? height : 7.5, 1.5);
            w.place(m, frame, "object " + o.id, kind_info("street_light"));
            ++w.report.objects;
            continue;
          }
          b.semantic(SemanticClass::kPole)
              .material(materials::metal("galvanised steel", linear_rgb(150, 152, 150), 0.45));
          const double r0 = std::max(0.04, std::min(0.15, o.radius > 0.0 ? o.radius : 0.06));
          b.tube({0, 0, 0}, {0, 0, height > 0.2 ? height : 3.0}, r0, r0 * 0.8, 8, true);
        } else if (type == "tree" || type == "vegetation") {
          RandomStream rng(derive_seed(w.options.seed, "object " + o.id + "#" + std::to_string(k)));
          const ArticulatedMesh m = type == "tree" ? make_tree(rng, height > 1.0 ? height : 8.0)
                                                   : make_bush(rng, std::max(0.8, x1 - x0));
          w.place(m, frame, "object " + o.id, kind_info(type));
          ++w.report.objects;
          continue;
        } else if (type == "barrier" || type == "guardrail" || type == "railing" ||
                   type == "soundbarrier" || type == "fence") {
          const double l = lengths[k] > 0.0 ? lengths[k] : std::max(x1 - x0, 0.3);
          if (type == "soundbarrier") {
            b.semantic(SemanticClass::kWall)
                .material(materials::plain("noise barrier", linear_rgb(120, 130, 125), 0.8));
            b.box({0, -0.1, 0}, {l, 0.1, height > 0.5 ? height : 3.0});
          } else {
            const ArticulatedMesh m = make_rail(l, type == "fence");
            const Rigid start = frame * rigid_from_pose(lengths[k] > 0.0 ? 0.0 : x0, 0, 0, 0, 0, 0);
            w.place(m, start, "object " + o.id,
                    kind_info(type == "fence" ? "fence" : "guard_rail"));
            ++w.report.objects;
            continue;
          }
        } else if (type == "building" || type == "obstacle" || type == "trafficisland" ||
                   type == "gantry") {
          const bool building = type == "building";
          b.semantic(building ? SemanticClass::kBuilding : SemanticClass::kStatic);
          Material m = building
                           ? materials::plain("facade", linear_rgb(180, 170, 150), 0.85)
                           : materials::plain("obstacle concrete", linear_rgb(150, 148, 140), 0.9);
          if (building) {
            m.pattern = Pattern::kFacade;
            m.pattern_scale = 3.2;
            m.params = {3.0, 0.5, 0.45, 4.0};
            m.seed = static_cast<uint32_t>(stable_hash(o.id));
          }
          b.material(m);
          const double h = height > 0.0 ? height : (building ? 10.0 : 1.0);
          if (outline.size() >= 3) {
            std::vector<std::vector<Vec3>> rings(2);
            for (const Vec3& p : outline) {
              rings[0].push_back(p);
              rings[1].push_back(p + Vec3{0, 0, h});
            }
            b.loft(rings, true);
          } else {
            b.box({x0, y0, 0}, {x1, y1, h});
          }
        } else if (name.rfind("Speed_", 0) == 0 || name.rfind("speed_", 0) == 0) {
          const auto speed = parse_int(name.substr(6));
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
          // Beside the road: turned to face the traffic of its lane.
          const Rigid turned =
              frame * rigid_from_pose(0, 0, 0, o.orientation == "-" ? 0.0 : kPi, 0, 0);
          w.place(make_sign(f, 0.6, 0.6, 2.0, "sign DE 274 " + std::to_string(f.number)), turned,
                  "object " + o.id, sign);
          ++w.report.signs;
          continue;
        } else if (const RoadRunnerDashStyle* style = roadrunner_dash_style(name);
                   o.type == "-1" && style != nullptr) {
          // The outline is the line (open, in order); without one, the object's length along
          // its heading.
          b.semantic(SemanticClass::kLaneMarking)
              .material(style->yellow ? yellow_road_paint() : road_paint());
          std::vector<Vec3> line = outline;
          if (line.size() < 2) {
            const double l = std::max(o.length, 0.0);
            line = {{-0.5 * l, 0.0, 0.0}, {0.5 * l, 0.0, 0.0}};
          }
          dash_line(b, line, style->dash, style->gap, style->width);
          if (b.triangle_count() == 0) {
            continue;
          }
          info.kind = "road_mark";
          info.type = name;
          info.subtype = style->subtype;
          w.place_paint(b.take(), frame, "object " + o.id, info);
          ++w.report.objects;
          continue;
        } else if (std::vector<PaintPolygon> symbol;
                   o.type == "-1" && stencil_paint(name, o.length, o.width, symbol, info.subtype)) {
          b.semantic(SemanticClass::kLaneMarking).material(road_paint());
          add_paint(b, symbol);
          info.kind = "road_mark";
          info.type = name;
          info.text = info.subtype == "text" ? "STOP" : "";
          w.place_paint(b.take(), frame, "object " + o.id, info);
          ++w.report.objects;
          continue;
        } else {
          w.diagnostics.add_once(
              "object-type:" + o.type + ":" + (o.type == "-1" ? name : ""),
              make_warning(file, o.line,
                           "object type '" + o.type + "' (name '" + name + "') is not drawn"));
          continue;
        }
        if (b.triangle_count() > 0 && paint) {
          w.place_paint(b.take(), frame, "object " + o.id, info);
          ++w.report.objects;
        } else if (b.triangle_count() > 0) {
          w.place(b.take(), frame, "object " + o.id, info);
          ++w.report.objects;
        }
      }
    }
  }
  if (!refused.empty()) {
    throw InputError(std::move(refused));
  }
}

}  // namespace corsa::sensors::detail
