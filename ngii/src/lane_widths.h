#pragma once

// Lane widths measured before any road is fitted, per plan lane as a function of arc length
// along its centre polyline. Sources, in order: the B2 marks bounding the lane (a mark's
// R_linkID / L_linkID names the lane it bounds; the width is the distance from the left mark to
// the right one across the lane centre, or twice the distance to the one mark where the lane has
// a mark on one side only, except on junction paths), the spacing to the lane's L/R neighbour
// links, the widths where the lanes before and after it end and begin (a junction path takes its
// approach and exit lanes' widths), and only when none exists a fallback width, counted.

#include <functional>
#include <optional>
#include <vector>

#include "corsa/ngii/curve_fit.h"
#include "network.h"
#include "network_plan.h"

namespace corsa::ngii::detail {

/// Width (m) along one plan lane: samples (u = arc length along PlanLane::points, width).
class WidthProfile {
 public:
  WidthProfile() = default;
  explicit WidthProfile(std::vector<ProfileSample> samples) : samples_(std::move(samples)) {}
  bool empty() const { return samples_.empty(); }
  /// Interpolated width at u (clamped to the first / last sample).
  double at(double u) const;
  double front() const { return samples_.front().v; }
  double back() const { return samples_.back().v; }
  /// u of the first and last sample: the width is measured between them, held flat beyond.
  double first_u() const { return samples_.front().s; }
  double last_u() const { return samples_.back().s; }

 private:
  std::vector<ProfileSample> samples_;
};

enum class WidthSource : uint8_t { kMarks, kNeighbours, kTopology, kFallback };

struct PlanWidths {
  std::vector<std::vector<WidthProfile>> lanes;  ///< [plan road][lane]
  std::vector<std::vector<WidthSource>> sources;
  size_t counts[4] = {0, 0, 0, 0};  ///< plan lanes per WidthSource
};

/// An ordinary lane's end as built: its width (m) along the road's end cross-section and the
/// road's heading (rad) there.
struct JoinedLaneEnd {
  double width = 0.0;
  double heading = 0.0;
};
/// The built end (`at_end`) or start of lane `ref.lane` of ordinary plan road `ref.road`;
/// nothing when that road was not built.
using JoinedLaneEndOf =
    std::function<std::optional<JoinedLaneEnd>(const LaneIndex::Ref& ref, bool at_end)>;

/// Junction paths take the widths of the ordinary lanes they leave and enter at their ends
/// (easing back to their own over a few metres, or up to where the marks first give their
/// own), so that a path narrower or wider than the approach lane leaves no sliver of unpaved
/// ground beside the joint and no step in the edge. The ordinary lanes' widths are those of
/// the built roads (`joined`): the lane borders of a road (border_solver.h) are not its lanes'
/// measured widths. Called once the ordinary roads are built, before the paths.
void match_path_ends(const NetworkPlan& plan, const LaneIndex& index, const JoinedLaneEndOf& joined,
                     std::vector<std::vector<WidthProfile>>& widths);

/// Widths of every lane of every (not removed) plan road.
PlanWidths measure_widths(const NetworkPlan& plan, const Network& network, double fallback);

}  // namespace corsa::ngii::detail
