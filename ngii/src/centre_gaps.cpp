#include "centre_gaps.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <set>
#include <string>

#include "corsa/ngii/curve_fit.h"
#include "polyline.h"
#include "reference_line.h"
#include "road_frame.h"

namespace corsa::ngii::detail {
namespace {

constexpr double kStripStep = 1.0;        // m between gap samples along a road
constexpr double kStripMinGap = 0.01;     // m: narrower gaps are the fit's noise, left alone
constexpr double kStripMinWidth = 0.025;  // m: a strip lane narrower everywhere is not added
constexpr double kStripTolerance = 0.01;  // m: linear width pieces stay this close to the gaps
constexpr double kStripOpposite = -0.8;   // cos of the heading difference of opposing roads
constexpr double kStripReach = 2.0;       // m: roads whose box is farther are not looked at
// m: farthest a road's left edge lies from its reference line (the laneOffset of a one-lane
// turn fitted along its right edge is a lane width), for the road-to-road prefilter
constexpr double kStripEdgeReach = 10.0;

/// A centre mark: yellow (Type 1xx) or Kind 501 (centre line).
bool is_centre_mark(const SurfaceMark& mark) {
  return (!mark.type.empty() && mark.type[0] == '1') || mark.kind == "501";
}

/// Whether links a and b run opposite ways beside point q.
bool links_opposed(const Link& a, const Link& b, Vec2 q) {
  if (a.points.size() < 2 || b.points.size() < 2) {
    return false;
  }
  const Polyline la(a.points), lb(b.points);
  const Projection pa = la.project(q), pb = lb.project(q);
  return pa.distance < 10.0 && pb.distance < 10.0 &&
         dot(la.direction(pa.u), lb.direction(pb.u)) < kStripOpposite;
}

/// Links bounded on their left by a centre mark: the mark's R_linkID, and its L_linkID where
/// that link runs the other way (one mark digitised for both directions).
std::set<std::string> centre_bounded_links(const Layers& layers) {
  std::map<std::string, const Link*> links;
  for (const Link& link : layers.links) {
    links[link.id] = &link;
  }
  std::set<std::string> out;
  for (const SurfaceMark& mark : layers.marks) {
    if (!is_centre_mark(mark) || mark.right_link.empty() || mark.right_link == mark.left_link) {
      continue;
    }
    out.insert(mark.right_link);
    const auto right = links.find(mark.right_link), left = links.find(mark.left_link);
    if (right != links.end() && left != links.end() && !mark.points.empty()) {
      const Point3& middle = mark.points[mark.points.size() / 2];
      if (links_opposed(*right->second, *left->second, Vec2{middle.x, middle.y})) {
        out.insert(mark.left_link);
      }
    }
  }
  return out;
}

/// Where a road's leftmost lane has a centre mark on its left (road s range).
struct StripSpan {
  double s0 = 0.0, s1 = 0.0;
};

class StripBuilder {
 public:
  StripBuilder(std::vector<xodr::Road>& roads, const std::vector<LinkPlacement>& placements,
               const Layers& layers)
      : roads_(roads), frames_(roads.size()), spans_(roads.size()) {
    std::map<std::string, size_t> index;
    for (size_t r = 0; r < roads.size(); ++r) {
      index[roads[r].id] = r;
    }
    const std::set<std::string> bounded = centre_bounded_links(layers);
    for (const LinkPlacement& p : placements) {
      const auto it = index.find(p.road_id);
      if (it != index.end() && p.lane_id == -1 && p.section == 0 && bounded.count(p.link_id)) {
        spans_[it->second].push_back({p.s_start, p.s_end});
      }
    }
    // Only roads with a centre mark on their left somewhere are measured or measured against.
    for (size_t r = 0; r < roads.size(); ++r) {
      if (!spans_[r].empty() && eligible(roads[r])) {
        frames_[r] = std::make_unique<RoadFrame>(roads[r]);
      }
    }
    near_.resize(roads.size());
    for (size_t r = 0; r < roads.size(); ++r) {
      for (size_t o = 0; frames_[r] && o < roads.size(); ++o) {
        if (o != r && frames_[o] &&
            frames_[r]->box_gap(*frames_[o]) <= kStripReach + kStripEdgeReach) {
          near_[r].push_back(o);
        }
      }
    }
  }

  /// Half the gap to the opposing road at each station of road r (0 where there is none).
  std::vector<ProfileSample> half_gaps(size_t r) const {
    const xodr::Road& road = roads_[r];
    const int count = std::max(1, static_cast<int>(std::ceil(road.length / kStripStep)));
    std::vector<double> s(static_cast<size_t>(count) + 1);
    for (int i = 0; i <= count; ++i) {
      s[static_cast<size_t>(i)] = road.length * i / count;
    }
    const std::vector<RefSample> ref = sample_reference(road.plan_view, s);
    std::vector<ProfileSample> out;
    for (size_t i = 0; i < s.size(); ++i) {
      double gap = 0.0;
      if (bounded_at(r, s[i])) {
        const double t = frames_[r]->border(s[i], 0);
        const Vec2 edge{ref[i].x - t * std::sin(ref[i].hdg), ref[i].y + t * std::cos(ref[i].hdg)};
        gap = gap_from(r, edge, ref[i].hdg);
      }
      out.push_back({s[i], gap > kStripMinGap ? 0.5 * gap : 0.0});
    }
    return out;
  }

  bool eligible(const xodr::Road& road) const {
    return road.lane_sections.size() == 1 && road.lane_sections.front().lanes.size() >= 2 &&
           road.lane_sections.front().lanes.front().id == 0;  // no left lanes yet
  }
  bool has_frame(size_t r) const { return frames_[r] != nullptr; }

 private:
  bool bounded_at(size_t r, double s) const {
    for (const StripSpan& span : spans_[r]) {
      if (s >= span.s0 - 1e-6 && s <= span.s1 + 1e-6) {
        return true;
      }
    }
    return false;
  }

  /// Smallest gap (m) from the left edge point `edge` (road heading `hdg`) to the left edge of
  /// an opposing road whose leftmost lane is centre-bounded there; 0 when none lies within
  /// kCentreStripMaxGap on the left.
  double gap_from(size_t r, Vec2 edge, double hdg) const {
    double best = 0.0;
    for (const size_t o : near_[r]) {
      if (frames_[o]->box_distance(edge) > kStripReach) {
        continue;
      }
      const RoadFrame& other = *frames_[o];
      const RoadFrame::Position p = other.project(edge);
      if (std::abs(p.outside) > 1e-3 || std::cos(other.heading(p.s) - hdg) > kStripOpposite ||
          !bounded_at(o, p.s)) {
        continue;
      }
      // The point lies beyond the opposing road's left edge by the gap (its t grows leftward).
      const double gap = p.t - other.border(p.s, 0);
      if (gap > 0.0 && gap < kCentreStripMaxGap && (best == 0.0 || gap < best)) {
        best = gap;
      }
    }
    return best;
  }

  std::vector<xodr::Road>& roads_;
  std::vector<std::unique_ptr<RoadFrame>> frames_;
  std::vector<std::vector<StripSpan>> spans_;
  std::vector<std::vector<size_t>> near_;  ///< per road, the measured roads within reach
};

/// Linear pieces through the samples, each as long as every sample it spans stays within
/// kStripTolerance of it (a strip half a gap wide needs no smoother shape).
std::vector<xodr::Poly3> linear_pieces(const std::vector<ProfileSample>& samples) {
  std::vector<xodr::Poly3> out;
  size_t i = 0;
  while (i + 1 < samples.size()) {
    size_t j = i + 1;
    while (j + 1 < samples.size()) {
      const size_t next = j + 1;
      const double slope = (samples[next].v - samples[i].v) / (samples[next].s - samples[i].s);
      bool fits = true;
      for (size_t k = i + 1; k < next && fits; ++k) {
        const double v = samples[i].v + slope * (samples[k].s - samples[i].s);
        fits = std::abs(v - samples[k].v) <= kStripTolerance;
      }
      if (!fits) {
        break;
      }
      j = next;
    }
    const double slope = (samples[j].v - samples[i].v) / (samples[j].s - samples[i].s);
    out.push_back(xodr::Poly3{samples[i].s, samples[i].v, slope, 0.0, 0.0});
    i = j;
  }
  if (out.empty()) {
    out.push_back(xodr::Poly3{0.0, samples.empty() ? 0.0 : samples.front().v, 0.0, 0.0, 0.0});
  }
  return out;
}

}  // namespace

size_t close_centre_gaps(std::vector<xodr::Road>& roads,
                         const std::vector<LinkPlacement>& placements, const Layers& layers) {
  const StripBuilder builder(roads, placements, layers);
  // Measured on every road first, then added: each road's gap is to the other's driving edge.
  std::vector<std::vector<ProfileSample>> strips(roads.size());
  for (size_t r = 0; r < roads.size(); ++r) {
    if (builder.has_frame(r)) {
      strips[r] = builder.half_gaps(r);
    }
  }
  size_t added = 0;
  for (size_t r = 0; r < roads.size(); ++r) {
    const auto widest =
        std::max_element(strips[r].begin(), strips[r].end(),
                         [](const ProfileSample& a, const ProfileSample& b) { return a.v < b.v; });
    if (widest == strips[r].end() || widest->v < kStripMinWidth) {
      continue;
    }
    xodr::Lane lane;
    lane.id = 1;
    lane.type = xodr::LaneType::kRestricted;
    lane.type_name = "restricted";
    lane.widths = linear_pieces(strips[r]);
    lane.user_data.push_back(
        xodr::UserData{"ngii:centre-strip", "half the gap to the opposing road"});
    auto& lanes = roads[r].lane_sections.front().lanes;
    lanes.insert(lanes.begin(), std::move(lane));
    ++added;
  }
  return added;
}

}  // namespace corsa::ngii::detail
