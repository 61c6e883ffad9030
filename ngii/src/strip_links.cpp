#include "strip_links.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <string>
#include <utility>

#include "reference_line.h"

namespace corsa::ngii::detail {
namespace {

constexpr int kStripLane = 1;

/// The strip lane of a road (lane +1 of its only section, type restricted), or null.
xodr::Lane* strip_lane(xodr::Road& road) {
  if (road.lane_sections.size() != 1 || road.lane_sections.front().lanes.empty()) {
    return nullptr;
  }
  xodr::Lane& lane = road.lane_sections.front().lanes.front();
  return lane.id == kStripLane && lane.type == xodr::LaneType::kRestricted ? &lane : nullptr;
}

struct EdgePoint {
  double x = 0.0, y = 0.0;
};

/// The strips' roads by id, with the inner edge (t = laneOffset) at each end.
class StripEnds {
 public:
  explicit StripEnds(xodr::MapData& map) {
    for (xodr::Road& road : map.roads) {
      if (strip_lane(road) == nullptr) {
        continue;
      }
      Entry& e = roads_[road.id];
      e.road = &road;
      const std::vector<RefSample> ref = sample_reference(road.plan_view, {0.0, road.length});
      for (size_t k = 0; k < 2 && k < ref.size(); ++k) {
        const double s = k == 0 ? 0.0 : road.length;
        const double t = road.lane_offsets.empty() ? 0.0 : piecewise_value(road.lane_offsets, s);
        e.ends[k] = {ref[k].x - t * std::sin(ref[k].hdg), ref[k].y + t * std::cos(ref[k].hdg)};
      }
    }
  }

  xodr::Road* road(const std::string& id) const {
    const auto it = roads_.find(id);
    return it == roads_.end() ? nullptr : it->second.road;
  }

  /// Whether the strip of road a at its end (at_end) meets the strip of road b at its end
  /// (b_end): the roads run the same way through the joint (end to start) and the inner edges
  /// meet within kStripJoinReach.
  bool meet(const std::string& a, bool at_end, const std::string& b, bool b_end) const {
    const auto ia = roads_.find(a), ib = roads_.find(b);
    if (ia == roads_.end() || ib == roads_.end() || at_end == b_end || a == b) {
      return false;
    }
    const EdgePoint& p = ia->second.ends[at_end ? 1 : 0];
    const EdgePoint& q = ib->second.ends[b_end ? 1 : 0];
    return std::hypot(p.x - q.x, p.y - q.y) <= kStripJoinReach;
  }

 private:
  struct Entry {
    xodr::Road* road = nullptr;
    EdgePoint ends[2];
  };
  std::map<std::string, Entry> roads_;
};

bool names_junction(const xodr::RoadLink& link, const std::string& junction) {
  return link.element_type == xodr::LinkElement::kJunction && link.element_id == junction;
}

void add_unique(std::vector<int>& ids, int id) {
  if (std::find(ids.begin(), ids.end(), id) == ids.end()) {
    ids.push_back(id);
  }
}

/// Road-to-road links (§9.6): each strip names the strip of the road its road links to.
size_t link_roads(xodr::MapData& map, const StripEnds& strips) {
  size_t joins = 0;
  for (xodr::Road& road : map.roads) {
    xodr::Lane* lane = strip_lane(road);
    for (const bool at_end : {false, true}) {
      const xodr::RoadLink& link = at_end ? road.successor : road.predecessor;
      if (lane == nullptr || link.element_type != xodr::LinkElement::kRoad) {
        continue;
      }
      const bool other_end = link.contact_point == xodr::ContactPoint::kEnd;
      if (strips.meet(road.id, at_end, link.element_id, other_end)) {
        add_unique(at_end ? lane->successors : lane->predecessors, kStripLane);
        joins += at_end;  // each joint counted from the road that ends there
      }
    }
  }
  return joins;
}

/// Which end of `road` touches `junction` (-1: neither, 0 start, 1 end).
int end_at(const xodr::Road& road, const std::string& junction) {
  return names_junction(road.successor, junction)     ? 1
         : names_junction(road.predecessor, junction) ? 0
                                                      : -1;
}

/// Junction connections (§10.4): a laneLink 1 -> 1 where the incoming road's strip meets the
/// connecting (or linked) road's; and for default junctions, a connection from each road
/// leaving the junction whose strip meets a connecting road's end.
size_t link_junctions(xodr::MapData& map, const StripEnds& strips) {
  size_t joins = 0;
  for (xodr::Junction& junction : map.junctions) {
    std::set<std::pair<std::string, std::string>> joined;
    for (xodr::Connection& c : junction.connections) {
      const std::string& target = c.connecting_road.empty() ? c.linked_road : c.connecting_road;
      const xodr::Road* in = strips.road(c.incoming_road);
      const int in_end = in == nullptr ? -1 : end_at(*in, junction.id);
      const bool target_end = c.contact_point == xodr::ContactPoint::kEnd;
      if (in_end < 0 || !strips.meet(in->id, in_end == 1, target, target_end)) {
        continue;
      }
      const bool linked = std::any_of(c.lane_links.begin(), c.lane_links.end(),
                                      [](const xodr::LaneLink& l) { return l.from == kStripLane; });
      if (!linked) {
        c.lane_links.push_back({kStripLane, kStripLane});
        ++joins;
      }
      joined.insert({c.incoming_road, target});
    }
    if (junction.type != xodr::JunctionType::kDefault) {
      continue;
    }
    std::vector<xodr::Connection> added;
    for (const xodr::Road& road : map.roads) {
      // A connecting road of this junction whose successor is a road leaving it.
      if (road.junction != junction.id || strips.road(road.id) == nullptr ||
          road.successor.element_type != xodr::LinkElement::kRoad) {
        continue;
      }
      const xodr::Road* out = strips.road(road.successor.element_id);
      if (out == nullptr || end_at(*out, junction.id) != 0 ||
          joined.count({out->id, road.id}) != 0 || !strips.meet(out->id, false, road.id, true)) {
        continue;
      }
      xodr::Connection connection;
      connection.id = std::to_string(junction.connections.size() + added.size());
      connection.incoming_road = out->id;
      connection.connecting_road = road.id;
      connection.contact_point = xodr::ContactPoint::kEnd;
      connection.lane_links.push_back({kStripLane, kStripLane});
      added.push_back(std::move(connection));
      joined.insert({out->id, road.id});  // the joint is counted with the road link to it
    }
    for (xodr::Connection& connection : added) {
      junction.connections.push_back(std::move(connection));
    }
  }
  return joins;
}

}  // namespace

size_t link_centre_strips(xodr::MapData& map) {
  const StripEnds strips(map);
  return link_roads(map, strips) + link_junctions(map, strips);
}

}  // namespace corsa::ngii::detail
