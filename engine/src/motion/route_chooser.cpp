#include "motion/route_chooser.h"

#include <algorithm>

namespace corsa::engine::detail {

size_t RouteChooser::choose(const xodr::Map& map, const LaneFollow& lane,
                            std::span<const xodr::LaneEnd> candidates) const {
  const xodr::LaneGraph& graph = map.lane_graph();
  // Score 2: the very lane of a route step, entered the way the step drives it; 1: a lane of a
  // road the route uses, same direction; 0: off the route.
  std::vector<int> scores(candidates.size(), 0);
  int best = 0;
  for (size_t i = 0; i < candidates.size(); ++i) {
    const xodr::LaneRef& ref = graph.info(candidates[i].node).lane;
    const int dir = candidates[i].at_start ? 1 : -1;
    for (const xodr::RouteStep& step : plan_.steps) {
      const int step_dir = step.s_to >= step.s_from ? 1 : -1;
      if (step.lane.road != ref.road || step_dir != dir) {
        continue;
      }
      const int score = step.lane.section == ref.section && step.lane.lane == ref.lane ? 2 : 1;
      scores[i] = std::max(scores[i], score);
    }
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

}  // namespace corsa::engine::detail
