// Lane graph construction (OpenDRIVE 1.8 §9.4 lane links within a road and across road links,
// §10.4/§10.5 junction laneLinks of default and direct junctions). Links are collected from
// both sides (a lane's successor, the other lane's predecessor, the junction's laneLink) and
// merged, since real files often give only one of them.

#include "corsa/xodr/lane_graph.h"

#include <algorithm>
#include <cmath>
#include <tuple>

#include "corsa/core/diagnostic.h"
#include "corsa/xodr/map.h"
#include "corsa/xodr/map_parts.h"
#include "map_impl.h"
#include "road_eval.h"

namespace corsa::xodr {

std::optional<LaneNode> LaneGraph::find(const LaneRef& lane) const {
  if (lane.road >= road_first_section_.size()) {
    return std::nullopt;
  }
  const uint32_t first_section = road_first_section_[lane.road];
  const uint32_t road_end_section = lane.road + 1 < road_first_section_.size()
                                        ? road_first_section_[lane.road + 1]
                                        : static_cast<uint32_t>(section_first_node_.size() - 1);
  if (first_section + lane.section >= road_end_section) {
    return std::nullopt;
  }
  const uint32_t begin = section_first_node_[first_section + lane.section];
  const uint32_t end = section_first_node_[first_section + lane.section + 1];
  for (uint32_t node = begin; node < end; ++node) {
    if (nodes_[node].lane.lane == lane.lane) {
      return node;
    }
  }
  return std::nullopt;
}

std::span<const LaneEnd> LaneGraph::ends(LaneNode node, bool at_start) const {
  const size_t slot = 2 * static_cast<size_t>(node) + (at_start ? 0 : 1);
  return std::span<const LaneEnd>(end_targets_.data() + end_offsets_[slot],
                                  end_offsets_[slot + 1] - end_offsets_[slot]);
}

class LaneGraphBuilder {
 public:
  LaneGraphBuilder(const Map& map, corsa::Diagnostics& diagnostics)
      : map_(map), diagnostics_(diagnostics) {}

  LaneGraph build() {
    add_nodes();
    for (uint32_t road = 0; road < map_.road_count(); ++road) {
      link_sections(road);
      link_road(road, map_.road(road).predecessor, true);
      link_road(road, map_.road(road).successor, false);
    }
    for (const Junction& junction : map_.data().junctions) {
      for (const Connection& connection : junction.connections) {
        link_connection(junction, connection);
      }
    }
    finish();
    return std::move(graph_);
  }

 private:
  void add_nodes();
  void add_lengths(uint32_t road, uint32_t section, double s0, double s1, uint32_t first);
  void link_sections(uint32_t road);
  void link_road(uint32_t road, const RoadLink& link, bool at_start);
  void link_connection(const Junction& junction, const Connection& connection);
  void finish();

  LaneNode node_of(uint32_t road, uint32_t section, int lane) const {
    const auto node = graph_.find(LaneRef{road, section, lane});
    return node ? *node : kNoLane;
  }
  void join(LaneNode a, bool a_start, LaneNode b, bool b_start, int line) {
    if (a == kNoLane || b == kNoLane) {
      diagnostics_.add_once("missing lane link",
                            corsa::make_warning(map_.data().source_file, line,
                                                "a lane link names a lane that does not exist "
                                                "(ignored; further ones not reported)"));
      return;
    }
    joins_.emplace_back(LaneEnd{a, a_start}, LaneEnd{b, b_start});
  }
  /// World point of a lane's centre at the road's start or end (its first or last section).
  std::optional<WorldPose> lane_end_point(uint32_t road, bool at_start, int lane) const {
    const uint32_t section = at_start ? 0 : last_section(road);
    const double s = at_start ? map_.road(road).lane_sections[0].s : map_.road(road).length;
    const auto span = map_.lane_span_in_section(road, section, s, lane);
    if (!span) {
      return std::nullopt;
    }
    return map_.world_pose(road, s, span->t_center());
  }
  uint32_t last_section(uint32_t road) const {
    return static_cast<uint32_t>(map_.road(road).lane_sections.size() - 1);
  }

  const Map& map_;
  corsa::Diagnostics& diagnostics_;
  LaneGraph graph_;
  std::vector<std::pair<LaneEnd, LaneEnd>> joins_;
};

void LaneGraphBuilder::add_nodes() {
  for (uint32_t road = 0; road < map_.road_count(); ++road) {
    const Road& r = map_.road(road);
    graph_.road_first_section_.push_back(static_cast<uint32_t>(graph_.section_first_node_.size()));
    graph_.road_first_node_.push_back(static_cast<uint32_t>(graph_.nodes_.size()));
    for (uint32_t k = 0; k < r.lane_sections.size(); ++k) {
      graph_.section_first_node_.push_back(static_cast<uint32_t>(graph_.nodes_.size()));
      const LaneSection& section = r.lane_sections[k];
      const double s0 = std::min(section.s, r.length);
      const double s1 = std::max(s0, std::min(map_.section_end(road, k), r.length));
      const uint32_t first = static_cast<uint32_t>(graph_.nodes_.size());
      for (const Lane& lane : section.lanes) {
        if (lane.id == 0) {
          continue;
        }
        LaneGraph::NodeInfo info;
        info.lane = LaneRef{road, k, lane.id};
        info.type = lane.type;
        info.s_start = s0;
        info.s_end = s1;
        const bool right_hand = r.rule == TrafficRule::kRightHand;
        info.direction = lane.type == LaneType::kBidirectional ? TravelDirection::kBoth
                         : (lane.id < 0) == right_hand         ? TravelDirection::kForward
                                                               : TravelDirection::kBackward;
        graph_.nodes_.push_back(info);
      }
      add_lengths(road, k, s0, s1, first);
    }
  }
  graph_.section_first_node_.push_back(static_cast<uint32_t>(graph_.nodes_.size()));
  const size_t n = graph_.nodes_.size();
  graph_.left_.assign(n, kNoLane);
  graph_.right_.assign(n, kNoLane);
  for (LaneNode node = 0; node < n; ++node) {
    const LaneRef& ref = graph_.nodes_[node].lane;
    const int left = ref.lane == -1 ? 1 : ref.lane + 1;
    const int right = ref.lane == 1 ? -1 : ref.lane - 1;
    graph_.left_[node] = node_of(ref.road, ref.section, left);
    graph_.right_[node] = node_of(ref.road, ref.section, right);
  }
}

// Length of each lane's centre line t_c(s): ∫ sqrt((1 - κ t_c)² + t_c'²) ds (the speed of
// r(s) + t_c(s) N(s) for an arc-length reference line), by Simpson's rule on samples <= 2 m
// apart, with t_c' from central differences of the samples.
void LaneGraphBuilder::add_lengths(uint32_t road, uint32_t section, double s0, double s1,
                                   uint32_t first) {
  const LaneSection& lanes = map_.road(road).lane_sections[section];
  const int steps = 2 * std::max(1, static_cast<int>(std::ceil((s1 - s0) / 4.0)));
  const double h = (s1 - s0) / steps;
  const size_t count = lanes.lanes.size();
  std::vector<double> t((steps + 1) * count);
  std::vector<double> curvature(steps + 1);
  LaneSpan spans[detail::kMaxLanesPerSection];
  size_t n = 0;
  for (int i = 0; i <= steps; ++i) {
    const double s = s0 + h * i;
    curvature[i] = reference_curvature(map_, road, s);
    n = detail::compute_spans(lanes, s, detail::section_lane_offset(map_, road, section, s), spans);
    for (size_t j = 0; j < n; ++j) {
      t[i * count + j] = spans[j].t_center();
    }
  }
  if (h <= 0.0) {
    return;
  }
  for (size_t j = 0; j < n; ++j) {
    double total = 0.0;
    for (int i = 0; i <= steps; ++i) {
      const int lo = std::max(0, i - 1);
      const int hi = std::min(steps, i + 1);
      const double slope = (t[hi * count + j] - t[lo * count + j]) / (h * (hi - lo));
      const double along = 1.0 - curvature[i] * t[i * count + j];
      const double weight = (i == 0 || i == steps) ? 1.0 : (i % 2 == 1 ? 4.0 : 2.0);
      total += weight * std::sqrt(along * along + slope * slope);
    }
    graph_.nodes_[first + j].length = total * h / 3.0;
  }
}

void LaneGraphBuilder::link_sections(uint32_t road) {
  const Road& r = map_.road(road);
  for (uint32_t k = 0; k + 1 < r.lane_sections.size(); ++k) {
    for (const Lane& lane : r.lane_sections[k].lanes) {
      for (const int next : lane.successors) {
        join(node_of(road, k, lane.id), false, node_of(road, k + 1, next), true, lane.line);
      }
    }
    for (const Lane& lane : r.lane_sections[k + 1].lanes) {
      for (const int previous : lane.predecessors) {
        join(node_of(road, k + 1, lane.id), true, node_of(road, k, previous), false, lane.line);
      }
    }
  }
}

void LaneGraphBuilder::link_road(uint32_t road, const RoadLink& link, bool at_start) {
  if (link.element_type != LinkElement::kRoad) {
    return;  // junction links come from the junction's connections
  }
  const auto other = map_.find_road(link.element_id);
  if (!other) {
    return;
  }
  const Road& r = map_.road(road);
  const uint32_t section = at_start ? 0 : last_section(road);
  const uint32_t other_road = static_cast<uint32_t>(*other);
  bool other_start = link.contact_point != ContactPoint::kEnd;
  // Repair a contact point that contradicts the geometry (as in the junction case below).
  for (const Lane& lane : r.lane_sections[section].lanes) {
    const auto& targets = at_start ? lane.predecessors : lane.successors;
    if (targets.empty()) {
      continue;
    }
    const auto here = lane_end_point(road, at_start, lane.id);
    const auto named = lane_end_point(other_road, other_start, targets.front());
    const auto flipped = lane_end_point(other_road, !other_start, targets.front());
    if (here && named && flipped && std::hypot(here->x - named->x, here->y - named->y) > 2.0 &&
        std::hypot(here->x - flipped->x, here->y - flipped->y) < 0.5) {
      diagnostics_.add_once(
          "contact:" + r.id,
          corsa::make_warning(
              map_.data().source_file, r.line,
              "road '" + r.id + "': its " + (at_start ? "predecessor" : "successor") + " road '" +
                  link.element_id + "' meets it at its " + (other_start ? "end" : "start") +
                  ", not at the contactPoint " + (other_start ? "start" : "end") + "; using the " +
                  (other_start ? "end" : "start")));
      other_start = !other_start;
    }
    break;
  }
  const uint32_t other_section = other_start ? 0 : last_section(other_road);
  for (const Lane& lane : r.lane_sections[section].lanes) {
    for (const int target : at_start ? lane.predecessors : lane.successors) {
      join(node_of(road, section, lane.id), at_start, node_of(other_road, other_section, target),
           other_start, lane.line);
    }
  }
}

void LaneGraphBuilder::link_connection(const Junction& junction, const Connection& connection) {
  const auto incoming = map_.find_road(connection.incoming_road);
  const std::string& target_id =
      connection.connecting_road.empty() ? connection.linked_road : connection.connecting_road;
  const auto target = map_.find_road(target_id);
  if (!incoming || !target) {
    return;
  }
  // Which end of the incoming road touches this junction.
  const Road& in = map_.road(*incoming);
  bool in_start;
  if (in.successor.element_type == LinkElement::kJunction &&
      in.successor.element_id == junction.id) {
    in_start = false;
  } else if (in.predecessor.element_type == LinkElement::kJunction &&
             in.predecessor.element_id == junction.id) {
    in_start = true;
  } else {
    diagnostics_.add_once(
        "connection end:" + junction.id,
        corsa::make_warning(map_.data().source_file, connection.line,
                            "junction '" + junction.id + "': incoming road '" + in.id +
                                "' is not linked to the junction; its laneLinks are ignored"));
    return;
  }
  const uint32_t in_road = static_cast<uint32_t>(*incoming);
  const uint32_t out_road = static_cast<uint32_t>(*target);
  const bool target_start = connection.contact_point != ContactPoint::kEnd;
  const uint32_t target_section = target_start ? 0 : last_section(out_road);
  if (!connection.lane_links.empty()) {
    // Repair: some files link the wrong end of the incoming road to the junction (ASAM's
    // Ex_LHT-Complex-X-Junction: road 3 names the junction as predecessor, but its end is where
    // the connecting roads begin). When the named end is far from the connecting lane and the
    // other end meets it, the other end is used, with a warning.
    const LaneLink& link = connection.lane_links.front();
    const auto meet = [&](bool start) {
      const auto a = lane_end_point(in_road, start, link.from);
      const auto b = lane_end_point(out_road, target_start, link.to);
      return a && b ? std::hypot(a->x - b->x, a->y - b->y) : -1.0;
    };
    const double named = meet(in_start);
    const double other = meet(!in_start);
    if (named > 2.0 && other >= 0.0 && other < 0.5) {
      diagnostics_.add_once(
          "junction end:" + junction.id + ":" + in.id,
          corsa::make_warning(map_.data().source_file, connection.line,
                              "junction '" + junction.id + "': incoming road '" + in.id +
                                  "' meets the junction at its " + (in_start ? "end" : "start") +
                                  ", not at the " + (in_start ? "start" : "end") +
                                  " its link names; using the " + (in_start ? "end" : "start")));
      in_start = !in_start;
    }
  }
  const uint32_t in_section = in_start ? 0 : last_section(in_road);
  for (const LaneLink& link : connection.lane_links) {
    join(node_of(in_road, in_section, link.from), in_start,
         node_of(out_road, target_section, link.to), target_start, connection.line);
  }
}

void LaneGraphBuilder::finish() {
  const auto slot = [](const LaneEnd& end) {
    return 2 * size_t{end.node} + (end.at_start ? 0 : 1);
  };
  std::vector<std::pair<size_t, LaneEnd>> directed;
  directed.reserve(2 * joins_.size());
  for (const auto& [a, b] : joins_) {
    directed.emplace_back(slot(a), b);
    directed.emplace_back(slot(b), a);
  }
  const auto key = [](const std::pair<size_t, LaneEnd>& x) {
    return std::make_tuple(x.first, x.second.node, x.second.at_start);
  };
  std::sort(directed.begin(), directed.end(),
            [&](const auto& x, const auto& y) { return key(x) < key(y); });
  directed.erase(std::unique(directed.begin(), directed.end()), directed.end());
  const size_t slots = 2 * graph_.nodes_.size();
  graph_.end_offsets_.assign(slots + 1, 0);
  for (const auto& [s, end] : directed) {
    ++graph_.end_offsets_[s + 1];
  }
  for (size_t i = 0; i < slots; ++i) {
    graph_.end_offsets_[i + 1] += graph_.end_offsets_[i];
  }
  graph_.end_targets_.reserve(directed.size());
  for (const auto& [s, end] : directed) {
    graph_.end_targets_.push_back(end);
  }
  graph_.join_count_ = directed.size() / 2;
}

namespace detail {

LaneGraph build_lane_graph(const Map& map, corsa::Diagnostics& diagnostics) {
  return LaneGraphBuilder(map, diagnostics).build();
}

}  // namespace detail
}  // namespace corsa::xodr
