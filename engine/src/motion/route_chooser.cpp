#include "motion/route_chooser.h"

#include <algorithm>

namespace corsa::engine::detail {

namespace {

int step_direction(const xodr::RouteStep& step) { return step.s_to >= step.s_from ? 1 : -1; }

// 2: the very lane of a route step, entered the way the step drives it; 1: a lane of a road the
// route uses, same direction; 0: off the route.
int route_score(const RoutePlan& plan, const xodr::LaneGraph& graph, const xodr::LaneEnd& end) {
  const xodr::LaneRef& ref = graph.info(end.node).lane;
  const int dir = end.at_start ? 1 : -1;
  int score = 0;
  for (const xodr::RouteStep& step : plan.steps) {
    if (step.lane.road != ref.road || step_direction(step) != dir) {
      continue;
    }
    score = std::max(score, step.lane.section == ref.section && step.lane.lane == ref.lane ? 2 : 1);
  }
  return score;
}

}  // namespace

size_t RouteChooser::choose(const xodr::Map& map, const LaneFollow& lane,
                            std::span<const xodr::LaneEnd> candidates) const {
  const xodr::LaneGraph& graph = map.lane_graph();
  std::vector<int> scores(candidates.size(), 0);
  int best = 0;
  for (size_t i = 0; i < candidates.size(); ++i) {
    scores[i] = route_score(plan_, graph, candidates[i]);
    best = std::max(best, scores[i]);
  }
  std::vector<xodr::LaneEnd> tied;
  std::vector<size_t> index;
  for (size_t i = 0; i < candidates.size(); ++i) {
    if (scores[i] == best) {
      tied.push_back(candidates[i]);
      index.push_back(i);
    }
  }
  return index[choose_straightest(map, lane, tied)];
}

std::optional<LaneRedirect> RouteChooser::redirect(
    const xodr::Map& map, const LaneFollow& lane, std::span<const xodr::LaneEnd> candidates) const {
  const xodr::LaneGraph& graph = map.lane_graph();
  if (std::any_of(candidates.begin(), candidates.end(),
                  [&](const xodr::LaneEnd& end) { return route_score(plan_, graph, end) > 0; })) {
    return std::nullopt;
  }
  const auto& steps = plan_.steps;
  for (size_t k = 0; k + 1 < steps.size(); ++k) {
    const xodr::RouteStep& here = steps[k];
    const xodr::RouteStep& next = steps[k + 1];
    if (here.lane.road != lane.road || here.lane.section != lane.section ||
        here.lane.lane == lane.lane || step_direction(here) != lane.dir ||
        (next.lane.road == here.lane.road && next.lane.section == here.lane.section)) {
      continue;
    }
    const auto via = graph.find(here.lane);
    if (!via) {
      continue;
    }
    for (const xodr::LaneEnd& end : graph.ends(*via, lane.dir < 0)) {
      if (graph.info(end.node).lane == next.lane &&
          (end.at_start ? 1 : -1) == step_direction(next)) {
        return LaneRedirect{end, here.lane.lane};
      }
    }
  }
  return std::nullopt;
}

}  // namespace corsa::engine::detail
