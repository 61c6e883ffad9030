#include "ngii_measure.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <set>
#include <unordered_map>

#include "mesh_folds.h"

namespace corsa::test {
namespace {

using xodr::LaneRef;
using xodr::Map;

struct P3 {
  double x = 0.0, y = 0.0, z = 0.0;
};

/// Nearest point of a polyline to (x, y): distance, interpolated z, arc length, signed lateral
/// offset (+ left of the polyline's direction) and whether the foot is inside (not an end
/// reached from beyond it).
struct Foot {
  double distance = 1e300;
  double z = 0.0;
  double lateral = 0.0;  ///< signed offset of the point from the line (m, + left)
  double along = 0.0;    ///< segment index plus the fraction along it (vertex units)
  bool inside = false;
};

Foot foot_on(const std::vector<P3>& line, double x, double y) {
  Foot best;
  for (size_t i = 0; i + 1 < line.size(); ++i) {
    const double dx = line[i + 1].x - line[i].x, dy = line[i + 1].y - line[i].y;
    const double len2 = dx * dx + dy * dy;
    if (len2 <= 0.0) {
      continue;
    }
    const double f = ((x - line[i].x) * dx + (y - line[i].y) * dy) / len2;
    const double c = std::clamp(f, 0.0, 1.0);
    const double px = line[i].x + c * dx, py = line[i].y + c * dy;
    const double d = std::hypot(x - px, y - py);
    if (d < best.distance) {
      best.distance = d;
      best.z = line[i].z + c * (line[i + 1].z - line[i].z);
      best.lateral = (dx * (y - line[i].y) - dy * (x - line[i].x)) / std::sqrt(len2);
      best.along = static_cast<double>(i) + c;
      best.inside = !((i == 0 && f < 0.0) || (i + 2 == line.size() && f > 1.0));
    }
  }
  return best;
}

double percentile(std::vector<double> values, double p) {
  if (values.empty()) {
    return 0.0;
  }
  std::sort(values.begin(), values.end());
  const size_t k =
      std::min(values.size() - 1, static_cast<size_t>(std::ceil(p * values.size())) - 1);
  return values[k];
}

double length_of(const std::vector<ngii::Point3>& points) {
  double total = 0.0;
  for (size_t i = 1; i < points.size(); ++i) {
    total += std::hypot(points[i].x - points[i - 1].x, points[i].y - points[i - 1].y);
  }
  return total;
}

class Measurer {
 public:
  Measurer(const ngii::Layers& layers, const Map& map) : layers_(layers), map_(map) {
    ox_ = map.data().header.offset_x;
    oy_ = map.data().header.offset_y;
    for (const auto& link : layers.links) {
      links_[link.id] = &link;
      if (link.link_type != "1") {
        ++ordinary_starting_[link.from_node];
        ++ordinary_ending_[link.to_node];
      }
    }
    for (const auto& mark : layers.marks) {
      if (mark.right_link == mark.left_link) {
        continue;  // a mark naming one link on both sides crosses it, it does not bound it
      }
      if (!mark.right_link.empty()) left_marks_[mark.right_link].push_back(local(mark.points));
      if (!mark.left_link.empty()) right_marks_[mark.left_link].push_back(local(mark.points));
    }
    const auto& roads = map.data().roads;
    for (uint32_t r = 0; r < roads.size(); ++r) {
      for (uint32_t k = 0; k < roads[r].lane_sections.size(); ++k) {
        for (const auto& lane : roads[r].lane_sections[k].lanes) {
          if (lane.id == 0) {
            continue;
          }
          std::vector<std::string> ids;
          for (const auto& d : lane.user_data) {
            if (d.code == "ngii:link") {
              ids.push_back(d.value);
            }
          }
          const bool strip =
              std::any_of(lane.user_data.begin(), lane.user_data.end(),
                          [](const auto& d) { return d.code == "ngii:centre-strip"; });
          if (ids.empty() && strip && lane.type == xodr::LaneType::kRestricted) {
            continue;  // the converter's fill between double centre lines, named as such
          }
          if (ids.empty() && mouth_fill(lane)) {
            continue;  // the converter's paving beside a lane's joint, named as such
          }
          if (ids.empty()) {
            ++figures_.lanes_without_provenance;
            continue;
          }
          const LaneRef ref{r, k, lane.id};
          lanes_.push_back({ref, ids});
          for (const auto& id : ids) {
            lanes_of_[id].push_back(lanes_.size() - 1);
          }
        }
      }
    }
  }

  /// Lane ends the mouth-gap measure leaves out: centre strips, and lane ends at a split or
  /// merge (the lane begins or ends at zero width beside its neighbour).
  bool skip_mouth(const LaneRef& ref, bool at_start) const {
    return centre_strip(ref) || shares_node(source_link(ref, at_start), at_start);
  }

  NgiiFigures run() {
    link_ends();
    lane_joins();
    vertical();
    figures_.lateral_p95 = percentile(lateral_, 0.95);
    widths();
    side_by_side();
    return figures_;
  }

 private:
  struct LaneInfo {
    LaneRef ref;
    std::vector<std::string> links;
  };

  std::vector<P3> local(const std::vector<ngii::Point3>& points) const {
    std::vector<P3> out;
    out.reserve(points.size());
    for (const auto& p : points) {
      out.push_back({p.x - ox_, p.y - oy_, p.z});
    }
    return out;
  }

  /// Centre of a lane at road s, in its own section (s may be the section end).
  P3 centre(const LaneRef& ref, double s) const {
    const auto span = map_.lane_span_in_section(ref.road, ref.section, s, ref.lane);
    const auto pose = map_.world_pose(ref.road, s, span ? span->t_center() : 0.0);
    return {pose.x, pose.y, pose.z};
  }

  /// The first (last) A2 link a lane names.
  const ngii::Link* source_link(const LaneRef& ref, bool first) const {
    const auto& lane = map_.data().roads[ref.road].lane_sections[ref.section].lanes;
    for (const auto& l : lane) {
      if (l.id != ref.lane) {
        continue;
      }
      const xodr::UserData* found = nullptr;
      for (const auto& d : l.user_data) {
        if (d.code == "ngii:link" && (found == nullptr || !first)) {
          found = &d;
        }
      }
      if (found != nullptr) {
        const auto it = links_.find(found->value);
        return it == links_.end() ? nullptr : it->second;
      }
    }
    return nullptr;
  }

  /// Whether `link` (an ordinary lane link) starts (ends) at a node where another ordinary link
  /// also starts (ends): a lane splitting in two (two merging into one).
  bool shares_node(const ngii::Link* link, bool at_start) const {
    if (link == nullptr || link->link_type == "1") {
      return false;
    }
    const auto& table = at_start ? ordinary_starting_ : ordinary_ending_;
    const auto it = table.find(at_start ? link->from_node : link->to_node);
    return it != table.end() && it->second > 1;
  }

  double section_start(const LaneRef& ref) const {
    return map_.road(ref.road).lane_sections[ref.section].s;
  }
  double section_end(const LaneRef& ref) const { return map_.section_end(ref.road, ref.section); }

  std::vector<P3> centre_line(const LaneRef& ref, double step) const {
    const double s0 = section_start(ref), s1 = section_end(ref);
    const int n = std::max(1, static_cast<int>(std::ceil((s1 - s0) / step)));
    std::vector<P3> out;
    for (int i = 0; i <= n; ++i) {
      out.push_back(centre(ref, s0 + (s1 - s0) * i / n));
    }
    return out;
  }

  /// CORSA_MEASURE_LIST=1 lists every figure over 0.2 m on stderr.
  void add_gap(GapFigures& g, double d, const std::string& what) {
    if (std::getenv("CORSA_MEASURE_LIST") != nullptr && d > 0.2) {
      const char* kind = &g == &figures_.link_ends    ? "link_end"
                         : &g == &figures_.split_ends ? "split_end"
                         : &g == &figures_.lane_joins ? "join"
                                                      : "split_join";
      std::fprintf(stderr, "%s %.3f %s\n", kind, d, what.c_str());
    }
    ++g.count;
    g.over += d > 0.2;
    if (d > g.max) {
      g.max = d;
      g.worst = what;
    }
  }

  void link_ends() {
    for (const auto& link : layers_.links) {
      if (length_of(link.points) < 0.1) {
        continue;
      }
      const auto found = lanes_of_.find(link.id);
      if (found == lanes_of_.end()) {
        ++figures_.links_without_lane;
        continue;
      }
      const auto first = local({link.points.front()})[0];
      const auto last = local({link.points.back()})[0];
      double start_gap = 1e300, end_gap = 1e300;
      for (const size_t i : found->second) {
        const LaneInfo& lane = lanes_[i];
        if (lane.links.front() == link.id) {
          const P3 p = centre(lane.ref, section_start(lane.ref));
          start_gap = std::min(start_gap, std::hypot(p.x - first.x, p.y - first.y));
        }
        if (lane.links.back() == link.id) {
          const P3 p = centre(lane.ref, section_end(lane.ref));
          end_gap = std::min(end_gap, std::hypot(p.x - last.x, p.y - last.y));
        }
      }
      // A link continued in the next lane section of the same lane is measured where it starts
      // and ends, which is always a lane's first / last link somewhere.
      if (start_gap < 1e300) {
        add_gap(shares_node(&link, true) ? figures_.split_ends : figures_.link_ends, start_gap,
                link.id + " start");
      }
      if (end_gap < 1e300) {
        add_gap(shares_node(&link, false) ? figures_.split_ends : figures_.link_ends, end_gap,
                link.id + " end");
      }
    }
  }

  /// A shoulder the converter adds beside a lane continuing into a narrower one (no survey
  /// link is it).
  static bool mouth_fill(const xodr::Lane& lane) {
    return lane.type == xodr::LaneType::kShoulder &&
           std::any_of(lane.user_data.begin(), lane.user_data.end(),
                       [](const auto& d) { return d.code == "ngii:mouth-fill"; });
  }

  bool centre_strip(const LaneRef& ref) const {
    const xodr::Lane* lane = map_.lane(ref);
    return lane != nullptr && lane->type == xodr::LaneType::kRestricted &&
           std::any_of(lane->user_data.begin(), lane->user_data.end(),
                       [](const auto& d) { return d.code == "ngii:centre-strip"; });
  }

  /// Joins of the survey's lanes (the centre strips' joins are strip_joins.h's).
  void lane_joins() {
    const auto& graph = map_.lane_graph();
    for (xodr::LaneNode node = 0; node < graph.size(); ++node) {
      const auto& info = graph.info(node);
      if (centre_strip(info.lane)) {
        continue;
      }
      const P3 a = centre(info.lane, info.s_end);
      const ngii::Link* last = source_link(info.lane, false);
      for (const auto& end : graph.successors(node)) {
        const auto& next = graph.info(end.node);
        const double s_b = end.at_start ? next.s_start : next.s_end;
        const P3 b = centre(next.lane, s_b);
        const auto& road = map_.road(info.lane.road);
        const bool split =
            shares_node(source_link(next.lane, true), true) || shares_node(last, false);
        add_gap(split ? figures_.split_joins : figures_.lane_joins,
                std::hypot(a.x - b.x, a.y - b.y),
                "road " + road.id + " lane " + std::to_string(info.lane.lane) + " -> road " +
                    map_.road(next.lane.road).id + " lane " + std::to_string(next.lane.lane));
      }
    }
  }

  /// The map's heights under an A2 vertex found on the lane's centre line sampled every
  /// 0.5 m: `centre` at the centre's point level with it (its foot), `surface` at the vertex's
  /// own horizontal position (the foot's s, the centre's t plus the vertex's offset from it).
  /// Both are evaluated on the map at the foot's s, not interpolated between samples: a chord
  /// cuts the corner of a profile that bends by a metre within a few metres.
  struct VertexHeights {
    double centre = 0.0;
    double surface = 0.0;
  };
  VertexHeights heights_under(const LaneRef& ref, const std::vector<P3>& line, const Foot& f,
                              const P3& v) const {
    const double s0 = section_start(ref), s1 = section_end(ref);
    const double s = s0 + (s1 - s0) * f.along / static_cast<double>(line.size() - 1);
    const auto span = map_.lane_span_in_section(ref.road, ref.section, s, ref.lane);
    const double t_centre = span ? span->t_center() : 0.0;
    const auto centre = map_.world_pose(ref.road, s, t_centre);
    // t runs along a superelevated surface: step along it until the point is level with the
    // vertex (two steps leave millimetres on the steepest roll).
    double t = t_centre + f.lateral;
    auto at = map_.world_pose(ref.road, s, t);
    for (int step = 0; step < 2; ++step) {
      const double along_t = at.x - centre.x, along_t_y = at.y - centre.y;
      const double reach = std::hypot(along_t, along_t_y);
      if (reach < 1e-6) {
        break;
      }
      const double miss = ((v.x - at.x) * along_t + (v.y - at.y) * along_t_y) / reach;
      t += (t >= t_centre ? 1.0 : -1.0) * miss;
      at = map_.world_pose(ref.road, s, t);
    }
    return {centre.z, at.z};
  }

  void vertical() {
    const bool list = std::getenv("CORSA_MEASURE_LIST") != nullptr;
    for (const LaneInfo& lane : lanes_) {
      const std::vector<P3> line = centre_line(lane.ref, 0.5);
      std::vector<double> errors, centre_errors;
      for (const auto& id : lane.links) {
        const auto it = links_.find(id);
        if (it == links_.end()) {
          continue;
        }
        for (const P3& v : local(it->second->points)) {
          const Foot f = foot_on(line, v.x, v.y);
          if (f.inside && f.distance < 1.0) {
            const VertexHeights h = heights_under(lane.ref, line, f, v);
            errors.push_back(std::abs(h.surface - v.z));
            centre_errors.push_back(std::abs(h.centre - v.z));
            lateral_.push_back(f.distance);
          }
        }
      }
      if (errors.empty()) {
        continue;
      }
      ++figures_.lanes_measured;
      const double p95 = percentile(errors, 0.95);
      const double centre_p95 = percentile(centre_errors, 0.95);
      figures_.vertical_max =
          std::max(figures_.vertical_max, *std::max_element(errors.begin(), errors.end()));
      figures_.lanes_over_5cm += p95 > 0.05;
      figures_.lanes_centre_over_5cm += centre_p95 > 0.05;
      if (list && (p95 > 0.05 || centre_p95 > 0.05)) {
        std::fprintf(stderr, "vertical %.3f (centre %.3f) road %s lane %d %s\n", p95, centre_p95,
                     map_.road(lane.ref.road).id.c_str(), lane.ref.lane,
                     lane.links.front().c_str());
      }
      if (p95 > figures_.vertical_p95_max) {
        figures_.vertical_p95_max = p95;
        figures_.vertical_worst = lane.links.front();
      }
      if (centre_p95 > figures_.vertical_centre_p95_max) {
        figures_.vertical_centre_p95_max = centre_p95;
        figures_.vertical_centre_worst = lane.links.front();
      }
    }
  }

  /// Distance from the lane centre point c (heading h) to the nearest of `marks` on the given
  /// side (foot inside the mark, within 6 m); 1e300 when none.
  static double side_distance(const std::vector<std::vector<P3>>& marks, const P3& c, double h,
                              bool left) {
    double best = 1e300;
    const double nx = -std::sin(h), ny = std::cos(h);
    for (const auto& mark : marks) {
      const Foot f = foot_on(mark, c.x, c.y);
      if (!f.inside || f.distance > 6.0) {
        continue;
      }
      // A step to the left brings a mark on the left nearer.
      const bool on_left = foot_on(mark, c.x + 0.01 * nx, c.y + 0.01 * ny).distance < f.distance;
      if (on_left == left) {
        best = std::min(best, f.distance);
      }
    }
    return best;
  }

  void widths() {
    std::vector<double> all, single;
    for (const LaneInfo& lane : lanes_) {
      // The links along the lane; at each station the nearest one is the lane's link there.
      std::vector<std::pair<const ngii::Link*, std::vector<P3>>> links;
      for (const auto& id : lane.links) {
        if (const auto it = links_.find(id); it != links_.end()) {
          links.emplace_back(it->second, local(it->second->points));
        }
      }
      if (links.empty()) {
        continue;
      }
      std::vector<xodr::LaneSpan> spans;
      const double s0 = section_start(lane.ref), s1 = section_end(lane.ref);
      map_.lane_spans_in_section(lane.ref.road, lane.ref.section, s0, spans);
      // The driving side only: a centre strip (lane +1, below) is no lane of the survey, nor
      // is a shoulder paving the ground beside a joint.
      const bool one_lane =
          std::count_if(spans.begin(), spans.end(), [&](const auto& x) {
            const xodr::Lane* other = map_.lane(LaneRef{lane.ref.road, lane.ref.section, x.id});
            return x.id < 0 && !(other && mouth_fill(*other));
          }) == 1;
      std::vector<double> own;
      for (double s = s0 + 0.5; s < s1 - 0.5; s += 1.0) {
        const auto span =
            map_.lane_span_in_section(lane.ref.road, lane.ref.section, s, lane.ref.lane);
        if (!span) {
          continue;
        }
        const P3 c = centre(lane.ref, s);
        const P3 ahead = centre(lane.ref, std::min(s1, s + 0.25));
        const double h = std::atan2(ahead.y - c.y, ahead.x - c.x);
        const ngii::Link* link = links.front().first;
        double nearest = 1e300;
        for (const auto& [candidate, line] : links) {
          const double d = foot_on(line, c.x, c.y).distance;
          if (d < nearest) {
            nearest = d;
            link = candidate;
          }
        }
        // The marks naming that link: R_linkID (the lane on the mark's right) bounds it on the
        // left, L_linkID on the right.
        const auto left = left_marks_.find(link->id);
        const auto right = right_marks_.find(link->id);
        if (left == left_marks_.end() || right == right_marks_.end()) {
          continue;
        }
        const double dl = side_distance(left->second, c, h, true);
        const double dr = side_distance(right->second, c, h, false);
        if (dl > 10.0 || dr > 10.0) {
          continue;
        }
        const double error = std::abs(span->width() - (dl + dr));
        all.push_back(error);
        own.push_back(error);
        if (one_lane) {
          single.push_back(error);
        }
      }
      if (std::getenv("CORSA_MEASURE_LIST") != nullptr && percentile(own, 0.95) > 0.2) {
        std::fprintf(stderr, "width%s %.3f road %s lane %d %s (%zu samples)\n", one_lane ? "1" : "",
                     percentile(own, 0.95), map_.road(lane.ref.road).id.c_str(), lane.ref.lane,
                     lane.links.front().c_str(), own.size());
      }
    }
    figures_.width_samples = all.size();
    figures_.width_p95 = percentile(all, 0.95);
    figures_.width_p95_single = percentile(single, 0.95);
  }

  /// Fraction of `a` (sampled every metre) that has `b` beside it on the given side, 1.5-7 m.
  double beside_fraction(const std::vector<P3>& a, const std::vector<P3>& b, bool b_right) const {
    double total = 0.0, beside = 0.0;
    for (size_t i = 0; i + 1 < a.size(); ++i) {
      const double len = std::hypot(a[i + 1].x - a[i].x, a[i + 1].y - a[i].y);
      const int n = std::max(1, static_cast<int>(len));
      for (int k = 0; k < n; ++k) {
        const double f = (k + 0.5) / n;
        const double x = a[i].x + f * (a[i + 1].x - a[i].x);
        const double y = a[i].y + f * (a[i + 1].y - a[i].y);
        const Foot foot = foot_on(b, x, y);
        // b's lateral offset seen from b: a lies left of b when b is on a's right.
        const double lateral = b_right ? foot.lateral : -foot.lateral;
        total += len / n;
        if (foot.inside && lateral > 1.5 && lateral < 7.0) {
          beside += len / n;
        }
      }
    }
    return total > 0.0 ? beside / total : 0.0;
  }

  void side_by_side() {
    std::set<std::pair<std::string, std::string>> pairs;  // (left, right)
    for (const auto& link : layers_.links) {
      if (link.link_type == "1") {
        continue;
      }
      if (const auto it = links_.find(link.right_id);
          it != links_.end() && it->second->link_type != "1") {
        pairs.insert({link.id, link.right_id});
      }
      if (const auto it = links_.find(link.left_id);
          it != links_.end() && it->second->link_type != "1") {
        pairs.insert({link.left_id, link.id});
      }
    }
    for (const auto& [left, right] : pairs) {
      const auto a = local(links_.at(left)->points);
      const auto b = local(links_.at(right)->points);
      if (beside_fraction(a, b, true) < 0.9 || beside_fraction(b, a, false) < 0.9) {
        continue;
      }
      ++figures_.side_by_side_pairs;
      std::set<uint32_t> roads_left, roads_right;
      if (const auto it = lanes_of_.find(left); it != lanes_of_.end()) {
        for (const size_t i : it->second) roads_left.insert(lanes_[i].ref.road);
      }
      if (const auto it = lanes_of_.find(right); it != lanes_of_.end()) {
        for (const size_t i : it->second) roads_right.insert(lanes_[i].ref.road);
      }
      const bool shared = std::any_of(roads_left.begin(), roads_left.end(),
                                      [&](uint32_t r) { return roads_right.contains(r); });
      if (!shared) {
        ++figures_.split_pairs;
        if (figures_.split_examples.size() < 60) {
          figures_.split_examples.push_back(left + "|" + right);
        }
      }
    }
  }

  const ngii::Layers& layers_;
  const Map& map_;
  double ox_ = 0.0, oy_ = 0.0;
  std::unordered_map<std::string, const ngii::Link*> links_;
  std::unordered_map<std::string, int> ordinary_starting_, ordinary_ending_;  ///< per A1 node
  std::unordered_map<std::string, std::vector<std::vector<P3>>> left_marks_, right_marks_;
  std::vector<LaneInfo> lanes_;
  std::unordered_map<std::string, std::vector<size_t>> lanes_of_;
  NgiiFigures figures_;
  std::vector<double> lateral_;  ///< distances of A2 vertices from their lane centres (m)
};

}  // namespace

NgiiFigures measure_ngii(const ngii::Layers& layers, const xodr::Map& map) {
  Measurer measurer(layers, map);
  NgiiFigures figures = measurer.run();
  figures.mouth_gaps = corsa::test::mouth_gaps(
      map, [&](const LaneRef& ref, bool at_start) { return measurer.skip_mouth(ref, at_start); });
  figures.folded_roads = corsa::test::folded_roads(map);
  figures.centre_gaps = corsa::test::centre_gaps(layers, map);
  figures.strip_joins = corsa::test::strip_joins(map);
  return figures;
}

}  // namespace corsa::test
