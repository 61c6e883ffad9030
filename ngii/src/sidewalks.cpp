#include "sidewalks.h"

#include <algorithm>

#include "polyline.h"

namespace corsa::ngii::detail {
namespace {

constexpr double kKerb = 0.15;      // m: sidewalk height above the road surface
constexpr double kLaneReach = 3.5;  // m: a lane within this plus the sidewalk is beside it
constexpr int kSamples = 5;         // points checked along the outermost lane

struct Box {
  double x0, y0, x1, y1;
  bool contains(Vec2 p, double margin) const {
    return p.x >= x0 - margin && p.x <= x1 + margin && p.y >= y0 - margin && p.y <= y1 + margin;
  }
};

Box box_of(const std::vector<Point3>& points) {
  Box box{points[0].x, points[0].y, points[0].x, points[0].y};
  for (const Point3& p : points) {
    box = Box{std::min(box.x0, p.x), std::min(box.y0, p.y), std::max(box.x1, p.x),
              std::max(box.y1, p.y)};
  }
  return box;
}

}  // namespace

int sidewalk_lane_id(const xodr::Road& road) { return road.lane_sections.front().lanes.back().id; }

std::vector<bool> add_sidewalks(std::vector<xodr::Road>& roads, const NetworkPlan& plan,
                                const std::vector<int>& road_slot, const Network& network,
                                double width) {
  std::vector<bool> added(plan.roads.size(), false);
  // Every lane of every ordinary road, with its box, for the "something to the right" test.
  struct Other {
    size_t road;
    Polyline line;
    Box box;
  };
  std::vector<Other> others;
  for (size_t r = 0; r < plan.roads.size(); ++r) {
    if (plan.roads[r].removed || plan.roads[r].junction >= 0) {
      continue;
    }
    for (const PlanLane& lane : plan.roads[r].lanes) {
      others.push_back({r, Polyline(lane.points), box_of(lane.points)});
    }
  }
  const double reach = kLaneReach + width;
  for (size_t r = 0; r < plan.roads.size(); ++r) {
    const RoadPlan& road = plan.roads[r];
    if (road.removed || road.junction >= 0) {
      continue;
    }
    const PlanLane& outer = road.lanes.back();
    const bool neighbour = std::any_of(outer.links.begin(), outer.links.end(), [&](int link) {
      return network.links[static_cast<size_t>(link)].right >= 0;
    });
    if (neighbour) {
      continue;
    }
    const Polyline line(outer.points);
    bool beside = false;
    for (int k = 1; k <= kSamples && !beside; ++k) {
      const double u = line.length() * k / (kSamples + 1);
      const Vec2 p = xy(line.at(u));
      const Vec2 right{line.direction(u).y, -line.direction(u).x};
      for (const Other& other : others) {
        if (other.road == r || !other.box.contains(p, reach)) {
          continue;
        }
        const Projection q = other.line.project(p);
        if (q.along == 0.0 && q.distance < reach && dot(xy(other.line.at(q.u)) - p, right) > 0.5) {
          beside = true;
          break;
        }
      }
    }
    if (beside) {
      continue;
    }
    xodr::Road& target = roads[static_cast<size_t>(road_slot[r])];
    xodr::LaneSection& section = target.lane_sections.front();
    xodr::Lane sidewalk;
    sidewalk.id = section.lanes.back().id - 1;
    sidewalk.type = xodr::LaneType::kSidewalk;
    sidewalk.type_name = "sidewalk";
    sidewalk.widths.push_back(xodr::Poly3{0.0, width, 0.0, 0.0, 0.0});
    sidewalk.heights.push_back(xodr::LaneHeight{0.0, kKerb, kKerb});
    // Provenance: the link whose edge it runs along.
    sidewalk.user_data.push_back(
        xodr::UserData{"ngii:sidewalk", network.source(outer.links.front()).id});
    section.lanes.push_back(std::move(sidewalk));
    added[r] = true;
  }
  return added;
}

}  // namespace corsa::ngii::detail
