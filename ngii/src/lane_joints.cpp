#include "lane_joints.h"

#include <algorithm>
#include <cmath>

#include "corsa/xodr/geometry.h"
#include "polyline.h"
#include "reference_line.h"

namespace corsa::ngii::detail {
namespace {

constexpr double kMinJointWidth = 0.5;  // m: narrower lanes start or end beside a neighbour
constexpr double kMaxJointTurn = 20.0 * M_PI / 180.0;  // rad between the two roads' headings
// m: farthest a border moves (a lane at the tip of a painted island, 9 m wide, continuing into
// a 3 m lane is ground between two roads, not a lane's width)
constexpr double kMaxBorderMove = 0.75;
// m: a pair whose borders all move less is left alone (no gap of the 0.1 m that counts opens
// there, and every move takes the lane's width off what its marks say)
constexpr double kMinUsefulMove = 0.08;
constexpr double kMaxAlong = 0.5;  // m between the two lane ends along the road
// m between the two lanes' centres across the road: lanes further apart are not one lane
// continuing (a corner, a lane shifting sideways at the joint), and meeting edge to edge would
// move their centres off their links' ends.
constexpr double kMaxCentreOffset = 0.1;
// m: farthest a lane's centre may move at its end so that its borders cover the joined lane (a
// lane widening on one side only): the lane centres follow their links within 2-3 cm (p95),
// and a centre moved further takes its link's end vertex off it.
constexpr double kMaxCentreMove = 0.03;

/// One end of a built road: its reference point and heading there, and its border points.
struct JointEnd {
  Vec2 point;
  double heading = 0.0;
  std::vector<Vec2> borders;
};

JointEnd joint_end_of(const xodr::Road& road, bool at_end) {
  const xodr::Geometry& g = at_end ? road.plan_view.back() : road.plan_view.front();
  const xodr::RefPoint p = xodr::evaluate_geometry(g, at_end ? g.length : 0.0);
  return JointEnd{Vec2{p.x, p.y}, p.hdg, built_border_points(road, at_end)};
}

/// The targets collected for one road end: per border, the sum of the points asked for and
/// how many asked.
struct BorderVotes {
  std::vector<Vec2> sum;
  std::vector<int> count;
  void add(size_t border, Vec2 p, size_t borders) {
    if (sum.empty()) {
      sum.assign(borders, Vec2{0.0, 0.0});
      count.assign(borders, 0);
    }
    sum[border] = sum[border] + p;
    ++count[border];
  }
};

/// Whether lane k of borders `t` (left to right, + left) is the outermost lane of at least
/// kMinJointWidth on its left (`left`) or right side.
bool outermost_at_joint(const std::vector<double>& t, size_t k, bool left) {
  if (left) {
    for (size_t m = 0; m < k; ++m) {
      if (t[m] - t[m + 1] >= kMinJointWidth) {
        return false;
      }
    }
    return true;
  }
  for (size_t m = k + 1; m + 1 < t.size(); ++m) {
    if (t[m] - t[m + 1] >= kMinJointWidth) {
      return false;
    }
  }
  return true;
}

/// How two outer borders of a joined pair meet: the inner one moves onto the outer one (the
/// narrower lane widens to the wider one's edge), both meet halfway, or the outer one moves onto
/// the inner one (the wider lane narrows to the narrower one's edge: where the narrower lane's
/// other border is between two lanes of its road, so that it cannot widen without moving its
/// centre, the wider lane takes both its borders and keeps its own centre).
enum class JointMeeting { kOntoOuter, kHalfway, kOntoInner };

/// Where a border of lane A (`a`, t along A's end normal, + left) is to lie at the joint with
/// the lane it joins, whose border on the same side (`left`) is `b`. Inner borders (between two
/// lanes of a road) stay: the neighbouring lane covers the ground beyond them. An outer border
/// moves onto an inner one (the lanes then share both borders there, and their centres meet),
/// and of two outer borders the inner one moves onto the outer one, or with `halfway` both
/// meet halfway. Nothing where A's border stays.
std::optional<double> meeting_border(double a, bool a_outer, double b, bool b_outer, bool left,
                                     JointMeeting meeting) {
  if (!a_outer) {
    return std::nullopt;
  }
  if (!b_outer) {
    return b;
  }
  if (meeting == JointMeeting::kHalfway) {
    return 0.5 * (a + b);
  }
  const bool inside = left ? a < b : a > b;
  const bool moves = meeting == JointMeeting::kOntoOuter ? inside : !inside;
  return moves ? std::optional<double>(b) : std::nullopt;
}

/// Where the borders of lane i of road A (borders `ta`) and lane j of road B (`tb`, both in
/// t along A's end normal) are to lie at their joint: per lane, [0] its right border, [1] its
/// left one (nothing: it stays).
struct PairBorders {
  std::optional<double> a[2];
  std::optional<double> b[2];
};

/// The borders of a joined pair of lanes on both sides (meeting_border); of two outer borders
/// halfway between them where a lane's centre would move more than kMaxCentreMove (the lanes
/// differing in width on one side only). Nothing where a centre still moves more, where the two
/// centres would end up further apart than they were (and than kMaxCentreOffset: two inner
/// borders that differ keep the lanes' widths apart), where a border would move more than
/// kMaxBorderMove or where none moves as much as kMinUsefulMove.
std::optional<PairBorders> pair_borders(const std::vector<double>& ta, size_t i,
                                        const std::vector<double>& tb, size_t j) {
  const auto centre_move = [](const std::optional<double>* to, double left, double right) {
    return 0.5 * (to[1].value_or(left) - left + to[0].value_or(right) - right);
  };
  for (const JointMeeting meeting :
       {JointMeeting::kOntoOuter, JointMeeting::kHalfway, JointMeeting::kOntoInner}) {
    PairBorders to;
    for (const bool left : {true, false}) {
      const size_t ka = left ? i : i + 1;
      const size_t kb = left ? j : j + 1;
      const bool outer_a = outermost_at_joint(ta, i, left);
      const bool outer_b = outermost_at_joint(tb, j, left);
      to.a[left] = meeting_border(ta[ka], outer_a, tb[kb], outer_b, left, meeting);
      to.b[left] = meeting_border(tb[kb], outer_b, ta[ka], outer_a, left, meeting);
    }
    const double move_a = centre_move(to.a, ta[i], ta[i + 1]);
    const double move_b = centre_move(to.b, tb[j], tb[j + 1]);
    const double apart = 0.5 * (ta[i] + ta[i + 1] - tb[j] - tb[j + 1]);
    if (std::abs(move_a) > kMaxCentreMove || std::abs(move_b) > kMaxCentreMove ||
        std::abs(apart + move_a - move_b) > std::max(std::abs(apart), kMaxCentreOffset)) {
      continue;
    }
    double largest = 0.0;
    for (const bool left : {true, false}) {
      largest = std::max(
          largest, std::abs(to.a[left].value_or(ta[left ? i : i + 1]) - ta[left ? i : i + 1]));
      largest = std::max(
          largest, std::abs(to.b[left].value_or(tb[left ? j : j + 1]) - tb[left ? j : j + 1]));
    }
    if (largest > kMaxBorderMove || largest < kMinUsefulMove) {
      return std::nullopt;
    }
    return to;
  }
  return std::nullopt;
}

/// The averaged votes as EndBorders points; borders of a lane under kMinJointWidth wide move
/// with its neighbour that moves (`own`: the road's own border points there).
std::vector<std::optional<Vec2>> settled_border_points(const BorderVotes& votes,
                                                       const std::vector<Vec2>& own) {
  std::vector<std::optional<Vec2>> out(own.size());
  if (votes.sum.empty()) {
    return {};
  }
  for (size_t b = 0; b < own.size(); ++b) {
    if (votes.count[b] > 0) {
      out[b] = votes.sum[b] * (1.0 / votes.count[b]);
    }
  }
  for (bool changed = true; changed;) {
    changed = false;
    for (size_t b = 0; b + 1 < own.size(); ++b) {
      if (norm(own[b] - own[b + 1]) >= kMinJointWidth ||
          out[b].has_value() == out[b + 1].has_value()) {
        continue;
      }
      const size_t from = out[b] ? b : b + 1;
      const size_t to = out[b] ? b + 1 : b;
      out[to] = own[to] + (*out[from] - own[from]);
      changed = true;
    }
  }
  return out;
}

/// Two roads whose lanes continue one to one, every lane of one into the lane of the other in
/// the same place (a road cut in two, a joint where only the widths change): where their
/// centres are within kMaxCentreMove of each other but the borders between their lanes differ
/// (each pair alone would move a neighbour's centre), the road whose lanes span less across
/// takes all the other's borders, so that its lanes widen to the other's edges and the two
/// cross-sections meet everywhere. `ea` is road `a`'s end, `ta` its borders along its end
/// normal; votes go to `a_votes` or to road b's start in `start_votes`. False where the roads
/// do not qualify (the lane pairs are then met one by one).
template <typename EndOf>
bool meet_whole_sections(const NetworkPlan& plan, const LaneIndex& index, size_t a,
                         const JointEnd& ea, const std::vector<double>& ta, const EndOf& end_of,
                         BorderVotes& a_votes, std::vector<BorderVotes>& start_votes) {
  const RoadPlan& from = plan.roads[a];
  int b = -1;
  for (size_t i = 0; i < from.lanes.size(); ++i) {
    const auto& refs = index.starting[static_cast<size_t>(from.lanes[i].end_node)];
    if (refs.size() != 1 || refs[0].lane != static_cast<int>(i) || (i > 0 && refs[0].road != b)) {
      return false;
    }
    b = refs[0].road;
  }
  if (b < 0 || static_cast<size_t>(b) == a ||
      plan.roads[static_cast<size_t>(b)].lanes.size() != from.lanes.size()) {
    return false;
  }
  const JointEnd* eb = end_of(static_cast<size_t>(b), false);
  if (eb == nullptr || std::abs(angle_diff(eb->heading, ea.heading)) > kMaxJointTurn) {
    return false;
  }
  const Vec2 normal{-std::sin(ea.heading), std::cos(ea.heading)};
  const Vec2 tangent{std::cos(ea.heading), std::sin(ea.heading)};
  std::vector<double> tb;
  for (const Vec2& p : eb->borders) {
    tb.push_back(dot(p - ea.point, normal));
  }
  double largest = 0.0;
  for (size_t i = 0; i + 1 < ta.size(); ++i) {
    const Vec2 mid_a = 0.5 * (ea.borders[i] + ea.borders[i + 1]);
    const Vec2 mid_b = 0.5 * (eb->borders[i] + eb->borders[i + 1]);
    if (ta[i] - ta[i + 1] < kMinJointWidth || tb[i] - tb[i + 1] < kMinJointWidth ||
        std::abs(dot(mid_b - mid_a, normal)) > kMaxCentreMove ||
        std::abs(dot(mid_b - mid_a, tangent)) > kMaxAlong) {
      return false;
    }
  }
  for (size_t k = 0; k < ta.size(); ++k) {
    largest = std::max(largest, std::abs(ta[k] - tb[k]));
  }
  if (largest > kMaxBorderMove || largest < kMinUsefulMove) {
    return false;
  }
  const bool a_moves = ta.front() - ta.back() < tb.front() - tb.back();
  for (size_t k = 0; k < ta.size(); ++k) {
    if (a_moves) {
      a_votes.add(k, ea.point + normal * tb[k], ta.size());
    } else {
      start_votes[static_cast<size_t>(b)].add(k, ea.point + normal * ta[k], ta.size());
    }
  }
  return true;
}

}  // namespace

std::vector<Vec2> built_border_points(const xodr::Road& road, bool at_end) {
  std::vector<Vec2> out;
  if (road.plan_view.empty() || road.lane_sections.empty()) {
    return out;
  }
  const xodr::Geometry& g = at_end ? road.plan_view.back() : road.plan_view.front();
  const xodr::RefPoint p = xodr::evaluate_geometry(g, at_end ? g.length : 0.0);
  const double s = at_end ? road.length : 0.0;
  const xodr::LaneSection& section =
      at_end ? road.lane_sections.back() : road.lane_sections.front();
  // Widths are along the tilted surface (OpenDRIVE 1.8 §8.4.2): horizontal = t cos(roll).
  const double cos_roll = std::cos(piecewise_value(road.superelevation, s));
  const Vec2 origin{p.x, p.y};
  const Vec2 normal{-std::sin(p.hdg), std::cos(p.hdg)};
  double t = piecewise_value(road.lane_offsets, s);
  out.push_back(origin + normal * (t * cos_roll));
  for (const xodr::Lane& lane : section.lanes) {
    if (lane.id < 0) {
      t -= piecewise_value(lane.widths, s - section.s);
      out.push_back(origin + normal * (t * cos_roll));
    }
  }
  return out;
}

std::vector<EndBorders> joint_borders(const NetworkPlan& plan, const LaneIndex& index,
                                      const BuiltOrdinaryRoad& built) {
  const size_t roads = plan.roads.size();
  std::vector<BorderVotes> start_votes(roads), end_votes(roads);
  std::vector<std::optional<JointEnd>> starts(roads), ends(roads);
  const auto end_of = [&](size_t r, bool at_end) -> const JointEnd* {
    std::optional<JointEnd>& slot = at_end ? ends[r] : starts[r];
    if (!slot) {
      const xodr::Road* road = built(r);
      if (road == nullptr || road->plan_view.empty() || road->lane_sections.empty()) {
        return nullptr;
      }
      slot = joint_end_of(*road, at_end);
    }
    return slot->borders.size() == plan.roads[r].lanes.size() + 1 ? &*slot : nullptr;
  };
  for (size_t a = 0; a < roads; ++a) {
    const RoadPlan& from = plan.roads[a];
    if (from.removed || end_of(a, true) == nullptr) {
      continue;
    }
    const JointEnd& ea = *end_of(a, true);
    const Vec2 normal{-std::sin(ea.heading), std::cos(ea.heading)};
    const Vec2 tangent{std::cos(ea.heading), std::sin(ea.heading)};
    std::vector<double> ta;
    for (const Vec2& p : ea.borders) {
      ta.push_back(dot(p - ea.point, normal));
    }
    if (meet_whole_sections(plan, index, a, ea, ta, end_of, end_votes[a], start_votes)) {
      continue;
    }
    for (size_t i = 0; i < from.lanes.size(); ++i) {
      for (const LaneIndex::Ref& ref :
           index.starting[static_cast<size_t>(from.lanes[i].end_node)]) {
        const size_t b = static_cast<size_t>(ref.road);
        const size_t j = static_cast<size_t>(ref.lane);
        const JointEnd* eb = end_of(b, false);
        if (eb == nullptr || std::abs(angle_diff(eb->heading, ea.heading)) > kMaxJointTurn) {
          continue;
        }
        std::vector<double> tb;
        for (const Vec2& p : eb->borders) {
          tb.push_back(dot(p - ea.point, normal));
        }
        const double wa = ta[i] - ta[i + 1];
        const double wb = tb[j] - tb[j + 1];
        const Vec2 mid_a = 0.5 * (ea.borders[i] + ea.borders[i + 1]);
        const Vec2 mid_b = 0.5 * (eb->borders[j] + eb->borders[j + 1]);
        if (wa < kMinJointWidth || wb < kMinJointWidth ||
            std::abs(dot(mid_b - mid_a, normal)) > kMaxCentreOffset ||
            std::abs(dot(mid_b - mid_a, tangent)) > kMaxAlong) {
          continue;
        }
        const std::optional<PairBorders> to = pair_borders(ta, i, tb, j);
        if (!to) {
          continue;
        }
        const std::optional<double>* to_a = to->a;
        const std::optional<double>* to_b = to->b;
        for (const bool left : {true, false}) {
          if (to_a[left]) {
            end_votes[a].add(left ? i : i + 1, ea.point + normal * *to_a[left], ea.borders.size());
          }
          if (to_b[left]) {
            start_votes[b].add(left ? j : j + 1, ea.point + normal * *to_b[left],
                               eb->borders.size());
          }
        }
      }
    }
  }
  std::vector<EndBorders> out(roads);
  for (size_t r = 0; r < roads; ++r) {
    if (!start_votes[r].sum.empty()) {
      out[r].start = settled_border_points(start_votes[r], end_of(r, false)->borders);
    }
    if (!end_votes[r].sum.empty()) {
      out[r].end = settled_border_points(end_votes[r], end_of(r, true)->borders);
    }
  }
  return out;
}

}  // namespace corsa::ngii::detail
