#include "decorations.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <unordered_map>

#include "road_frame.h"
#include "signal_controllers.h"

namespace corsa::ngii::detail {
namespace {

/// A mark seen on one border of one road.
struct MarkPiece {
  size_t border = 0;  ///< 0: the centre lane's border; k: the outer border of lane -k
  double s0 = 0.0;
  double s1 = 0.0;
  std::string type;  ///< OpenDRIVE roadMark type
  std::string color;
  std::string lane_change;
  const SurfaceMark* mark = nullptr;
};

/// OpenDRIVE type, colour and laneChange of an NGII Type code (colour digit, single/double,
/// pattern: 1 solid, 2 dashed, 3 left dashed, 4 right dashed). `reversed` when the mark is
/// digitised against the road, which swaps left and right. Empty type for codes not mapped.
void map_type(const std::string& code, bool reversed, MarkPiece& piece) {
  if (code.size() != 3) {
    return;
  }
  piece.color = code[0] == '1' ? "yellow" : code[0] == '2' ? "white" : code[0] == '3' ? "blue" : "";
  const bool twin = code[1] == '2';
  char pattern = code[2];
  if (reversed && (pattern == '3' || pattern == '4')) {
    pattern = pattern == '3' ? '4' : '3';
  }
  if (piece.color.empty() || pattern < '1' || pattern > '4' || (code[1] != '1' && !twin)) {
    return;
  }
  if (pattern == '1') {
    piece.type = twin ? "solid solid" : "solid";
    piece.lane_change = "none";
  } else if (pattern == '2') {
    piece.type = twin ? "broken broken" : "broken";
    piece.lane_change = "both";
  } else {
    // Left dashed: the lane on the left (the higher id) may cross to the right (decrease).
    piece.type = pattern == '3' ? "broken solid" : "solid broken";
    piece.lane_change = pattern == '3' ? "decrease" : "increase";
  }
}

struct SignalCode {
  const char* type;
  const char* subtype;
};

/// OpenDRIVE signal type of an NGII C1 Type code, in the catalogue readers know with country
/// "OpenDRIVE" (the German VzKat numbers, as maliput, esmini and CARLA read them): 1000001 a
/// vehicle light, 1000011 arrow lights, 1000002 a pedestrian light, 1000013 a bicycle light.
SignalCode traffic_light_code(const std::string& ngii_type) {
  if (ngii_type == "4" || ngii_type == "6") {
    return {"1000011", "-1"};  // arrow three-colour lights
  }
  if (ngii_type == "11") {
    return {"1000002", "-1"};
  }
  if (ngii_type == "12" || ngii_type == "13") {
    return {"1000013", "-1"};
  }
  return {"1000001", "-1"};  // 1-3, 5, 7-10, 14, 15, 99: vehicle lights (4-colour ones too)
}

std::vector<Vec2> sample_points(const std::vector<Point3>& points, const Origin& origin) {
  std::vector<Vec2> out;
  const size_t step = std::max<size_t>(1, points.size() / 16);
  for (size_t i = 0; i < points.size(); i += step) {
    out.push_back(Vec2{points[i].x - origin.x, points[i].y - origin.y});
  }
  out.push_back(Vec2{points.back().x - origin.x, points.back().y - origin.y});
  return out;
}

class Decorator {
 public:
  Decorator(xodr::MapData& map, const std::vector<LinkPlacement>& placements, const Layers& layers,
            const Origin& origin, Diagnostics& diagnostics)
      : map_(map), layers_(layers), origin_(origin), diagnostics_(diagnostics) {
    for (size_t r = 0; r < map.roads.size(); ++r) {
      road_index_.emplace(map.roads[r].id, r);
    }
    for (const LinkPlacement& p : placements) {
      by_link_[p.link_id].push_back(&p);
    }
    frames_.resize(map.roads.size());
  }

  size_t road_marks() {
    std::vector<std::vector<MarkPiece>> pieces(map_.roads.size());
    for (const SurfaceMark& mark : layers_.marks) {
      if (mark.points.size() < 2) {
        continue;
      }
      for (const std::string* link : {&mark.right_link, &mark.left_link}) {
        if (!link->empty()) {
          place_mark(mark, *link, pieces);
        }
      }
    }
    size_t written = 0;
    for (size_t r = 0; r < map_.roads.size(); ++r) {
      written += write_marks(map_.roads[r], pieces[r]);
    }
    return written;
  }

  /// Tunnel and bridge records from the A2 RoadType of the links along each road (2 tunnel,
  /// 3 bridge, 4 underground road, 5 overpass; §13.13, §13.14): the s ranges of the lanes whose
  /// links have that type, merged per road.
  size_t structures() {
    std::unordered_map<std::string, const Link*> links;
    for (const Link& link : layers_.links) {
      links.emplace(link.id, &link);
    }
    // (road, kind) -> s intervals
    std::map<std::pair<size_t, char>, std::vector<std::pair<double, double>>> spans;
    for (const auto& [id, placements] : by_link_) {
      const auto it = links.find(id);
      if (it == links.end() || it->second->road_type.size() != 1) {
        continue;
      }
      const char kind = it->second->road_type[0];
      if (kind < '2' || kind > '5') {
        continue;
      }
      for (const LinkPlacement* p : placements) {
        spans[{road_index_.at(p->road_id), kind}].emplace_back(p->s_start, p->s_end);
      }
    }
    size_t made = 0;
    for (auto& [key, intervals] : spans) {
      std::sort(intervals.begin(), intervals.end());
      std::vector<std::pair<double, double>> merged;
      for (const auto& interval : intervals) {
        if (!merged.empty() && interval.first <= merged.back().second + 0.5) {
          merged.back().second = std::max(merged.back().second, interval.second);
        } else {
          merged.push_back(interval);
        }
      }
      xodr::Road& road = map_.roads[key.first];
      for (const auto& [s0, s1] : merged) {
        const std::string id = road.id + "_" + std::to_string(made);
        if (key.second == '2' || key.second == '4') {
          road.tunnels.push_back(
              xodr::Tunnel{id, key.second == '2' ? "tunnel" : "underground road", s0, s1 - s0,
                           key.second == '2' ? "standard" : "underpass", 1.0, 0.0});
        } else {
          road.bridges.push_back(
              xodr::Bridge{id, key.second == '3' ? "bridge" : "overpass", s0, s1 - s0, "concrete"});
        }
        ++made;
      }
    }
    return made;
  }

  size_t signals() {
    size_t placed = 0;
    for (const TrafficLight& light : layers_.lights) {
      placed += place_signal(light);
    }
    return placed;
  }

 private:
  const RoadFrame& frame(size_t road) {
    if (!frames_[road]) {
      frames_[road] = std::make_unique<RoadFrame>(map_.roads[road]);
    }
    return *frames_[road];
  }

  void place_mark(const SurfaceMark& mark, const std::string& link,
                  std::vector<std::vector<MarkPiece>>& pieces) {
    const auto found = by_link_.find(link);
    if (found == by_link_.end()) {
      return;
    }
    const std::vector<Vec2> points = sample_points(mark.points, origin_);
    for (const LinkPlacement* placement : found->second) {
      const size_t road = road_index_.at(placement->road_id);
      const RoadFrame& f = frame(road);
      const size_t k = static_cast<size_t>(-placement->lane_id);  // lane -k
      double s0 = 1e300, s1 = -1e300, t_sum = 0.0, inner = 0.0, outer = 0.0;
      int count = 0;
      for (const Vec2& q : points) {
        const RoadFrame::Position p = f.project(q);
        if (std::abs(p.outside) > 0.5 || p.s < placement->s_start - 0.5 ||
            p.s > placement->s_end + 0.5) {
          continue;
        }
        s0 = std::min(s0, p.s);
        s1 = std::max(s1, p.s);
        t_sum += p.t;
        inner += f.border(p.s, k - 1);
        outer += f.border(p.s, k);
        ++count;
      }
      if (count < 2 || s1 - s0 < 0.5) {
        continue;  // across the road (a stop line) or beside another part of it
      }
      const double t = t_sum / count;
      const bool is_inner = std::abs(t - inner / count) < std::abs(t - outer / count);
      if (std::min(std::abs(t - inner / count), std::abs(t - outer / count)) > 1.0) {
        continue;
      }
      // Direction of the mark against the road at its middle.
      const Vec2 d = points.back() - points.front();
      const double road_heading = f.heading(0.5 * (s0 + s1));
      const bool reversed = dot(d, Vec2{std::cos(road_heading), std::sin(road_heading)}) < 0.0;
      MarkPiece piece;
      piece.border = is_inner ? k - 1 : k;
      piece.s0 = s0;
      piece.s1 = s1;
      piece.mark = &mark;
      map_type(mark.type, reversed, piece);
      if (piece.type.empty()) {
        // A located note, not a warning: the code is valid in the data model (999 "other")
        // and names no kind of line to draw; nothing is guessed.
        Diagnostic note = make_warning(layers_.mark_file, 0,
                                       "marking Type '" + mark.type +
                                           "' has no OpenDRIVE roadMark; such marks are left "
                                           "out (first seen here)");
        note.severity = Severity::kNote;
        note.record = mark.record;
        diagnostics_.add_once("ngii-mark-type:" + mark.type, std::move(note));
        continue;
      }
      pieces[road].push_back(piece);
    }
  }

  /// roadMark records per border: each mark from where it starts, "none" across gaps > 1 m.
  size_t write_marks(xodr::Road& road, std::vector<MarkPiece>& pieces) {
    size_t written = 0;
    auto& lanes = road.lane_sections.front().lanes;  // [0] centre, [k] lane -k
    std::stable_sort(pieces.begin(), pieces.end(), [](const MarkPiece& a, const MarkPiece& b) {
      return a.border != b.border ? a.border < b.border : a.s0 < b.s0;
    });
    size_t i = 0;
    while (i < pieces.size()) {
      const size_t border = pieces[i].border;
      std::vector<xodr::RoadMark>& marks = lanes[border].road_marks;
      double cursor = 0.0;
      const SurfaceMark* last = nullptr;
      for (; i < pieces.size() && pieces[i].border == border; ++i) {
        const MarkPiece& piece = pieces[i];
        if (piece.mark == last || piece.s1 <= cursor) {
          continue;  // the same mark seen from both lanes, or covered already
        }
        const double start = std::max(piece.s0, cursor);
        if (start > cursor + 1.0 || (marks.empty() && start > 1.0)) {
          xodr::RoadMark none;
          none.s_offset = marks.empty() ? 0.0 : cursor;
          marks.push_back(none);
        }
        xodr::RoadMark record;
        record.s_offset = marks.empty() ? 0.0 : start;
        record.type = piece.type;
        record.color = piece.color;
        record.lane_change = piece.lane_change;
        record.width = 0.15;
        marks.push_back(record);
        ++written;
        cursor = piece.s1;
        last = piece.mark;
      }
      if (cursor < road.length - 1.0) {
        xodr::RoadMark none;
        none.s_offset = cursor;
        marks.push_back(none);
      }
    }
    return written;
  }

  bool place_signal(const TrafficLight& light) {
    const Vec2 q{light.position.x - origin_.x, light.position.y - origin_.y};
    // Prefer a road carrying the controlled link; otherwise the road nearest to the light.
    size_t best_road = map_.roads.size();
    RoadFrame::Position best;
    double best_score = 1e300;
    const auto consider = [&](size_t road, double penalty) {
      if (frame(road).box_distance(q) + penalty >= best_score) {
        return;
      }
      const RoadFrame::Position p = frame(road).project(q);
      const double score = std::abs(p.outside) * 10.0 + std::abs(p.t) + penalty;
      if (score < best_score) {
        best_score = score;
        best = p;
        best_road = road;
      }
    };
    if (const auto found = by_link_.find(light.link_id); found != by_link_.end()) {
      for (const LinkPlacement* placement : found->second) {
        consider(road_index_.at(placement->road_id), 0.0);
      }
    }
    if (best_road == map_.roads.size() || std::abs(best.outside) > 1.0) {
      for (size_t r = 0; r < map_.roads.size(); ++r) {
        consider(r, 5.0);
      }
    }
    if (best_road == map_.roads.size()) {
      return false;
    }
    xodr::Road& road = map_.roads[best_road];
    xodr::Signal signal;
    signal.id = light.id;
    signal.name =
        "traffic light " + light.id + " (NGII type " + light.type + ") for link " + light.link_id;
    signal.s = best.s;
    signal.t = best.t;
    signal.z_offset = light.position.z - piecewise_value(road.elevation, best.s);
    signal.orientation = "+";
    signal.dynamic = true;
    // The generic catalogue of OpenDRIVE signals (country "OpenDRIVE"); the NGII code stays in
    // userData.
    const SignalCode code = traffic_light_code(light.type);
    signal.country = "OpenDRIVE";
    signal.type = code.type;
    signal.subtype = code.subtype;
    signal.user_data.push_back(xodr::UserData{"ngii:C1_TRAFFICLIGHT.Type", light.type});
    signal.user_data.push_back(xodr::UserData{"ngii:link", light.link_id});
    road.signals.push_back(std::move(signal));
    return true;
  }

  xodr::MapData& map_;
  const Layers& layers_;
  const Origin& origin_;
  Diagnostics& diagnostics_;
  std::unordered_map<std::string, size_t> road_index_;
  std::unordered_map<std::string, std::vector<const LinkPlacement*>> by_link_;
  std::vector<std::unique_ptr<RoadFrame>> frames_;
};

}  // namespace

Decorations decorate(xodr::MapData& map, const std::vector<LinkPlacement>& placements,
                     const Layers& layers, const Origin& origin, Diagnostics& diagnostics) {
  Decorator decorator(map, placements, layers, origin, diagnostics);
  Decorations out;
  out.road_marks = decorator.road_marks();
  out.signals = decorator.signals();
  for (xodr::Road& road : map.roads) {
    std::stable_sort(road.signals.begin(), road.signals.end(),
                     [](const xodr::Signal& a, const xodr::Signal& b) { return a.s < b.s; });
  }
  out.controllers = add_signal_controllers(map);
  out.structures = decorator.structures();
  return out;
}

}  // namespace corsa::ngii::detail
