// Shortest lane route (Dijkstra). States are (lane node, travel direction) entered at the lane's
// entry end; the start point adds a few "start states" (its lane and the lanes reachable from it
// by lane changes in the same section) that begin part-way along. Lane changes keep the
// fraction of the section travelled and cost RouteOptions::lane_change_cost; driving costs the
// lane centre length travelled.

#include "corsa/xodr/route.h"

#include <algorithm>
#include <limits>
#include <queue>

namespace corsa::xodr {
namespace {

constexpr uint32_t kNone = UINT32_MAX;
constexpr double kInfinity = std::numeric_limits<double>::infinity();

struct State {
  LaneNode node = kNoLane;
  bool forward = true;
  double enter_fraction = 0.0;  ///< fraction of the lane (in travel direction) where it begins
  double cost = kInfinity;
  uint32_t parent = kNone;   ///< state we came from
  bool lane_change = false;  ///< reached from `parent` by a lane change
};

class Router {
 public:
  Router(const Map& map, const RouteOptions& options)
      : map_(map), graph_(map.lane_graph()), options_(options) {}

  std::optional<Route> run(const LanePoint& from, const LanePoint& to);

 private:
  bool allowed(LaneNode node, bool forward) const {
    const auto& info = graph_.info(node);
    if (!is_drivable(info.type)) {
      return false;
    }
    return options_.against_traffic || info.direction == TravelDirection::kBoth ||
           (info.direction == TravelDirection::kForward) == forward;
  }
  /// Fraction of the lane travelled (in direction) at road s.
  double fraction(LaneNode node, bool forward, double s) const {
    const auto& info = graph_.info(node);
    const double span = info.s_end - info.s_start;
    if (span <= 0.0) {
      return 0.0;
    }
    const double f = std::clamp((s - info.s_start) / span, 0.0, 1.0);
    return forward ? f : 1.0 - f;
  }
  double road_s(LaneNode node, bool forward, double f) const {
    const auto& info = graph_.info(node);
    return forward ? info.s_start + f * (info.s_end - info.s_start)
                   : info.s_end - f * (info.s_end - info.s_start);
  }
  uint32_t state_of(LaneNode node, bool forward) const { return 2 * node + (forward ? 0 : 1); }
  void relax(uint32_t index, double cost, uint32_t parent, bool lane_change) {
    State& state = states_[index];
    if (cost < state.cost) {
      state.cost = cost;
      state.parent = parent;
      state.lane_change = lane_change;
      queue_.emplace(cost, index);
    }
  }
  /// From a state at fraction f with cost c: the target (if ahead), the exit, lane changes.
  void expand(uint32_t index, double f);
  Route reconstruct(uint32_t last, double target_fraction) const;

  const Map& map_;
  const LaneGraph& graph_;
  RouteOptions options_;
  std::vector<State> states_;
  std::vector<uint32_t> partway_;  ///< per entry state: its part-way twin near the start
  std::priority_queue<std::pair<double, uint32_t>, std::vector<std::pair<double, uint32_t>>,
                      std::greater<>>
      queue_;
  LaneNode target_ = kNoLane;
  double target_s_ = 0.0;
  double best_ = kInfinity;
  uint32_t best_state_ = kNone;
};

void Router::expand(uint32_t index, double f) {
  const State state = states_[index];
  const double length =
      graph_.info(state.node).length *
      (options_.lane_cost_scale.empty() ? 1.0 : options_.lane_cost_scale[state.node]);
  if (state.node == target_) {
    const double ft = fraction(state.node, state.forward, target_s_);
    if (ft >= f && state.cost + (ft - f) * length < best_) {
      best_ = state.cost + (ft - f) * length;
      best_state_ = index;
    }
  }
  // Lane changes at this point, into neighbours driven the same way.
  if (options_.allow_lane_changes) {
    for (const LaneNode side : {graph_.left(state.node), graph_.right(state.node)}) {
      if (side != kNoLane && allowed(side, state.forward)) {
        uint32_t next = state_of(side, state.forward);
        if (f > 0.0) {
          // Part-way along (only around the start point): one extra state per lane and
          // direction keeps that fraction.
          if (partway_[next] == kNone) {
            partway_[next] = static_cast<uint32_t>(states_.size());
            states_.push_back(State{side, state.forward, f, kInfinity, kNone, false});
          }
          next = partway_[next];
        }
        relax(next, state.cost + options_.lane_change_cost, index, true);
      }
    }
  }
  // Drive to the exit end and on into every lane joined there.
  const double exit_cost = state.cost + (1.0 - f) * length;
  for (const LaneEnd& end : graph_.ends(state.node, !state.forward)) {
    if (allowed(end.node, end.at_start)) {
      const double entry =
          options_.lane_entry_cost.empty() ? 0.0 : options_.lane_entry_cost[end.node];
      relax(state_of(end.node, end.at_start), exit_cost + entry, index, false);
    }
  }
}

std::optional<Route> Router::run(const LanePoint& from, const LanePoint& to) {
  if (from.road >= map_.road_count() || to.road >= map_.road_count()) {
    return std::nullopt;
  }
  const auto start = graph_.find(
      LaneRef{from.road, static_cast<uint32_t>(map_.section_index(from.road, from.s)), from.lane});
  const auto target = graph_.find(
      LaneRef{to.road, static_cast<uint32_t>(map_.section_index(to.road, to.s)), to.lane});
  if (!start || !target) {
    return std::nullopt;
  }
  target_ = *target;
  target_s_ = to.s;
  states_.assign(2 * graph_.size(), State{});
  for (LaneNode node = 0; node < graph_.size(); ++node) {
    states_[2 * node] = State{node, true, 0.0, kInfinity, kNone, false};
    states_[2 * node + 1] = State{node, false, 0.0, kInfinity, kNone, false};
  }
  // Start states, appended after the entry states so that they keep their own fraction.
  partway_.assign(states_.size(), kNone);
  for (const bool forward : {true, false}) {
    if (allowed(*start, forward)) {
      partway_[state_of(*start, forward)] = static_cast<uint32_t>(states_.size());
      states_.push_back(
          State{*start, forward, fraction(*start, forward, from.s), 0.0, kNone, false});
      queue_.emplace(0.0, static_cast<uint32_t>(states_.size() - 1));
    }
  }
  while (!queue_.empty()) {
    const auto [cost, index] = queue_.top();
    queue_.pop();
    if (cost > states_[index].cost || cost >= best_) {
      if (cost >= best_) {
        break;
      }
      continue;
    }
    expand(index, states_[index].enter_fraction);
  }
  if (best_state_ == kNone) {
    return std::nullopt;
  }
  return reconstruct(best_state_, fraction(target_, states_[best_state_].forward, target_s_));
}

Route Router::reconstruct(uint32_t last, double target_fraction) const {
  std::vector<uint32_t> chain;
  for (uint32_t index = last; index != kNone; index = states_[index].parent) {
    chain.push_back(index);
  }
  std::reverse(chain.begin(), chain.end());
  Route route;
  for (size_t i = 0; i < chain.size(); ++i) {
    const State& state = states_[chain[i]];
    // A state is left where the next one begins: at a lane change, at the same fraction; when
    // driving on, at the exit end; the last one at the target.
    double leave = target_fraction;
    if (i + 1 < chain.size()) {
      const State& next = states_[chain[i + 1]];
      leave = next.lane_change ? next.enter_fraction : 1.0;
    }
    RouteStep step;
    step.lane = graph_.info(state.node).lane;
    step.s_from = road_s(state.node, state.forward, state.enter_fraction);
    step.s_to = road_s(state.node, state.forward, leave);
    step.lane_change = state.lane_change;
    route.length += (leave - state.enter_fraction) * graph_.info(state.node).length;
    route.lane_changes += state.lane_change ? 1 : 0;
    route.steps.push_back(step);
  }
  return route;
}

}  // namespace

std::optional<Route> find_route(const Map& map, const LanePoint& from, const LanePoint& to,
                                const RouteOptions& options) {
  Router router(map, options);
  return router.run(from, to);
}

}  // namespace corsa::xodr
