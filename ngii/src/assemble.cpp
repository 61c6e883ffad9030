#include "assemble.h"

#include <algorithm>
#include <array>
#include <map>
#include <optional>
#include <set>

#include "corsa/xodr/geometry.h"
#include "lane_joints.h"
#include "path_lane_ends.h"
#include "reference_line.h"
#include "sidewalks.h"
#include "union_find.h"

namespace corsa::ngii::detail {
namespace {

int lane_id(int index) { return -index - 1; }

/// Lane pairs (index in `from`, index in `to`) where a lane of `from` ends where one of `to`
/// starts.
std::vector<std::pair<int, int>> lane_pairs(const RoadPlan& from, const RoadPlan& to) {
  std::vector<std::pair<int, int>> pairs;
  for (size_t i = 0; i < from.lanes.size(); ++i) {
    for (size_t j = 0; j < to.lanes.size(); ++j) {
      if (from.lanes[i].end_node == to.lanes[j].start_node) {
        pairs.emplace_back(static_cast<int>(i), static_cast<int>(j));
      }
    }
  }
  return pairs;
}

class Assembler {
 public:
  Assembler(const NetworkPlan& plan, const Network& network, const Origin& origin,
            const ConvertOptions& options, Diagnostics& diagnostics)
      : plan_(plan),
        network_(network),
        origin_(origin),
        options_(options),
        diagnostics_(diagnostics),
        index_(plan) {}

  Assembly run() {
    widths_ = measure_widths(plan_, network_, options_.fallback_lane_width);
    out_.summary.widths_from_marks = widths_.counts[0];
    out_.summary.widths_from_neighbours = widths_.counts[1];
    out_.summary.widths_from_topology = widths_.counts[2];
    out_.summary.fallback_widths = widths_.counts[3];
    number();
    build_roads();
    neighbours();
    link_ordinary_roads();
    link_connecting_roads();
    default_junctions();
    direct_junctions();
    if (options_.sidewalk_width > 0.0) {
      sidewalks();
    }
    return std::move(out_);
  }

 private:
  bool connecting(int road) const { return plan_.roads[static_cast<size_t>(road)].junction >= 0; }

  void number() {
    road_slot_.assign(plan_.roads.size(), -1);
    for (size_t r = 0; r < plan_.roads.size(); ++r) {
      if (!plan_.roads[r].removed) {
        road_slot_[r] = static_cast<int>(out_.roads.size());
        out_.roads.emplace_back();
        out_.roads.back().id = std::to_string(out_.roads.size());
      }
    }
    next_id_ = static_cast<int>(out_.roads.size()) + 1;
    junction_id_.assign(plan_.junctions.size(), "");
    for (size_t j = 0; j < plan_.junctions.size(); ++j) {
      if (!plan_.junctions[j].roads.empty()) {
        junction_id_[j] = std::to_string(next_id_++);
      }
    }
  }

  xodr::Road& road_of(int plan_road) {
    return out_.roads[static_cast<size_t>(road_slot_[static_cast<size_t>(plan_road)])];
  }

  void build_roads() {
    const size_t total = plan_.roads.size();
    std::vector<RoadEndLines> end_lines = road_end_lines(plan_, origin_);
    // Ordinary roads first: junction paths then end on the cross-sections those roads end on
    // (join_ends).
    std::vector<std::optional<BuiltRoad>> built(total);
    size_t done = 0;
    const auto build = [&](size_t r) {
      built[r] =
          build_road(plan_.roads[r], network_, origin_, widths_.lanes[r], end_lines[r], options_);
      if (options_.progress) {
        options_.progress(0.1 + 0.85 * static_cast<double>(++done) / static_cast<double>(total));
      }
    };
    const auto path = [&](size_t r) {
      return plan_.roads[r].junction >= 0 && !plan_.roads[r].absorbed;
    };
    for (size_t r = 0; r < total; ++r) {
      if (!plan_.roads[r].removed && !path(r)) {
        build(r);
      }
    }
    const std::vector<RoadEndLines> own_lines = end_lines;
    const auto end_of = [&](size_t r, bool at_end) -> std::optional<BuiltEnd> {
      if (!built[r] || built[r]->road.plan_view.empty()) {
        return std::nullopt;
      }
      const auto& records = built[r]->road.plan_view;
      const xodr::Geometry& g = at_end ? records.back() : records.front();
      const xodr::RefPoint p = xodr::evaluate_geometry(g, at_end ? g.length : 0.0);
      return BuiltEnd{Vec2{p.x, p.y}, p.hdg};
    };
    // Ordinary roads of one lane (and lanes splitting off it) starting where one other road's
    // one lane (and lanes merging into it) ends, again on its end's cross-section (their ends stay,
    // so the roads they lead into keep theirs).
    std::vector<RoadEndLines> used_lines = end_lines;
    for (const size_t r : join_ends(plan_, end_of, JoinedEnds::kOrdinaryStarts, end_lines)) {
      used_lines[r] = build_joined(r, end_lines[r], own_lines[r], built[r]);
    }
    meet_joined_lanes(used_lines, built);
    // Junction paths take the built widths of the lanes they join at their ends.
    const auto joined_end = [&](const LaneIndex::Ref& ref,
                                bool at_end) -> std::optional<JoinedLaneEnd> {
      const auto end = end_of(static_cast<size_t>(ref.road), at_end);
      if (!end) {
        return std::nullopt;
      }
      const xodr::Road& road = built[static_cast<size_t>(ref.road)]->road;
      const xodr::LaneSection& section =
          at_end ? road.lane_sections.back() : road.lane_sections.front();
      for (const xodr::Lane& lane : section.lanes) {
        if (lane.id == lane_id(ref.lane)) {
          const double s = at_end ? road.length - section.s : 0.0;
          return JoinedLaneEnd{piecewise_value(lane.widths, s), end->heading};
        }
      }
      return std::nullopt;
    };
    match_path_ends(plan_, index_, joined_end, widths_.lanes);
    join_ends(plan_, end_of, JoinedEnds::kJunctionPaths, end_lines);
    std::vector<RoadEndLines> path_lines(total);
    for (size_t r = 0; r < total; ++r) {
      if (!plan_.roads[r].removed && path(r)) {
        path_lines[r] = build_joined(r, end_lines[r], own_lines[r], built[r]);
        if (options_.progress) {
          options_.progress(0.1 + 0.85 * static_cast<double>(++done) / static_cast<double>(total));
        }
      }
    }
    paths_meet_lane_ends(
        plan_, index_, end_lines, path_lines,
        [&](size_t r, const EndBorders& targets) {
          return build_road(plan_.roads[r], network_, origin_, widths_.lanes[r], path_lines[r],
                            options_, targets);
        },
        built);
    ordinary_ends_on_paths(
        plan_, index_, end_lines, path_lines, end_of,
        [&](size_t o, const RoadEndLines& lines) {
          return build_road(plan_.roads[o], network_, origin_, widths_.lanes[o], lines, options_,
                            joint_borders_[o]);
        },
        used_lines, built);
    for (size_t r = 0; r < total; ++r) {
      if (plan_.roads[r].removed) {
        continue;
      }
      const RoadPlan& plan = plan_.roads[r];
      BuiltRoad& built_road = *built[r];
      xodr::Road& road = road_of(static_cast<int>(r));
      const std::string id = road.id;
      road = std::move(built_road.road);
      road.id = id;
      road.name = unique_name(plan);
      road.junction = plan.junction >= 0 ? junction_id_[static_cast<size_t>(plan.junction)] : "-1";
      ConversionSummary& sum = out_.summary;
      sum.lanes += plan.lanes.size();
      sum.geometries += road.plan_view.size();
      sum.kinks += built_road.kinks;
      sum.max_lane_error = std::max(sum.max_lane_error, built_road.source_error);
      sum.max_smoothed_error = std::max(sum.max_smoothed_error, built_road.lane_error);
      sum.max_reference_error = std::max(sum.max_reference_error, built_road.reference_error);
      sum.connecting_roads += plan.junction >= 0;
      for (size_t k = 0; k < built_road.spans.size(); ++k) {
        // Provenance: the A2 links along the lane, in order (what --placements lists too).
        auto& user_data = road.lane_sections.front().lanes[k + 1].user_data;
        for (const BuiltRoad::Span& span : built_road.spans[k]) {
          user_data.push_back(xodr::UserData{"ngii:link", network_.source(span.link).id});
        }
        for (const BuiltRoad::Span& span : built_road.spans[k]) {
          out_.placements.push_back(LinkPlacement{network_.source(span.link).id, id, 0,
                                                  lane_id(static_cast<int>(k)), span.s_start,
                                                  span.s_end});
        }
      }
    }
    out_.summary.roads = out_.roads.size();
  }

  /// A junction path on the lines of the roads it joins (`joined`), else on `own`: a path
  /// that cannot turn onto a joined line within its length (its lane would fold or end off its
  /// link's end, a short path between two lines skewed by 20-50 degrees, or its reference line
  /// would need a corner tighter than the fit's 1 m minimum radius: a kink) keeps its own line
  /// at that end, the other end first. A road whose fitted records fold on its own lines too
  /// (fitted_road_folds: a border or mark slanting across the road at a tight corner of its
  /// records, which the joined lines do not cause) takes the first joined lines on which only
  /// that check fails: its own lines leave the wedge at the joint for no gain.
  RoadEndLines build_joined(size_t r, const RoadEndLines& joined, const RoadEndLines& own,
                            std::optional<BuiltRoad>& out) const {
    RoadEndLines start_only = joined;
    start_only.end = own.end;
    start_only.end_shared = own.end_shared;
    RoadEndLines end_only = joined;
    end_only.start = own.start;
    end_only.start_shared = own.start_shared;
    std::optional<BuiltRoad> records_fold;
    const RoadEndLines* records_fold_lines = nullptr;
    for (const RoadEndLines* lines :
         std::array<const RoadEndLines*, 3>{&joined, &start_only, &end_only}) {
      out = build_road(plan_.roads[r], network_, origin_, widths_.lanes[r], *lines, options_);
      if (out->folds || out->kinks != 0 || out->end_error > kLaneEndMoveLimit) {
        continue;
      }
      if (!fitted_road_folds(out->road)) {
        return *lines;
      }
      if (!records_fold) {
        records_fold = std::move(out);
        records_fold_lines = lines;
      }
    }
    out = build_road(plan_.roads[r], network_, origin_, widths_.lanes[r], own, options_);
    if (records_fold && fitted_road_folds(out->road)) {
      out = std::move(records_fold);
      return *records_fold_lines;
    }
    return own;
  }

  /// Ordinary lanes joined end to start meet edge to edge (lane_joints.h): each ordinary road
  /// whose borders move at an end is built again on the lines it was built on (`lines`), and
  /// kept where it neither folds nor has more kinks than before.
  void meet_joined_lanes(const std::vector<RoadEndLines>& lines,
                         std::vector<std::optional<BuiltRoad>>& built) {
    joint_borders_.assign(plan_.roads.size(), EndBorders{});
    const std::vector<EndBorders> targets =
        joint_borders(plan_, index_, [&](size_t r) -> const xodr::Road* {
          const RoadPlan& road = plan_.roads[r];
          const bool path = road.junction >= 0 && !road.absorbed;
          return road.removed || path || !built[r] ? nullptr : &built[r]->road;
        });
    for (size_t r = 0; r < targets.size(); ++r) {
      if (targets[r].empty()) {
        continue;
      }
      BuiltRoad again = build_road(plan_.roads[r], network_, origin_, widths_.lanes[r], lines[r],
                                   options_, targets[r]);
      if (!again.folds && again.kinks <= built[r]->kinks && !fitted_road_folds(again.road)) {
        built[r] = std::move(again);
        joint_borders_[r] = targets[r];
      }
    }
  }

  /// The leftmost lane's first A2 link, and its last when it has several ("first..last"); a
  /// name taken already gets " #2", " #3", ... (connecting roads sharing their first link).
  std::string unique_name(const RoadPlan& plan) {
    const PlanLane& lane = plan.lanes[0];
    std::string name = network_.source(lane.links.front()).id;
    if (lane.links.size() > 1) {
      name += ".." + network_.source(lane.links.back()).id;
    }
    const int seen = ++names_[name];
    return seen == 1 ? name : name + " #" + std::to_string(seen);
  }

  /// Roads whose lanes continue from (`before`) or into this road's lanes.
  std::set<int> neighbours_of(int road, bool before) const {
    std::set<int> out;
    for (const PlanLane& lane : plan_.roads[static_cast<size_t>(road)].lanes) {
      const auto& refs = before ? index_.ending[static_cast<size_t>(lane.start_node)]
                                : index_.starting[static_cast<size_t>(lane.end_node)];
      for (const auto& ref : refs) {
        out.insert(ref.road);
      }
    }
    return out;
  }

  void neighbours() {
    successors_.resize(plan_.roads.size());
    predecessors_.resize(plan_.roads.size());
    for (size_t r = 0; r < plan_.roads.size(); ++r) {
      if (!plan_.roads[r].removed) {
        successors_[r] = neighbours_of(static_cast<int>(r), false);
        predecessors_[r] = neighbours_of(static_cast<int>(r), true);
      }
    }
  }

  /// The one junction a set of connecting roads belongs to, or -1 (warns when several).
  int junction_of(const std::set<int>& roads, int road) {
    int junction = -1;
    for (const int other : roads) {
      const int j = plan_.roads[static_cast<size_t>(other)].junction;
      if (j >= 0 && junction >= 0 && j != junction) {
        diagnostics_.add_once(
            "ngii-two-junctions:" + std::to_string(road),
            make_warning(network_.layers().link_file, 0,
                         "road " + road_of(road).id + " (" + road_of(road).name +
                             ") touches two junctions at one end; linked to one"));
      }
      if (j >= 0 && junction < 0) {
        junction = j;
      }
    }
    return junction;
  }

  void link_ordinary_roads() {
    direct_slots_ = UnionFind(plan_.roads.size() * 2);
    for (size_t r = 0; r < plan_.roads.size(); ++r) {
      if (plan_.roads[r].removed || connecting(static_cast<int>(r))) {
        continue;
      }
      const int road = static_cast<int>(r);
      for (const bool at_end : {true, false}) {
        const std::set<int>& next = at_end ? successors_[r] : predecessors_[r];
        if (next.empty()) {
          continue;
        }
        xodr::RoadLink& link = at_end ? road_of(road).successor : road_of(road).predecessor;
        if (const int j = junction_of(next, road); j >= 0) {
          link = {xodr::LinkElement::kJunction, junction_id_[static_cast<size_t>(j)],
                  xodr::ContactPoint::kNone};
          continue;
        }
        const int other = *next.begin();
        const std::set<int>& back = at_end ? predecessors_[static_cast<size_t>(other)]
                                           : successors_[static_cast<size_t>(other)];
        if (next.size() == 1 && back.size() == 1 && *back.begin() == road) {
          link = {xodr::LinkElement::kRoad, road_of(other).id,
                  at_end ? xodr::ContactPoint::kStart : xodr::ContactPoint::kEnd};
          link_lanes(road, other, at_end);
          continue;
        }
        // A split or a merge of ordinary lanes: a direct junction (slots 2r = start, 2r+1 = end).
        for (const int o : next) {
          direct_slots_.unite(2 * r + (at_end ? 1 : 0),
                              2 * static_cast<size_t>(o) + (at_end ? 0 : 1));
        }
      }
    }
  }

  void link_lanes(int road, int other, bool at_end) {
    xodr::LaneSection& section = road_of(road).lane_sections.front();
    const auto pairs = at_end ? lane_pairs(plan_.roads[static_cast<size_t>(road)],
                                           plan_.roads[static_cast<size_t>(other)])
                              : lane_pairs(plan_.roads[static_cast<size_t>(other)],
                                           plan_.roads[static_cast<size_t>(road)]);
    for (const auto& [from, to] : pairs) {
      const int mine = at_end ? from : to;
      const int theirs = at_end ? to : from;
      xodr::Lane& lane = section.lanes[static_cast<size_t>(mine) + 1];  // [0] is the centre lane
      (at_end ? lane.successors : lane.predecessors).push_back(lane_id(theirs));
    }
  }

  void link_connecting_roads() {
    for (size_t r = 0; r < plan_.roads.size(); ++r) {
      if (plan_.roads[r].removed || !connecting(static_cast<int>(r))) {
        continue;
      }
      const int road = static_cast<int>(r);
      for (const bool at_end : {true, false}) {
        const std::set<int>& next = at_end ? successors_[r] : predecessors_[r];
        // An ordinary road at this end. Another connecting road may also touch it (a path that
        // goes on through the junction is a separate, longer connecting road): not linked.
        int chosen = -1;
        bool only_connecting = false;
        for (const int other : next) {
          if (!connecting(other)) {
            chosen = chosen < 0 ? other : chosen;
          } else {
            only_connecting = true;
          }
        }
        if (chosen < 0 && only_connecting) {
          diagnostics_.add_once(
              "ngii-chained:" + std::to_string(road),
              make_warning(network_.layers().link_file, 0,
                           "connecting road " + road_of(road).id + " (" + road_of(road).name +
                               ") continues only into another connecting road; that link is "
                               "left out"));
        }
        if (chosen < 0) {
          continue;
        }
        (at_end ? road_of(road).successor : road_of(road).predecessor) =
            xodr::RoadLink{xodr::LinkElement::kRoad, road_of(chosen).id,
                           at_end ? xodr::ContactPoint::kStart : xodr::ContactPoint::kEnd};
        link_lanes(road, chosen, at_end);
      }
    }
  }

  void default_junctions() {
    for (size_t j = 0; j < plan_.junctions.size(); ++j) {
      if (plan_.junctions[j].roads.empty()) {
        continue;
      }
      xodr::Junction junction;
      junction.id = junction_id_[j];
      junction.name = "intersection " + junction.id;
      std::vector<int> members = plan_.junctions[j].roads;
      std::sort(members.begin(), members.end());
      for (const int c : members) {
        for (const int incoming : predecessors_[static_cast<size_t>(c)]) {
          if (connecting(incoming)) {
            continue;
          }
          xodr::Connection connection;
          connection.id = std::to_string(junction.connections.size());
          connection.incoming_road = road_of(incoming).id;
          connection.connecting_road = road_of(c).id;
          connection.contact_point = xodr::ContactPoint::kStart;
          for (const auto& [from, to] : lane_pairs(plan_.roads[static_cast<size_t>(incoming)],
                                                   plan_.roads[static_cast<size_t>(c)])) {
            connection.lane_links.push_back({lane_id(from), lane_id(to)});
          }
          junction.connections.push_back(std::move(connection));
        }
      }
      out_.junctions.push_back(std::move(junction));
      ++out_.summary.junctions;
    }
  }

  void direct_junctions() {
    // Components of joined road-end slots with more than one member.
    std::map<size_t, std::vector<size_t>> components;
    for (size_t slot = 0; slot < direct_slots_.size(); ++slot) {
      components[direct_slots_.find(slot)].push_back(slot);
    }
    for (auto& [root, slots] : components) {
      if (slots.size() < 2) {
        continue;
      }
      xodr::Junction junction;
      junction.id = std::to_string(next_id_++);
      junction.name = "split/merge " + junction.id;
      junction.type = xodr::JunctionType::kDirect;
      std::sort(slots.begin(), slots.end());
      for (const size_t slot : slots) {
        const int road = static_cast<int>(slot / 2);
        const bool at_end = slot % 2 == 1;
        (at_end ? road_of(road).successor : road_of(road).predecessor) =
            xodr::RoadLink{xodr::LinkElement::kJunction, junction.id, xodr::ContactPoint::kNone};
        if (!at_end) {
          continue;
        }
        for (const int linked : successors_[static_cast<size_t>(road)]) {
          xodr::Connection connection;
          connection.id = std::to_string(junction.connections.size());
          connection.incoming_road = road_of(road).id;
          connection.linked_road = road_of(linked).id;
          connection.contact_point = xodr::ContactPoint::kStart;
          for (const auto& [from, to] : lane_pairs(plan_.roads[static_cast<size_t>(road)],
                                                   plan_.roads[static_cast<size_t>(linked)])) {
            connection.lane_links.push_back({lane_id(from), lane_id(to)});
          }
          junction.connections.push_back(std::move(connection));
        }
      }
      out_.junctions.push_back(std::move(junction));
      ++out_.summary.direct_junctions;
    }
  }

  /// Sidewalk lanes (sidewalks.h), joined where their roads join road to road.
  void sidewalks() {
    const std::vector<bool> has =
        add_sidewalks(out_.roads, plan_, road_slot_, network_, options_.sidewalk_width);
    for (size_t r = 0; r < plan_.roads.size(); ++r) {
      if (!has[r]) {
        continue;
      }
      ++out_.summary.sidewalks;
      ++out_.summary.lanes;
      xodr::Road& road = road_of(static_cast<int>(r));
      xodr::Lane& lane = road.lane_sections.front().lanes.back();
      for (const bool at_end : {true, false}) {
        const xodr::RoadLink& link = at_end ? road.successor : road.predecessor;
        const std::set<int>& next = at_end ? successors_[r] : predecessors_[r];
        if (link.element_type != xodr::LinkElement::kRoad || next.size() != 1 ||
            !has[static_cast<size_t>(*next.begin())]) {
          continue;
        }
        const int other = sidewalk_lane_id(road_of(*next.begin()));
        (at_end ? lane.successors : lane.predecessors).push_back(other);
      }
    }
  }

  const NetworkPlan& plan_;
  const Network& network_;
  const Origin& origin_;
  const ConvertOptions& options_;
  Diagnostics& diagnostics_;
  LaneIndex index_;
  PlanWidths widths_;
  /// Per road: where its borders were moved at its ends (meet_joined_lanes), kept for a
  /// road built again later.
  std::vector<EndBorders> joint_borders_;
  Assembly out_;
  std::vector<int> road_slot_;
  std::vector<std::string> junction_id_;
  int next_id_ = 1;
  std::vector<std::set<int>> successors_;
  std::vector<std::set<int>> predecessors_;
  std::map<std::string, int> names_;  ///< road names given so far, with their use count
  UnionFind direct_slots_;            ///< road ends (2 r + at_end) joined at shared nodes
};

}  // namespace

Assembly assemble(const NetworkPlan& plan, const Network& network, const Origin& origin,
                  const ConvertOptions& options, Diagnostics& diagnostics) {
  return Assembler(plan, network, origin, options, diagnostics).run();
}

}  // namespace corsa::ngii::detail
