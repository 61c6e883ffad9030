#include "network_plan.h"

#include <algorithm>
#include <functional>
#include <set>
#include <string>

#include "polyline.h"
#include "staggered_ends.h"
#include "union_find.h"

namespace corsa::ngii::detail {
namespace {

/// Junction paths beyond this many stop the enumeration (a safeguard against pathological
/// branching; real intersections have a few dozen).
constexpr size_t kMaxPaths = 100000;
/// An ordinary road at a mixed end no longer than this (m) joins the junction whole; a longer
/// one has its first (or last) kCutLength metres cut off into the junction.
constexpr double kWholeLength = 25.0;
constexpr double kCutLength = 10.0;

PlanLane lane_of_link(const Network& network, int link) {
  const LinkState& state = network.links[static_cast<size_t>(link)];
  return PlanLane{state.points, {link}, {0.0}, state.from, state.to, {}, {}, {}, {}};
}

/// Appends `tail` to `head` (dropping a repeated joint vertex).
void append_points(std::vector<Point3>& head, const std::vector<Point3>& tail) {
  size_t first = 0;
  if (!head.empty() && !tail.empty() && norm(xy(head.back()) - xy(tail.front())) < 0.01) {
    first = 1;
  }
  head.insert(head.end(), tail.begin() + static_cast<std::ptrdiff_t>(first), tail.end());
}

/// Every path through intersection links from an entry (reached from an ordinary link, or from
/// nothing) to an exit (leading to an ordinary link, or to nothing).
class PathFinder {
 public:
  PathFinder(const Network& network, Diagnostics& diagnostics)
      : network_(network), diagnostics_(diagnostics) {}

  std::vector<std::vector<int>> run() {
    const int n = static_cast<int>(network_.size());
    covered_.assign(static_cast<size_t>(n), false);
    // Paths to exits first; then, for links no such path covers (a roundabout ring), paths
    // that close a loop; then paths from links only reachable from inside a cycle.
    for (const Mode mode : {Mode::kExits, Mode::kLoops}) {
      for (int link = 0; link < n; ++link) {
        if (junction_link(link) && is_entry(link)) {
          walk({link}, mode);
        }
      }
    }
    for (int link = 0; link < n; ++link) {
      if (junction_link(link) && !covered_[static_cast<size_t>(link)]) {
        walk({link}, Mode::kAll);
      }
    }
    return std::move(paths_);
  }

 private:
  bool junction_link(int link) const {
    return network_.is_junction(link) && !network_.links[static_cast<size_t>(link)].removed;
  }

  bool is_entry(int link) const {
    const auto& before =
        network_.ending[static_cast<size_t>(network_.links[static_cast<size_t>(link)].from)];
    if (before.empty()) {
      return true;
    }
    return std::any_of(before.begin(), before.end(), [&](int b) { return !junction_link(b); });
  }

  enum class Mode { kExits, kLoops, kAll };

  void walk(std::vector<int> path, Mode mode) {
    if (paths_.size() >= kMaxPaths) {
      if (!truncated_) {
        truncated_ = true;
        diagnostics_.add(make_warning(network_.layers().link_file, 0,
                                      "too many paths through intersection links; the rest "
                                      "are left out"));
      }
      return;
    }
    const int current = path.back();
    const auto& after =
        network_.starting[static_cast<size_t>(network_.links[static_cast<size_t>(current)].to)];
    bool exits = after.empty();
    std::vector<int> next;
    for (const int a : after) {
      if (!junction_link(a)) {
        exits = true;
      } else if (std::find(path.begin(), path.end(), a) == path.end()) {
        next.push_back(a);
      }
    }
    // A path that only closes a loop (every successor already on it: once round a roundabout)
    // leads nowhere new; it is kept only when it covers links no other path does.
    const bool closes_loop = !exits && next.empty();
    const bool uncovered = std::any_of(
        path.begin(), path.end(), [&](int link) { return !covered_[static_cast<size_t>(link)]; });
    const bool keep =
        (exits && mode != Mode::kLoops) || (closes_loop && uncovered && mode != Mode::kExits);
    if (keep) {
      for (const int link : path) {
        covered_[static_cast<size_t>(link)] = true;
      }
      paths_.push_back(path);
    }
    for (const int a : next) {
      std::vector<int> longer = path;
      longer.push_back(a);
      walk(std::move(longer), mode);
    }
  }

  const Network& network_;
  Diagnostics& diagnostics_;
  std::vector<std::vector<int>> paths_;
  std::vector<bool> covered_;
  bool truncated_ = false;
};

RoadPlan path_plan(const Network& network, const std::vector<int>& path) {
  PlanLane lane;
  for (const int link : path) {
    const LinkState& state = network.links[static_cast<size_t>(link)];
    lane.links.push_back(link);
    lane.link_starts.push_back(Polyline(lane.points).length());
    append_points(lane.points, state.points);
  }
  // link_starts[0] measured on an empty polyline is 0; later ones at the joints.
  lane.start_node = network.links[static_cast<size_t>(path.front())].from;
  lane.end_node = network.links[static_cast<size_t>(path.back())].to;
  RoadPlan plan;
  plan.lanes.push_back(std::move(lane));
  return plan;
}

struct Box {
  double x0, y0, x1, y1;
  bool overlaps(const Box& o) const { return x0 <= o.x1 && o.x0 <= x1 && y0 <= o.y1 && o.y0 <= y1; }
};

Box box_of(const std::vector<Point3>& points) {
  Box box{points[0].x, points[0].y, points[0].x, points[0].y};
  for (const Point3& p : points) {
    box = Box{std::min(box.x0, p.x), std::min(box.y0, p.y), std::max(box.x1, p.x),
              std::max(box.y1, p.y)};
  }
  return box;
}

bool segments_cross(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
  const double d1 = cross(b - a, c - a);
  const double d2 = cross(b - a, d - a);
  const double d3 = cross(d - c, a - c);
  const double d4 = cross(d - c, b - c);
  return ((d1 > 0) != (d2 > 0)) && ((d3 > 0) != (d4 > 0));
}

bool polylines_cross(const std::vector<Point3>& a, const std::vector<Point3>& b) {
  for (size_t i = 0; i + 1 < a.size(); ++i) {
    for (size_t j = 0; j + 1 < b.size(); ++j) {
      if (segments_cross(xy(a[i]), xy(a[i + 1]), xy(b[j]), xy(b[j + 1]))) {
        return true;
      }
    }
  }
  return false;
}

class Planner {
 public:
  Planner(const Network& network, bool several_incoming, Diagnostics& diagnostics)
      : network_(network), several_incoming_(several_incoming), diagnostics_(diagnostics) {}

  NetworkPlan run(const LateralStructure& lateral) {
    plan_.node_keys = static_cast<int>(network_.layers().nodes.size());
    for (const LaneRun& run : lateral.runs) {
      if (network_.is_junction(run.links.front())) {
        continue;
      }
      RoadPlan road;
      for (size_t k = 0; k < run.links.size(); ++k) {
        road.lanes.push_back(lane_of_link(network_, run.links[k]));
        road.lanes.back().start_shape = run.starts[k];
        road.lanes.back().end_shape = run.ends[k];
      }
      plan_.roads.push_back(std::move(road));
    }
    const size_t first_connecting = plan_.roads.size();
    for (const auto& path : PathFinder(network_, diagnostics_).run()) {
      plan_.roads.push_back(path_plan(network_, path));
    }
    cluster(first_connecting);
    // Each pass absorbs one mixed end; every absorption removes one, so this terminates.
    for (size_t guard = 0; guard < 100000 && resolve_mixed_ends(); ++guard) {
    }
    join_touching_junctions();
    for (size_t j = 0; j < plan_.junctions.size(); ++j) {
      chain_connecting_roads(static_cast<int>(j));
    }
    trim_staggered_ends(plan_);
    trim_off_line_ends(plan_);
    add_context();
    return std::move(plan_);
  }

  /// Fills every lane's lead_in / lead_out from its best-aligned neighbour at each end.
  void add_context() {
    const LaneIndex index(plan_);
    for (RoadPlan& road : plan_.roads) {
      for (PlanLane& lane : road.lanes) {
        lane.lead_in = neighbour_piece(index.ending[static_cast<size_t>(lane.start_node)], lane,
                                       /*before=*/true);
        lane.lead_out = neighbour_piece(index.starting[static_cast<size_t>(lane.end_node)], lane,
                                        /*before=*/false);
      }
    }
  }

  std::vector<Point3> neighbour_piece(const std::vector<LaneIndex::Ref>& refs, const PlanLane& lane,
                                      bool before) const {
    constexpr double kContext = 6.0;  // m
    const Polyline own(lane.points);
    const Vec2 own_direction = before ? own.direction(0.0) : own.direction(own.length());
    const PlanLane* best = nullptr;
    double best_alignment = 0.5;  // cos of the largest accepted turn (60 degrees)
    for (const auto& ref : refs) {
      const PlanLane& other =
          plan_.roads[static_cast<size_t>(ref.road)].lanes[static_cast<size_t>(ref.lane)];
      if (&other == &lane) {
        continue;
      }
      const Polyline line(other.points);
      const Vec2 direction = before ? line.direction(line.length()) : line.direction(0.0);
      const double alignment = dot(direction, own_direction);
      if (alignment > best_alignment) {
        best_alignment = alignment;
        best = &other;
      }
    }
    if (best == nullptr) {
      return {};
    }
    const Polyline line(best->points);
    return before ? line.slice(std::max(0.0, line.length() - kContext), line.length())
                  : line.slice(0.0, std::min(kContext, line.length()));
  }

 private:
  /// Groups the connecting roads into junctions.
  void cluster(size_t first) {
    const size_t count = plan_.roads.size() - first;
    UnionFind groups(count);
    const LaneIndex index(plan_);
    // Paths sharing a link, an approach road end or an exit road start, or a bare node.
    std::vector<int> by_link(network_.size(), -1);
    std::vector<int> by_key(static_cast<size_t>(plan_.node_keys) * 2, -1);
    const auto join_key = [&](size_t key, size_t member) {
      int& slot = by_key[key];
      if (slot < 0) {
        slot = static_cast<int>(member);
      } else {
        groups.unite(static_cast<size_t>(slot), member);
      }
    };
    for (size_t i = 0; i < count; ++i) {
      const PlanLane& lane = plan_.roads[first + i].lanes[0];
      for (const int link : lane.links) {
        int& slot = by_link[static_cast<size_t>(link)];
        if (slot < 0) {
          slot = static_cast<int>(i);
        } else {
          groups.unite(static_cast<size_t>(slot), i);
        }
      }
      join_key(static_cast<size_t>(lane.start_node) * 2, i);
      join_key(static_cast<size_t>(lane.end_node) * 2 + 1, i);
      // Approach and exit roads: every end of the same road joins the same junction.
      for (const auto& ref : index.ending[static_cast<size_t>(lane.start_node)]) {
        if (static_cast<size_t>(ref.road) < first) {
          join_key(
              static_cast<size_t>(plan_.roads[static_cast<size_t>(ref.road)].lanes[0].end_node) *
                      2 +
                  1,
              i);
        }
      }
      for (const auto& ref : index.starting[static_cast<size_t>(lane.end_node)]) {
        if (static_cast<size_t>(ref.road) < first) {
          join_key(
              static_cast<size_t>(plan_.roads[static_cast<size_t>(ref.road)].lanes[0].start_node) *
                  2,
              i);
        }
      }
    }
    // Crossing paths belong to the same intersection.
    std::vector<Box> boxes;
    for (size_t i = 0; i < count; ++i) {
      boxes.push_back(box_of(plan_.roads[first + i].lanes[0].points));
    }
    for (size_t i = 0; i < count; ++i) {
      for (size_t j = i + 1; j < count; ++j) {
        if (groups.find(i) != groups.find(j) && boxes[i].overlaps(boxes[j]) &&
            polylines_cross(plan_.roads[first + i].lanes[0].points,
                            plan_.roads[first + j].lanes[0].points)) {
          groups.unite(i, j);
        }
      }
    }
    std::vector<int> junction_of(count, -1);
    for (size_t i = 0; i < count; ++i) {
      const size_t root = groups.find(i);
      if (junction_of[root] < 0) {
        junction_of[root] = static_cast<int>(plan_.junctions.size());
        plan_.junctions.emplace_back();
      }
      const int j = junction_of[root];
      plan_.roads[first + i].junction = j;
      plan_.junctions[static_cast<size_t>(j)].roads.push_back(static_cast<int>(first + i));
    }
  }

  /// One pass over approach ends / exit starts that lead both into a junction and straight on
  /// to an ordinary road; returns whether anything changed.
  bool resolve_mixed_ends() {
    bool changed = false;
    const LaneIndex index(plan_);
    for (size_t r = 0; r < plan_.roads.size(); ++r) {
      if (plan_.roads[r].removed) {
        continue;
      }
      if (plan_.roads[r].junction >= 0) {
        if (resolve_split_exit(index, static_cast<int>(r))) {
          return true;
        }
        continue;
      }
      for (const bool at_end : {true, false}) {
        std::set<int> junctions;
        std::set<int> ordinary;
        for (const PlanLane& lane : plan_.roads[r].lanes) {
          const int key = at_end ? lane.end_node : lane.start_node;
          for (const auto& ref : at_end ? index.starting[static_cast<size_t>(key)]
                                        : index.ending[static_cast<size_t>(key)]) {
            const int j = plan_.roads[static_cast<size_t>(ref.road)].junction;
            (j >= 0 ? junctions : ordinary).insert(j >= 0 ? j : ref.road);
          }
        }
        const int junction = junctions.empty() ? -1 : *junctions.begin();
        if (junctions.size() > 1) {
          // One road end leads into two junctions: they are one intersection.
          for (const int other : junctions) {
            if (other != junction) {
              merge_junctions(junction, other);
            }
          }
          return true;
        }
        if (junctions.empty() || ordinary.empty()) {
          continue;
        }
        for (const int other : ordinary) {
          absorb(other, junction, /*head=*/at_end);
          changed = true;
        }
        if (changed) {
          return true;  // indices changed: rebuild the lane index
        }
      }
    }
    return changed;
  }

  /// A connecting road lane that leads into (or comes from) several ordinary roads cannot name
  /// them all as its successor (or predecessor): their first (last) metres join the junction,
  /// where each gets its own chain. Returns whether anything changed.
  bool resolve_split_exit(const LaneIndex& index, int road) {
    const RoadPlan& plan = plan_.roads[static_cast<size_t>(road)];
    for (const bool at_end : {true, false}) {
      for (const PlanLane& lane : plan.lanes) {
        const int key = at_end ? lane.end_node : lane.start_node;
        std::set<int> ordinary;
        for (const auto& ref : at_end ? index.starting[static_cast<size_t>(key)]
                                      : index.ending[static_cast<size_t>(key)]) {
          if (plan_.roads[static_cast<size_t>(ref.road)].junction < 0) {
            ordinary.insert(ref.road);
          }
        }
        if (ordinary.size() > 1) {
          const int junction = plan.junction;
          for (const int other : ordinary) {
            absorb(other, junction, /*head=*/at_end);
          }
          return true;
        }
      }
    }
    return false;
  }

  /// Moves ordinary road `road` (or its first/last kCutLength metres) into `junction`.
  void absorb(int road, int junction, bool head) {
    RoadPlan& plan = plan_.roads[static_cast<size_t>(road)];
    const double length = Polyline(plan.lanes[0].points).length();
    if (length <= kWholeLength) {
      plan.junction = junction;
      plan.absorbed = true;
      plan_.junctions[static_cast<size_t>(junction)].roads.push_back(road);
      return;
    }
    RoadPlan piece = cut(plan, head ? kCutLength : length - kCutLength, head);
    piece.junction = junction;
    piece.absorbed = true;
    plan_.junctions[static_cast<size_t>(junction)].roads.push_back(
        static_cast<int>(plan_.roads.size()));
    plan_.roads.push_back(std::move(piece));
  }

  /// Junctions whose connecting roads lead into each other are one junction.
  void join_touching_junctions() {
    for (bool changed = true; changed;) {
      changed = false;
      const LaneIndex index(plan_);
      for (const RoadPlan& road : plan_.roads) {
        if (road.removed || road.junction < 0) {
          continue;
        }
        for (const PlanLane& lane : road.lanes) {
          for (const auto& ref : index.starting[static_cast<size_t>(lane.end_node)]) {
            const int other = plan_.roads[static_cast<size_t>(ref.road)].junction;
            if (other >= 0 && other != road.junction) {
              merge_junctions(road.junction, other);
              changed = true;
            }
          }
        }
        if (changed) {
          break;
        }
      }
    }
  }

  /// Rebuilds the connecting roads of junction `j` so that none leads into another: every lane
  /// becomes a single-lane piece, and every chain of pieces from an approach (or nothing) to an
  /// exit (or nothing) becomes one connecting road (OpenDRIVE 1.8 §10.4: connecting roads join
  /// incoming and outgoing roads). A piece on several chains is repeated in each. The lanes of
  /// an ordinary road taken into the junction whole stay one connecting road of several lanes
  /// where each is a chain of its own (side_by_side_runs).
  void chain_connecting_roads(int j) {
    std::vector<int> pieces;
    std::vector<std::vector<int>> groups;  // the pieces of each absorbed road of several lanes
    for (const int r : plan_.junctions[static_cast<size_t>(j)].roads) {
      if (plan_.roads[static_cast<size_t>(r)].removed) {
        continue;
      }
      // Moved out first: the pushes below may reallocate plan_.roads, so no reference into it
      // is kept across them.
      std::vector<PlanLane> lanes = std::move(plan_.roads[static_cast<size_t>(r)].lanes);
      const bool absorbed = plan_.roads[static_cast<size_t>(r)].absorbed;
      plan_.roads[static_cast<size_t>(r)].removed = true;
      if (absorbed && lanes.size() > 1) {
        groups.emplace_back();
      }
      for (PlanLane& lane : lanes) {
        RoadPlan single;
        single.junction = j;
        single.absorbed = absorbed;
        single.lanes.push_back(std::move(lane));
        if (absorbed && lanes.size() > 1) {
          groups.back().push_back(static_cast<int>(plan_.roads.size()));
        }
        pieces.push_back(static_cast<int>(plan_.roads.size()));
        plan_.roads.push_back(std::move(single));
      }
    }
    const LaneIndex index(plan_);
    const auto lane_of = [&](int piece) -> const PlanLane& {
      return plan_.roads[static_cast<size_t>(piece)].lanes[0];
    };
    const auto in_junction = [&](int road) {
      return plan_.roads[static_cast<size_t>(road)].junction == j;
    };
    // Intersection paths are already complete from approach to exit: chains only run through
    // absorbed pieces of ordinary roads (path -> piece, piece -> path, piece -> piece).
    const auto chains_into = [&](int from, int to) {
      return in_junction(from) && in_junction(to) &&
             (plan_.roads[static_cast<size_t>(from)].absorbed ||
              plan_.roads[static_cast<size_t>(to)].absorbed);
    };
    std::vector<std::vector<int>> chains;
    std::set<int> covered;
    std::function<void(std::vector<int>&)> walk = [&](std::vector<int>& chain) {
      if (chains.size() >= kMaxPaths) {
        return;
      }
      bool exits = false;
      std::vector<int> next;
      for (const auto& ref : index.starting[static_cast<size_t>(lane_of(chain.back()).end_node)]) {
        if (!in_junction(ref.road)) {
          exits = true;
        } else if (chains_into(chain.back(), ref.road) &&
                   std::find(chain.begin(), chain.end(), ref.road) == chain.end()) {
          next.push_back(ref.road);
        }
      }
      if (exits || next.empty()) {
        chains.push_back(chain);
        covered.insert(chain.begin(), chain.end());
      }
      for (const int n : next) {
        chain.push_back(n);
        walk(chain);
        chain.pop_back();
      }
    };
    for (const bool entries_only : {true, false}) {
      for (const int piece : pieces) {
        const auto& before = index.ending[static_cast<size_t>(lane_of(piece).start_node)];
        // A chain starts at a piece entered from outside the junction, or from nothing it
        // chains from (other intersection paths ending here are separate connecting roads).
        const bool entry = std::any_of(before.begin(), before.end(),
                                       [&](auto r) { return !in_junction(r.road); }) ||
                           std::none_of(before.begin(), before.end(),
                                        [&](auto r) { return chains_into(r.road, piece); });
        if ((entries_only && entry) || (!entries_only && !covered.contains(piece))) {
          std::vector<int> chain{piece};
          walk(chain);
        }
      }
    }
    JunctionPlan& junction = plan_.junctions[static_cast<size_t>(j)];
    junction.roads.clear();
    for (const int piece : pieces) {
      plan_.roads[static_cast<size_t>(piece)].removed = true;
    }
    const std::vector<std::vector<int>> runs = side_by_side_runs(groups, chains, index, j);
    std::vector<int> run_of(plan_.roads.size(), -1);
    for (size_t g = 0; g < runs.size(); ++g) {
      for (const int piece : runs[g]) {
        run_of[static_cast<size_t>(piece)] = static_cast<int>(g);
      }
    }
    std::set<int> written;  // runs already written
    for (const auto& chain : chains) {
      if (const int g = chain.size() == 1 ? run_of[static_cast<size_t>(chain.front())] : -1;
          g >= 0) {
        if (written.insert(g).second) {
          RoadPlan road;
          road.junction = j;
          for (const int piece : runs[static_cast<size_t>(g)]) {
            road.lanes.push_back(lane_of(piece));
          }
          junction.roads.push_back(static_cast<int>(plan_.roads.size()));
          plan_.roads.push_back(std::move(road));
        }
        continue;
      }
      RoadPlan road;
      road.junction = j;
      PlanLane lane = lane_of(chain.front());
      for (size_t k = 1; k < chain.size(); ++k) {
        const PlanLane& next = lane_of(chain[k]);
        const double shift = Polyline(lane.points).length();
        for (size_t i = 0; i < next.links.size(); ++i) {
          lane.links.push_back(next.links[i]);
          lane.link_starts.push_back(shift + next.link_starts[i]);
        }
        append_points(lane.points, next.points);
        lane.end_node = next.end_node;
      }
      road.lanes.push_back(std::move(lane));
      junction.roads.push_back(static_cast<int>(plan_.roads.size()));
      plan_.roads.push_back(std::move(road));
    }
  }

  /// The lanes of junction `j` that stay one connecting road of several lanes: runs of
  /// neighbouring lanes of an ordinary road taken into the junction whole (`groups`: its
  /// pieces, left to right), side by side in the survey, so that a vehicle may change between
  /// them. A run takes only lanes that are a chain of their own (neither following nor leading
  /// into another piece of the junction), that each come from at most one road and lead into
  /// at most one, and that all lead into the same road (a connecting road has one road after
  /// it, OpenDRIVE 1.8 §10.3 road linkage). With `several_incoming_` they may come from
  /// different roads, each feeding the connecting road through a <connection> of its own
  /// (OpenDRIVE 1.8 §12.4: one per incoming road); without it they come from the same road,
  /// since OpenDRIVE 1.7 §10.3 represents each connecting road by exactly one <connection>.
  /// The other lanes stay one-lane paths.
  std::vector<std::vector<int>> side_by_side_runs(const std::vector<std::vector<int>>& groups,
                                                  const std::vector<std::vector<int>>& chains,
                                                  const LaneIndex& index, int j) const {
    std::vector<int> on_chains(plan_.roads.size(), 0);       // chains through the piece
    std::vector<bool> on_longer(plan_.roads.size(), false);  // one of them has other pieces
    for (const auto& chain : chains) {
      for (const int piece : chain) {
        ++on_chains[static_cast<size_t>(piece)];
        on_longer[static_cast<size_t>(piece)] =
            on_longer[static_cast<size_t>(piece)] || chain.size() > 1;
      }
    }
    // The roads outside the junction that end where the piece starts (or start where it ends).
    const auto outside = [&](int piece, bool at_end) {
      const PlanLane& lane = plan_.roads[static_cast<size_t>(piece)].lanes[0];
      const auto& refs = at_end ? index.starting[static_cast<size_t>(lane.end_node)]
                                : index.ending[static_cast<size_t>(lane.start_node)];
      std::set<int> roads;
      for (const auto& ref : refs) {
        if (plan_.roads[static_cast<size_t>(ref.road)].junction != j) {
          roads.insert(ref.road);
        }
      }
      return roads;
    };
    const auto runs_on = [&](int piece, int next) {
      return (several_incoming_ || outside(piece, false) == outside(next, false)) &&
             outside(piece, true) == outside(next, true) && outside(piece, false).size() <= 1 &&
             outside(next, false).size() <= 1 && outside(piece, true).size() <= 1;
    };
    std::vector<std::vector<int>> runs;
    for (const auto& group : groups) {
      std::vector<int> run;
      for (const int piece : group) {
        const bool alone =
            on_chains[static_cast<size_t>(piece)] == 1 && !on_longer[static_cast<size_t>(piece)];
        if (!run.empty() && (!alone || !runs_on(run.back(), piece))) {
          if (run.size() > 1) {
            runs.push_back(std::move(run));
          }
          run.clear();
        }
        if (alone) {
          run.push_back(piece);
        }
      }
      if (run.size() > 1) {
        runs.push_back(std::move(run));
      }
    }
    return runs;
  }

  /// Moves every connecting road of junction `from` into junction `into`.
  void merge_junctions(int into, int from) {
    auto& source = plan_.junctions[static_cast<size_t>(from)].roads;
    for (const int road : source) {
      plan_.roads[static_cast<size_t>(road)].junction = into;
      plan_.junctions[static_cast<size_t>(into)].roads.push_back(road);
    }
    source.clear();
  }

  /// Cuts `plan` across its lanes at arc length `u` of the leftmost lane; returns the head
  /// (`head`) or tail piece and keeps the rest in `plan`. The cut gets fresh topology keys.
  RoadPlan cut(RoadPlan& plan, double u, bool head) {
    const Polyline first(plan.lanes[0].points);
    const Vec2 c = xy(first.at(u));
    const Vec2 d = first.direction(u);
    RoadPlan piece;
    for (PlanLane& lane : plan.lanes) {
      const Polyline line(lane.points);
      // Where the cut line (normal through c) crosses this lane: its nearest crossing.
      const double cut_u = crossing_u(line, c, d, std::clamp(u, 0.0, line.length()));
      auto [front, back] = split_lane(lane, cut_u, plan_.node_keys++);
      if (head) {
        piece.lanes.push_back(std::move(front));
        lane = std::move(back);
      } else {
        piece.lanes.push_back(std::move(back));
        lane = std::move(front);
      }
    }
    return piece;
  }

  const Network& network_;
  bool several_incoming_;  // a connecting road may take lanes from several incoming roads
  Diagnostics& diagnostics_;
  NetworkPlan plan_;
};

}  // namespace

LaneIndex::LaneIndex(const NetworkPlan& plan)
    : starting(static_cast<size_t>(plan.node_keys)), ending(static_cast<size_t>(plan.node_keys)) {
  for (size_t r = 0; r < plan.roads.size(); ++r) {
    if (plan.roads[r].removed) {
      continue;
    }
    for (size_t k = 0; k < plan.roads[r].lanes.size(); ++k) {
      const PlanLane& lane = plan.roads[r].lanes[k];
      starting[static_cast<size_t>(lane.start_node)].push_back(
          {static_cast<int>(r), static_cast<int>(k)});
      ending[static_cast<size_t>(lane.end_node)].push_back(
          {static_cast<int>(r), static_cast<int>(k)});
    }
  }
}

NetworkPlan plan_network(const Network& network, const LateralStructure& lateral,
                         bool several_incoming, Diagnostics& diagnostics) {
  return Planner(network, several_incoming, diagnostics).run(lateral);
}

}  // namespace corsa::ngii::detail
