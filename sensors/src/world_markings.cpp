// OpenDRIVE signals that are paint on the road rather than posts. OpenDRIVE 1.8 §14 lets a
// signal stand for a road marking. The German StVO catalogue (also CARLA's country "OpenDRIVE"
// and VIRES' sample maps) numbers the markings 293-299 and 340-341. Drawn: 293
// Fussgaengerueberweg (zebra bars 0.5 m wide and 0.5 m apart, 4 m along the road), 294 Haltlinie
// (a stop line 0.5 m wide) and 341 Wartelinie (a give-way line 0.5 m wide, dashes 0.5 m long with
// 0.25 m gaps; dimensions of the German RMS). The Korean road traffic safety signs number the
// road surface markings 501-549 (Enforcement Rule of the Road Traffic Act, annex 6, part 5;
// maps with country "KR"/"KOR", such as OpenDRIVE made from NGII data). Drawn: 530 stop line
// (30-60 cm wide: 0.45 m), 532 and 533 crosswalk and raised crosswalk (zebra, at least 4 m along
// the road), 529 crosswalk ahead (a hollow diamond 1.35 m wide with 2.5 m sides, per lane), the
// direction arrows 537-541 (straight, left, right, straight and left, straight and right; one
// per lane, pointing the lane's way) and, when the signal gives its length and width, the
// hatched areas 524 (no-stopping zone: yellow, cross-hatched) and 531 (safety zone: white,
// diagonal stripes), and the words 519 slow (천천히) and 521 stop (정지) in Hangul, one per lane.
// Lane markings lie across the lanes the signal covers: its <validity> lanes (§14.2), or else
// the drivable lanes its orientation serves ("+": the lanes carrying traffic towards +s; a
// crosswalk spans every drivable lane). The signal's `length` (1.8), when given, is the paint's
// extent along the road. The other markings (lines, other words and symbols) are left out with one
// warning per type: a road's lanes draw their lines already.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "corsa/core/strings.h"
#include "road_symbols.h"
#include "world_build.h"
#include "world_props.h"

namespace corsa::sensors::detail {
namespace {

enum class MarkKind { kCrosswalk, kStopLine, kGiveWayLine, kCrosswalkAhead, kArrow, kHatch, kWord };

struct MarkSpec {
  MarkKind kind;
  double along;  ///< m along the road when the signal gives no length
  const char* label;
  ArrowShape arrow = ArrowShape::kStraight;  ///< kArrow
  bool yellow = false;                       ///< kHatch: yellow paint, cross-hatched
  const char32_t* word = nullptr;            ///< kWord: its Hangul syllables
  const char* text = "";                     ///< kWord: the same word in UTF-8, for its labels
};

std::optional<MarkSpec> german_marking(const std::string& type) {
  if (type == "293") {
    return MarkSpec{MarkKind::kCrosswalk, 4.0, "crosswalk"};
  }
  if (type == "294") {
    return MarkSpec{MarkKind::kStopLine, 0.5, "stop_line"};
  }
  if (type == "341") {
    return MarkSpec{MarkKind::kGiveWayLine, 0.5, "give_way_line"};
  }
  return std::nullopt;
}

bool other_german_marking(const std::string& type) {
  const auto n = parse_int(type);
  return n && ((*n >= 295 && *n <= 299) || *n == 340);
}

/// Korean road surface markings (annex 6, part 5 of the Road Traffic Act's rule).
std::optional<MarkSpec> korean_marking(const std::string& type) {
  if (type == "530") {
    return MarkSpec{MarkKind::kStopLine, 0.45, "stop_line"};
  }
  if (type == "532" || type == "533") {
    return MarkSpec{MarkKind::kCrosswalk, 4.0, "crosswalk"};
  }
  if (type == "529") {
    return MarkSpec{MarkKind::kCrosswalkAhead, 2.0 * std::sqrt(2.5 * 2.5 - 0.675 * 0.675),
                    "crosswalk_ahead"};
  }
  // Direction arrows, 5 m long (the rule's urban size; 6 m on fast roads is the signal's length).
  constexpr std::pair<const char*, ArrowShape> kArrows[] = {
      {"537", ArrowShape::kStraight},      {"538", ArrowShape::kLeft},
      {"539", ArrowShape::kRight},         {"540", ArrowShape::kStraightLeft},
      {"541", ArrowShape::kStraightRight},
  };
  for (const auto& [code, shape] : kArrows) {
    if (type == code) {
      return MarkSpec{MarkKind::kArrow, 5.0, "arrow", shape};
    }
  }
  // Words, 4 m along the road: 519 slow reads 천천히 ("slowly"), 521 stop reads 정지 ("stop").
  if (type == "519") {
    return MarkSpec{.kind = MarkKind::kWord,
                    .along = 4.0,
                    .label = "text",
                    .word = U"\uCC9C\uCC9C\uD788",
                    .text = "천천히"};
  }
  if (type == "521") {
    return MarkSpec{.kind = MarkKind::kWord,
                    .along = 4.0,
                    .label = "text",
                    .word = U"\uC815\uC9C0",
                    .text = "정지"};
  }
  if (type == "524" || type == "531") {
    return MarkSpec{MarkKind::kHatch, 0.0, type == "524" ? "no_stopping_zone" : "safety_zone",
                    ArrowShape::kStraight, type == "524"};
  }
  return std::nullopt;
}

/// What a Korean marking number Corsa does not paint stands for, where the annex's name is
/// confirmed (520 slow, 542 unprotected left turn, 543 lane change: their drawings were not
/// confirmed, so they are not guessed); empty for the others.
std::string korean_marking_name(const std::string& type) {
  constexpr std::pair<const char*, const char*> kNames[] = {
      {"520", "slow"}, {"542", "unprotected left turn"}, {"543", "lane change"}};
  for (const auto& [code, name] : kNames) {
    if (type == code) {
      return name;
    }
  }
  return {};
}

/// True for the other numbers of the Korean marking series (lines, arrows, text, areas), which
/// are paint too and never a sign on a post.
bool other_korean_marking(const std::string& type) {
  const auto n = parse_int(type);
  return n && *n >= 500 && *n <= 599;
}

/// True when the marking covers the lane: one of its validity ranges holds it, or (without
/// validities) it is a drivable or biking lane that its orientation serves.
bool covers(const xodr::Signal& s, const xodr::Lane& lane, bool left_hand, bool every_side) {
  if (lane.id == 0) {
    return false;
  }
  if (!s.validities.empty()) {
    return std::any_of(s.validities.begin(), s.validities.end(), [&](const xodr::LaneValidity& v) {
      return lane.id >= std::min(v.from_lane, v.to_lane) &&
             lane.id <= std::max(v.from_lane, v.to_lane);
    });
  }
  if (!xodr::is_drivable(lane.type) && lane.type != xodr::LaneType::kBiking) {
    return false;
  }
  if (every_side || (s.orientation != "+" && s.orientation != "-")) {
    return true;
  }
  // Right-hand traffic drives towards +s on the right lanes (negative ids), left-hand traffic on
  // the left ones.
  const bool towards_plus_s = (lane.id < 0) != left_hand;
  return (s.orientation == "+") == towards_plus_s;
}

/// The largest extent (m) a marking painted from a signal takes across the road, and a hatched
/// area or painted symbol along it: far beyond any real marking, it keeps a wild size from
/// painting (and counting) without end.
constexpr double kMaxMarkingExtent = 50.0;

/// `value` (m, a signal's `what`) capped at kMaxMarkingExtent, with a located warning when it
/// was more.
double capped_marking_extent(WorldBuild& w, const xodr::Signal& s, double value, const char* what) {
  if (value <= kMaxMarkingExtent) {
    return value;
  }
  w.diagnostics.add_once(
      std::string("signal-marking-extent:") + what + ":" + s.id,
      make_warning(w.map.data().source_file, s.line,
                   "road marking signal " + s.id + " (type '" + s.type + "'): its " + what + " " +
                       format_double(value) + " m is more than " +
                       format_fixed(kMaxMarkingExtent, 0) + " m; painted " +
                       format_fixed(kMaxMarkingExtent, 0) + " m"));
  return kMaxMarkingExtent;
}

/// Paints flat quads given in road coordinates (s along, t across) into a mesh in `frame`.
class RoadPainter {
 public:
  RoadPainter(const xodr::Map& map, size_t road, const Rigid& frame)
      : map_(map), road_(road), back_(frame.inverse()) {
    b_.semantic(SemanticClass::kLaneMarking).material(road_paint());
  }
  void quad(double s0, double s1, double t0, double t1) {
    if (t1 - t0 < 0.01 || s1 - s0 < 0.01) {
      return;
    }
    b_.polygon({at(s0, t0), at(s1, t0), at(s1, t1), at(s0, t1)}, {});
  }
  /// A convex polygon of (s, t) corners.
  void polygon(const std::vector<std::pair<double, double>>& corners) {
    std::vector<Vec3> points;
    for (const auto& [s, t] : corners) {
      points.push_back(at(s, t));
    }
    b_.polygon(points, {});
  }
  MeshBuilder& builder() { return b_; }

 private:
  Vec3 at(double s, double t) const {
    const xodr::WorldPose p = map_.world_pose(road_, s, t);
    return back_.apply({p.x, p.y, p.z + 0.012});  // 1.2 cm above the surface, as lane marks
  }
  const xodr::Map& map_;
  size_t road_;
  Rigid back_;
  MeshBuilder b_;
};

/// A hollow diamond (stroke 0.15 m) filling s0..s1 along the road and 1.35 m across, centred on
/// the lane t0..t1: the Korean crosswalk-ahead sign (120-150 cm wide, sides 2.5 m).
void paint_diamond(RoadPainter& paint, double s0, double s1, double t0, double t1) {
  const double sc = 0.5 * (s0 + s1), tc = 0.5 * (t0 + t1);
  const double half_l = 0.5 * (s1 - s0), half_w = std::min(0.675, 0.5 * (t1 - t0));
  const double stroke = 0.15;
  // The inner diamond is the outer one scaled so that every edge moves in by the stroke.
  const double inset = 1.0 - stroke * std::hypot(half_l, half_w) / (half_l * half_w);
  if (half_w < 0.3 || inset <= 0.0) {
    return;
  }
  const double ds[4] = {half_l, 0.0, -half_l, 0.0};
  const double dt[4] = {0.0, half_w, 0.0, -half_w};
  for (int i = 0; i < 4; ++i) {
    const int j = (i + 1) % 4;
    paint.polygon({{sc + ds[i], tc + dt[i]},
                   {sc + ds[j], tc + dt[j]},
                   {sc + inset * ds[j], tc + inset * dt[j]},
                   {sc + inset * ds[i], tc + inset * dt[i]}});
  }
}

/// A lane the marking covers: its borders (t0 < t1) and the way its traffic drives along s
/// (+1 or -1).
struct CoveredLane {
  double t0, t1;
  int dir;
  bool operator<(const CoveredLane& o) const { return t0 < o.t0; }
};

/// The part of a convex polygon on the side x >= cut (side +1) or x <= cut (side -1): convex,
/// counter-clockwise like it; fewer than 3 corners when nothing is left.
PaintPolygon clip_symbol_at_x(const PaintPolygon& polygon, double cut, int side) {
  PaintPolygon out;
  for (size_t i = 0; i < polygon.size(); ++i) {
    const Vec2 a = polygon[i], b = polygon[(i + 1) % polygon.size()];
    const double da = side * (a.x - cut), db = side * (b.x - cut);
    if (da >= 0.0) {
      out.push_back(a);
    }
    if ((da > 0.0 && db < 0.0) || (da < 0.0 && db > 0.0)) {
      const double f = da / (da - db);
      out.push_back({cut, a.y + f * (b.y - a.y)});
    }
  }
  return out;
}

/// Symbol polygons (x the lane's way, y to its left) painted centred on (s_mid, t_mid). The
/// road's frame bends with the road, so a polygon longer than kSymbolSlab along x is cut into
/// slabs of at most that length (each still convex), whose corners then follow a curve's lane
/// offsets to within millimetres (a 0.5 m chord at a 20 m radius is 1.6 mm off its arc).
void paint_symbol(RoadPainter& paint, const std::vector<PaintPolygon>& symbol, double s_mid,
                  double t_mid, int dir) {
  constexpr double kSymbolSlab = 0.5;
  std::vector<std::pair<double, double>> corners;
  auto paint_piece = [&](const PaintPolygon& piece) {
    corners.clear();
    for (const Vec2& p : piece) {
      corners.emplace_back(s_mid + dir * p.x, t_mid + dir * p.y);  // a half turn keeps winding
    }
    paint.polygon(corners);
  };
  for (const PaintPolygon& polygon : symbol) {
    double x_min = polygon.front().x, x_max = polygon.front().x;
    for (const Vec2& p : polygon) {
      x_min = std::min(x_min, p.x);
      x_max = std::max(x_max, p.x);
    }
    const int slabs = static_cast<int>(std::ceil((x_max - x_min) / kSymbolSlab - 1e-9));
    if (slabs <= 1) {
      paint_piece(polygon);
      continue;
    }
    const double step = (x_max - x_min) / slabs;
    for (int k = 0; k < slabs; ++k) {
      PaintPolygon piece = polygon;
      if (k > 0) {
        piece = clip_symbol_at_x(piece, x_min + k * step, 1);
      }
      if (k + 1 < slabs) {
        piece = clip_symbol_at_x(piece, x_min + (k + 1) * step, -1);
      }
      if (piece.size() >= 3) {
        paint_piece(piece);
      }
    }
  }
}

/// Paints the marking on one covered lane from s0 to s1; false when a word does not fit the
/// lane (every other marking is painted, or left out by its own rule, and returns true).
bool paint_span(RoadPainter& paint, const MarkSpec& spec, double s0, double s1,
                const CoveredLane& lane, double t_first) {
  const double t0 = lane.t0, t1 = lane.t1;
  if (spec.kind == MarkKind::kCrosswalkAhead) {
    paint_diamond(paint, s0, s1, t0, t1);
    return true;
  }
  if (spec.kind == MarkKind::kArrow) {
    // A straight arrow 0.9 m across (its head), a turning one 1.8 m, kept 0.3 m off the lines.
    const bool straight = spec.arrow == ArrowShape::kStraight;
    const double across = std::min(straight ? 0.9 : 1.8, t1 - t0 - 0.6);
    if (across > 0.3) {
      paint_symbol(paint, arrow_symbol(spec.arrow, s1 - s0, across), 0.5 * (s0 + s1),
                   0.5 * (t0 + t1), lane.dir);
    }
    return true;
  }
  if (spec.kind == MarkKind::kWord) {
    // Syllables at most 1 m wide with kHangulSyllableGap of one between them, kept 0.3 m off
    // the lines; at least 0.3 m wide, or the word is not painted in this lane.
    const std::u32string_view word(spec.word);
    const double n = static_cast<double>(word.size());
    const double across = std::min(n + kHangulSyllableGap * (n - 1.0), t1 - t0 - 0.6);
    if (across <= 0.3 * n) {
      return false;
    }
    std::vector<PaintPolygon> symbol;
    if (!hangul_symbol(word, s1 - s0, across, symbol)) {
      // The painted words are our constants: a syllable hangul_symbol lacks is our bug.
      throw std::logic_error("a painted road word uses a syllable hangul_symbol does not know");
    }
    paint_symbol(paint, symbol, 0.5 * (s0 + s1), 0.5 * (t0 + t1), lane.dir);
    return true;
  }
  if (spec.kind == MarkKind::kStopLine) {
    paint.quad(s0, s1, t0, t1);
    return true;
  }
  // Bars (crosswalk: 0.5 m every 1.0 m) or dashes (give-way line: 0.5 m every 0.75 m) laid out
  // from the first covered lane's edge, so that they run on across lane borders.
  const double bar = 0.5;
  const double period = spec.kind == MarkKind::kCrosswalk ? 1.0 : 0.75;
  // At most one bar per period of the lane's width (and two for the ends; no lane is wider
  // than kMaxMarkingExtent): counted, since a += period stops advancing where t is large.
  const double k0 = std::floor((t0 - t_first) / period);
  const double span = t1 - t0 <= kMaxMarkingExtent ? t1 - t0 : kMaxMarkingExtent;
  const auto bars = static_cast<int64_t>(std::ceil(span / period)) + 2;
  double a = t_first + k0 * period;
  for (int64_t k = 0; k < bars && a < t1; ++k, a += period) {
    paint.quad(s0, s1, std::max(a, t0), std::min(a + bar, t1));
  }
  return true;
}

/// The lanes a marking covers at s_mid (see covers()); a word covers no biking lane.
std::vector<CoveredLane> covered_lanes(const WorldBuild& w, size_t r, const xodr::Signal& s,
                                       const MarkSpec& spec, double s_mid) {
  const xodr::Road& road = w.map.road(r);
  const bool left_hand = road.rule == xodr::TrafficRule::kLeftHand;
  std::vector<xodr::LaneSpan> spans;
  w.map.lane_spans(r, s_mid, spans);
  const auto& lanes = road.lane_sections[w.map.section_index(r, s_mid)].lanes;
  std::vector<CoveredLane> covered;
  for (const xodr::LaneSpan& span : spans) {
    const auto lane = std::find_if(lanes.begin(), lanes.end(),
                                   [&](const xodr::Lane& l) { return l.id == span.id; });
    // Words speak to drivers: a biking lane gets none.
    const bool skipped = spec.kind == MarkKind::kWord && lane != lanes.end() &&
                         lane->type == xodr::LaneType::kBiking;
    if (lane != lanes.end() && !skipped && span.width() > 0.05 &&
        covers(s, *lane, left_hand, spec.kind == MarkKind::kCrosswalk)) {
      const bool towards_plus_s = (lane->id < 0) != left_hand;
      covered.push_back({span.t_min(), span.t_max(), towards_plus_s ? 1 : -1});
    }
  }
  std::sort(covered.begin(), covered.end());
  return covered;
}

/// Adds the painted marking as one labelled object (paint is stuff by its class, but a marking
/// painted from a signal is one object with labels, so it takes the next static id as props do).
void add_marking(WorldBuild& w, RoadPainter& paint, const Rigid& frame, const MarkSpec& spec,
                 const xodr::Signal& s) {
  if (paint.builder().triangle_count() == 0) {
    return;
  }
  ObjectInfo info = signal_info(s);
  info.kind = spec.label;
  info.text = spec.text;
  StaticMesh mesh = to_static_mesh(paint.builder().take(), frame, "road marking " + s.id);
  mesh.object = info;
  mesh.instance_id = kStaticInstanceBase + static_cast<uint32_t>(w.scene.static_mesh_count());
  w.scene.add_static_mesh(std::move(mesh));
  ++w.report.markings;
}

/// A hatched area of the signal's length and width, centred on its s and t along the road;
/// left out with a located warning when the signal gives no size.
void build_hatched_area(WorldBuild& w, size_t r, const xodr::Signal& s, const MarkSpec& spec) {
  const xodr::Road& road = w.map.road(r);
  if (s.length < 0.5 || s.width < 0.5) {
    w.diagnostics.add_once("signal-marking-size:" + s.country + ":" + s.type,
                           make_warning(w.map.data().source_file, s.line,
                                        "hatched area signal " + s.id + " (type '" + s.type +
                                            "') gives no length and width; left out"));
    return;
  }
  const double along = capped_marking_extent(w, s, std::min(s.length, road.length), "length");
  const double across = capped_marking_extent(w, s, s.width, "width");
  const double s_mid = std::clamp(s.s, 0.5 * along, road.length - 0.5 * along);
  const xodr::WorldPose p = w.map.world_pose(r, s_mid, 0.0);
  const Rigid frame = rigid_from_pose(p.x, p.y, p.z, p.h, 0.0, 0.0);
  RoadPainter paint(w.map, r, frame);
  if (spec.yellow) {
    paint.builder().material(yellow_road_paint());
  }
  // Stripes 0.3 m wide every 1.5 m (cross-hatched every 2 m), a 0.2 m border.
  paint_symbol(
      paint,
      hatch_symbol(along, across, spec.yellow ? 0.2 : 0.3, spec.yellow ? 2.0 : 1.5, spec.yellow),
      s_mid, s.t, 1);
  add_marking(w, paint, frame, spec, s);
}

}  // namespace

bool build_signal_marking(WorldBuild& w, size_t r, const xodr::Signal& s) {
  const std::string& file = w.map.data().source_file;
  const bool korean = is_korean(s.country);
  const std::optional<MarkSpec> spec = korean ? korean_marking(s.type) : german_marking(s.type);
  if (!spec) {
    if (!(korean ? other_korean_marking(s.type) : other_german_marking(s.type))) {
      return false;
    }
    const std::string name = korean ? korean_marking_name(s.type) : std::string();
    w.diagnostics.add_once(
        "signal-marking:" + s.country + ":" + s.type,
        make_warning(file, s.line,
                     "signal type '" + s.type + "' (country '" + s.country + "'" +
                         (name.empty() ? "" : ", " + name) +
                         ") is a road marking Corsa does not paint from a signal; left out"));
    return true;
  }
  if (spec->kind == MarkKind::kHatch) {
    build_hatched_area(w, r, s, *spec);
    return true;
  }
  const xodr::Road& road = w.map.road(r);
  double along = std::min(s.length > 0.01 ? s.length : spec->along, road.length);
  if (spec->kind == MarkKind::kWord || spec->kind == MarkKind::kArrow) {
    along = capped_marking_extent(w, s, along, "length");  // a symbol is cut every 0.5 m
  }
  // Centred on s, shifted to stay on the road (a stop line at a road's end, as maps put them).
  const double s0 = std::clamp(s.s - 0.5 * along, 0.0, road.length - along);
  const double s1 = s0 + along;
  const double s_mid = 0.5 * (s0 + s1);
  std::vector<CoveredLane> covered = covered_lanes(w, r, s, *spec, s_mid);
  if (covered.empty()) {
    const double width = s.width > 0.1 ? capped_marking_extent(w, s, s.width, "width") : 3.0;
    w.diagnostics.add_once("signal-marking-lanes:" + s.id,
                           make_warning(file, s.line,
                                        "road marking signal " + s.id + " covers no lane at s " +
                                            format_fixed(s_mid, 2) + "; painted " +
                                            format_fixed(width, 2) + " m wide around its t"));
    covered.push_back({s.t - 0.5 * width, s.t + 0.5 * width, s.orientation == "-" ? -1 : 1});
  }
  const xodr::WorldPose p = w.map.world_pose(r, s_mid, 0.0);
  const Rigid frame = rigid_from_pose(p.x, p.y, p.z, p.h, 0.0, 0.0);
  RoadPainter paint(w.map, r, frame);
  bool fits = false;
  for (const CoveredLane& lane : covered) {
    fits = paint_span(paint, *spec, s0, s1, lane, covered.front().t0) || fits;
  }
  if (!fits) {
    w.diagnostics.add_once("signal-marking-fit:" + s.id,
                           make_warning(file, s.line,
                                        "road marking signal " + s.id + " (type '" + s.type +
                                            "'): no lane it covers at s " + format_fixed(s_mid, 2) +
                                            " is wide enough for its word; left out"));
  }
  add_marking(w, paint, frame, *spec, s);
  return true;
}

}  // namespace corsa::sensors::detail
