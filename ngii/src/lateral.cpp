#include "lateral.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "corsa/core/strings.h"
#include "lane_numbers.h"
#include "polyline.h"

namespace corsa::ngii::detail {

Side side_of(const Polyline& a, const Polyline& b) {
  Side side;
  side.lat_min = std::numeric_limits<double>::infinity();
  side.lat_max = -side.lat_min;
  constexpr int kSamples = 9;
  int beside = 0;
  int opposite = 0;
  for (int k = 0; k < kSamples; ++k) {
    const double u = b.length() * k / (kSamples - 1);
    const Point3 q = b.at(u);
    const Projection p = a.project(xy(q));
    side.lat_min = std::min(side.lat_min, p.lateral);
    side.lat_max = std::max(side.lat_max, p.lateral);
    if (k == 0) {
      side.lat_start = p.lateral;
      side.stagger_start = p.u + p.along;
    }
    if (k == kSamples / 2) {
      side.lat_mid = p.lateral;
    }
    if (k == kSamples - 1) {
      side.lat_end = p.lateral;
      side.stagger_end = a.length() - p.u - p.along;
    }
    if (p.along == 0.0) {
      ++beside;
      side.lat_mean += std::abs(p.lateral);
      opposite += dot(a.direction(p.u), b.direction(u)) < -0.5;
    }
  }
  side.overlap = beside > 0;
  // Diverging paths (a turn leaving beside a straight path) are still the same direction.
  side.same_direction = 2 * opposite <= beside;
  side.lat_mean = beside > 0 ? side.lat_mean / beside : std::numeric_limits<double>::infinity();
  return side;
}

namespace {

/// Why `right` cannot be the right neighbour of `left`, or empty when it can. Sides are seen
/// from `left`; a right neighbour has negative lateral offsets.
std::string why_not_neighbours(const Network& net, int left, int right) {
  const LinkState& a = net.links[static_cast<size_t>(left)];
  const LinkState& b = net.links[static_cast<size_t>(right)];
  if (b.removed) {
    return "points to a zero-length link that was removed";
  }
  if (a.to == b.from || b.to == a.from) {
    return "points to a link that continues it (a successor or predecessor), not a neighbour";
  }
  const Side side = side_of(Polyline(a.points), Polyline(b.points));
  if (!side.overlap) {
    return "points to a link that does not run beside it";
  }
  if (!side.same_direction) {
    return "points to a link running the other way";
  }
  if (side.lat_max > 0.5 || side.lat_min > -1.0) {
    return "points to a link on the wrong side";
  }
  if (side.lat_min < -12.0 && side.lat_max < -12.0) {
    return "points to a link " + format_fixed(-side.lat_max, 1) + " m away";
  }
  return {};
}

/// Lower is a better left/right pair (mean lateral gap off a lane width, plus stagger).
double pair_score(const Network& net, int left, int right) {
  const Side side = side_of(Polyline(net.links[static_cast<size_t>(left)].points),
                            Polyline(net.links[static_cast<size_t>(right)].points));
  return std::abs(side.lat_mean - 3.4) +
         0.1 * (std::abs(side.stagger_start) + std::abs(side.stagger_end));
}

const char* field_name(bool right) { return right ? "R_LinkID" : "L_LinkID"; }

class NeighbourRepair {
 public:
  NeighbourRepair(Network& net, CorrectionLog& log) : net_(net), log_(log) {}

  void drop_invalid() {
    for (int i = 0; i < static_cast<int>(net_.size()); ++i) {
      for (const bool right : {false, true}) {
        const int other = pointer(i, right);
        if (other < 0) {
          continue;
        }
        const std::string reason =
            right ? why_not_neighbours(net_, i, other) : why_not_neighbours(net_, other, i);
        if (!reason.empty()) {
          set(i, right, -1, reason);
        }
      }
    }
  }

  void make_reciprocal() {
    for (int i = 0; i < static_cast<int>(net_.size()); ++i) {
      for (const bool right : {true, false}) {
        const int b = pointer(i, right);
        if (b < 0) {
          continue;
        }
        const int back = pointer(b, !right);
        if (back == i) {
          continue;
        }
        const std::string me = net_.source(i).id;
        if (back < 0) {
          set(b, !right, i, "the neighbour " + me + " points here (" + field_name(right) + ")");
          continue;
        }
        // Two links claim the same side of b: keep the better pair, drop the other pointer.
        const double mine = right ? pair_score(net_, i, b) : pair_score(net_, b, i);
        const double theirs = right ? pair_score(net_, back, b) : pair_score(net_, b, back);
        const std::string other = net_.source(back).id;
        if (mine < theirs) {
          if (pointer(back, right) == b) {
            set(back, right, -1,
                "not reciprocated: " + net_.source(b).id + " lies closer beside " + me);
          }
          set(b, !right, i, "non-reciprocal L/R: " + me + " lies closer than " + other);
        } else {
          set(i, right, -1,
              "non-reciprocal L/R: " + net_.source(b).id + " has " + other + " on that side");
        }
      }
    }
  }

  /// Ordinary links with no neighbour on a side, paired with a parallel same-direction link
  /// 2.3-6 m away whose ends line up, when each is the other's only such candidate.
  void infer_missing() {
    const int n = static_cast<int>(net_.size());
    std::vector<Box> boxes(static_cast<size_t>(n));
    for (int i = 0; i < n; ++i) {
      boxes[static_cast<size_t>(i)] = box_of(net_.links[static_cast<size_t>(i)].points);
    }
    std::vector<int> best_right(static_cast<size_t>(n), -1);
    std::vector<int> right_count(static_cast<size_t>(n), 0);
    std::vector<int> left_count(static_cast<size_t>(n), 0);
    std::vector<Polyline> lines(static_cast<size_t>(n));
    for (int i = 0; i < n; ++i) {
      lines[static_cast<size_t>(i)] = Polyline(net_.links[static_cast<size_t>(i)].points);
    }
    for (int a = 0; a < n; ++a) {
      if (!open_side(a, true)) {
        continue;
      }
      for (int b = 0; b < n; ++b) {
        if (b == a || !open_side(b, false) ||
            !boxes[static_cast<size_t>(a)].near(boxes[static_cast<size_t>(b)])) {
          continue;
        }
        if (parallel_pair(lines[static_cast<size_t>(a)], lines[static_cast<size_t>(b)])) {
          best_right[static_cast<size_t>(a)] = b;
          ++right_count[static_cast<size_t>(a)];
          ++left_count[static_cast<size_t>(b)];
        }
      }
    }
    for (int a = 0; a < n; ++a) {
      const int b = best_right[static_cast<size_t>(a)];
      if (b < 0 || right_count[static_cast<size_t>(a)] != 1 ||
          left_count[static_cast<size_t>(b)] != 1) {
        continue;
      }
      const Side side = side_of(lines[static_cast<size_t>(a)], lines[static_cast<size_t>(b)]);
      const std::string gap = format_fixed(-side.lat_mid, 1);
      set(a, true, b,
          "parallel same-direction link " + gap + " m to the right with matching ends (" +
              "neighbour not recorded)");
      set(b, false, a,
          "parallel same-direction link " + gap + " m to the left with matching ends (" +
              "neighbour not recorded)");
    }
  }

 private:
  struct Box {
    double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    bool near(const Box& o) const {
      constexpr double kMargin = 6.0;
      return x0 - kMargin <= o.x1 && o.x0 - kMargin <= x1 && y0 - kMargin <= o.y1 &&
             o.y0 - kMargin <= y1;
    }
  };
  static Box box_of(const std::vector<Point3>& points) {
    Box box{points[0].x, points[0].y, points[0].x, points[0].y};
    for (const Point3& p : points) {
      box.x0 = std::min(box.x0, p.x);
      box.y0 = std::min(box.y0, p.y);
      box.x1 = std::max(box.x1, p.x);
      box.y1 = std::max(box.y1, p.y);
    }
    return box;
  }

  bool open_side(int link, bool right) const {
    const LinkState& state = net_.links[static_cast<size_t>(link)];
    return !state.removed && !net_.is_junction(link) && (right ? state.right : state.left) < 0 &&
           state.length >= 5.0;
  }

  static bool parallel_pair(const Polyline& a, const Polyline& b) {
    const Side side = side_of(a, b);
    const double slack = std::max(3.0, 0.05 * a.length());
    const auto lane_gap = [](double lateral) { return lateral < -2.3 && lateral > -6.0; };
    return side.same_direction && lane_gap(side.lat_start) && lane_gap(side.lat_end) &&
           lane_gap(side.lat_mid) && side.lat_max < -2.3 && side.lat_min > -6.0 &&
           std::abs(side.stagger_start) <= slack && std::abs(side.stagger_end) <= slack;
  }

  int pointer(int link, bool right) const {
    const LinkState& state = net_.links[static_cast<size_t>(link)];
    return right ? state.right : state.left;
  }

  void set(int link, bool right, int value, const std::string& reason) {
    LinkState& state = net_.links[static_cast<size_t>(link)];
    int& slot = right ? state.right : state.left;
    if (slot == value) {
      return;
    }
    const std::string old_id = slot < 0 ? "" : net_.source(slot).id;
    const std::string new_id = value < 0 ? "" : net_.source(value).id;
    slot = value;
    log_.add(link, field_name(right), old_id, new_id, reason);
  }

  Network& net_;
  CorrectionLog& log_;
};

/// How right-hand neighbour b joins a in one road, if it does.
enum class Join { kNone, kBeside, kSplit, kMerge };

Join road_join(const Network& net, int a, int b) {
  if (net.source(a).link_type != net.source(b).link_type) {
    return Join::kNone;
  }
  const LinkState& la = net.links[static_cast<size_t>(a)];
  const LinkState& lb = net.links[static_cast<size_t>(b)];
  const Polyline pa(la.points);
  const Polyline pb(lb.points);
  const Side side = side_of(pa, pb);
  const double slack = std::max(3.0, 0.1 * std::min(pa.length(), pb.length()));
  const auto lane_gap = [](double lateral) { return lateral < -1.5 && lateral > -7.0; };
  const bool start_beside = lane_gap(side.lat_start) && std::abs(side.stagger_start) <= slack;
  const bool end_beside = lane_gap(side.lat_end) && std::abs(side.stagger_end) <= slack;
  if (start_beside && end_beside && lane_gap(side.lat_mid)) {
    return Join::kBeside;
  }
  // One lane splitting into two (both start at one node) or two merging into one: the same
  // road, where one of them widens from (narrows to) nothing.
  if (!side.same_direction || (la.from == lb.from && la.to == lb.to)) {
    return Join::kNone;
  }
  if (la.from == lb.from && end_beside) {
    return Join::kSplit;
  }
  if (la.to == lb.to && start_beside) {
    return Join::kMerge;
  }
  return Join::kNone;
}

/// Lateral offset (m) of `link`, `reach` metres from its shared end, from the straight
/// continuation of `other` (the link before or after the shared node): 0 for the lane that
/// carries straight on.
double deviation(const Network& net, int link, int other, bool at_start) {
  const Polyline line(net.links[static_cast<size_t>(link)].points);
  const Polyline base(net.links[static_cast<size_t>(other)].points);
  const double reach = std::min(15.0, 0.5 * line.length());
  const Point3 q = line.at(at_start ? reach : line.length() - reach);
  const Point3 a = base.at(at_start ? base.length() : 0.0);
  const Vec2 d = base.direction(at_start ? base.length() : 0.0);
  return std::abs(cross(d, xy(q) - xy(a)));
}

/// Which of neighbours `left` and `right` sharing a node is the lane that appears (at_start) or
/// disappears there: the one turning away from the link through the node; without one, a
/// left-turn pocket, else the right (outer) lane.
bool left_one_is_new(const Network& net, int left, int right, bool at_start) {
  const LinkState& state = net.links[static_cast<size_t>(left)];
  const auto& through = at_start ? net.ending[static_cast<size_t>(state.from)]
                                 : net.starting[static_cast<size_t>(state.to)];
  if (through.size() == 1) {
    return deviation(net, left, through[0], at_start) > deviation(net, right, through[0], at_start);
  }
  return is_pocket_number(net.source(left).lane_no) && !is_pocket_number(net.source(right).lane_no);
}

}  // namespace

void repair_neighbours(Network& network, CorrectionLog& log) {
  NeighbourRepair repair(network, log);
  repair.drop_invalid();
  repair.make_reciprocal();
  repair.infer_missing();
}

LateralStructure lateral_structure(const Network& network) {
  LateralStructure out;
  const int n = static_cast<int>(network.size());
  std::vector<int> group_of(static_cast<size_t>(n), -1);
  std::vector<int> visited(static_cast<size_t>(n), -1);  // walk stamp, guards against cycles
  const auto left_of = [&](int link) { return network.links[static_cast<size_t>(link)].left; };
  const auto right_of = [&](int link) { return network.links[static_cast<size_t>(link)].right; };
  const auto free = [&](int link) {
    return link >= 0 && group_of[static_cast<size_t>(link)] < 0 &&
           !network.links[static_cast<size_t>(link)].removed;
  };
  for (int i = 0; i < n; ++i) {
    while (free(i)) {
      int leftmost = i;
      visited[static_cast<size_t>(i)] = i;
      for (int l = left_of(i); free(l) && visited[static_cast<size_t>(l)] != i; l = left_of(l)) {
        visited[static_cast<size_t>(l)] = i;
        leftmost = l;
      }
      std::vector<int> group;
      for (int r = leftmost; free(r); r = right_of(r)) {
        group_of[static_cast<size_t>(r)] = static_cast<int>(out.groups.size());
        group.push_back(r);
      }
      out.groups.push_back(std::move(group));
      // If i was not on the right-walk from its leftmost link, the next pass starts at i.
    }
  }
  for (size_t g = 0; g < out.groups.size(); ++g) {
    const std::vector<int>& group = out.groups[g];
    const auto single = [&](size_t k) {
      return LaneRun{{group[k]},
                     {LaneEnd::kBeside},
                     {LaneEnd::kBeside},
                     static_cast<int>(g),
                     static_cast<int>(k)};
    };
    LaneRun run = single(0);
    for (size_t k = 1; k < group.size(); ++k) {
      const Join join = road_join(network, group[k - 1], group[k]);
      if (join == Join::kNone) {
        out.runs.push_back(std::move(run));
        run = single(k);
        continue;
      }
      run.links.push_back(group[k]);
      run.starts.push_back(LaneEnd::kBeside);
      run.ends.push_back(LaneEnd::kBeside);
      if (join == Join::kSplit || join == Join::kMerge) {
        const bool at_start = join == Join::kSplit;
        auto& ends = at_start ? run.starts : run.ends;
        const size_t right = ends.size() - 1;
        if (left_one_is_new(network, group[k - 1], group[k], at_start)) {
          ends[right - 1] = LaneEnd::kFromRight;
        } else {
          ends[right] = LaneEnd::kFromLeft;
        }
      }
    }
    out.runs.push_back(std::move(run));
  }
  return out;
}

}  // namespace corsa::ngii::detail
