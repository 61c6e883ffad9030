// Precautions of generated traffic (controllers/npc_caution.h).

#include "controllers/npc_caution.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "controllers/follow_view.h"
#include "corsa/engine/oriented_box.h"
#include "geometry/segment.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {
namespace {

constexpr double kSideMargin = 0.5;      // m each side of a vehicle's corridor
constexpr double kBehindReach = 40.0;    // m behind, for faster scenario vehicles
constexpr double kWalkerLook = 4.0;      // m ahead a walker looks
constexpr double kWalkerBand = 0.9;      // m either side of a walker's path it keeps clear
constexpr double kWalkerStep = 0.7;      // m a walker steps aside (walkers are 0.6 m wide)
constexpr double kWalkerContact = 0.9;   // m ahead: too close to walk on
constexpr double kWalkerAbreast = 0.65;  // m across: walkers nearer than this would touch
constexpr double kSlack = 0.01;          // m around a grid query, against rounding

/// A frame at an entity's reference point, x along its heading, y to its left.
struct LocalFrame {
  double x = 0.0, y = 0.0, c = 1.0, s = 0.0;
  explicit LocalFrame(const Pose& pose)
      : x(pose.x), y(pose.y), c(std::cos(pose.h)), s(std::sin(pose.h)) {}
  LocalFrame(double x_in, double y_in, double c_in, double s_in)
      : x(x_in), y(y_in), c(c_in), s(s_in) {}
  void to_local(double wx, double wy, double& lx, double& ly) const {
    const double dx = wx - x, dy = wy - y;
    lx = dx * c + dy * s;
    ly = -dx * s + dy * c;
  }
};

/// The frame at `me`, entity `index` of `view`. The cosine and sine of its heading are those of
/// its box in the view when the view took the same heading, to the bit (box_of computes them as
/// LocalFrame(pose) does): the picture was mostly taken at the pose the entity still has.
LocalFrame frame_at(const Entity& me, uint32_t index, const FollowView& view) {
  const Pose& pose = me.state().pose;
  if (view.has_shapes() && index < view.targets().size()) {
    const FollowTarget& seen = view.targets()[index];
    if (seen.present && same_bits(seen.h, pose.h)) {
      return LocalFrame(pose.x, pose.y, seen.shape.cos_h, seen.shape.sin_h);
    }
  }
  return LocalFrame(pose);
}

/// The extent along x of the part of `box` (another entity's) that lies within |y| <= half in
/// `frame`; false when no part does.
[[gnu::hot]] bool extent_in_band(const LocalFrame& frame, const FlatBox& box, double half,
                                 double& x_min, double& x_max) {
  double px[4], py[4];
  for (int k = 0; k < 4; ++k) {
    const double along = (k == 0 || k == 3) ? box.half_length : -box.half_length;
    const double across = k < 2 ? box.half_width : -box.half_width;
    frame.to_local(box.cx + along * box.cos_h - across * box.sin_h,
                   box.cy + along * box.sin_h + across * box.cos_h, px[k], py[k]);
  }
  x_min = 1e300;
  x_max = -1e300;
  if (std::abs(py[0]) <= half && std::abs(py[1]) <= half && std::abs(py[2]) <= half &&
      std::abs(py[3]) <= half) {
    // The whole box in the band (mostly a box ahead in the lane): every edge is kept whole, from
    // t = 0 to t = 1 as below, to the bit (1 x d is d; 0 x d is not folded, for d infinite or
    // NaN), without the tests of each edge's ends.
    for (int k = 0; k < 4; ++k) {
      const double ax = px[k], d = px[(k + 1) % 4] - ax;
      const double start = ax + 0.0 * d, end = ax + d;
      x_min = std::min(std::min(x_min, start), end);
      x_max = std::max(std::max(x_max, start), end);
    }
    return x_min <= x_max;
  }
  for (int k = 0; k < 4; ++k) {
    // Clip edge k -> k+1 to the band.
    const double ax = px[k], ay = py[k];
    const double bx = px[(k + 1) % 4], by = py[(k + 1) % 4];
    double t0 = 0.0, t1 = 1.0;
    const double dy = by - ay;
    if (std::abs(ay) <= half && std::abs(by) <= half) {
      // Both ends in the band (the usual case: a box ahead in the lane): the clipping below
      // would keep the whole edge, t0 = +0 and t1 = 1 to the bit (with -half <= ay, by <= half
      // the rounded quotients are ta <= 0 and tb >= 1, since rounding is monotonic and
      // (by - ay) / dy rounds to 1), without its two divisions.
    } else if (std::abs(dy) < 1e-12) {
      if (std::abs(ay) > half) {
        continue;
      }
    } else {
      double ta = (-half - ay) / dy, tb = (half - ay) / dy;
      if (ta > tb) {
        std::swap(ta, tb);
      }
      t0 = std::max(t0, ta);
      t1 = std::min(t1, tb);
      if (t0 > t1) {
        continue;
      }
    }
    for (const double t : {t0, t1}) {
      const double x = ax + t * (bx - ax);
      x_min = std::min(x_min, x);
      x_max = std::max(x_max, x);
    }
  }
  return x_min <= x_max;
}

// The bounding box (m) of the rectangle [x0, x1] x [-half, half] of `frame` widened by `margin`
// on every side of the box, and whether every input is finite (else the box may be NaN).
struct RectangleBounds {
  double x_min = 0.0, y_min = 0.0, x_max = 0.0, y_max = 0.0;
  bool finite = false;
};

[[gnu::always_inline]] inline RectangleBounds bounds_of(const LocalFrame& frame, double x0,
                                                        double x1, double half, double margin) {
  double x_min = std::numeric_limits<double>::infinity(), x_max = -x_min;
  double y_min = x_min, y_max = -x_min;
  for (const double lx : {x0, x1}) {
    for (const double ly : {-half, half}) {
      const double wx = frame.x + lx * frame.c - ly * frame.s;
      const double wy = frame.y + lx * frame.s + ly * frame.c;
      x_min = std::min(x_min, wx);
      x_max = std::max(x_max, wx);
      y_min = std::min(y_min, wy);
      y_max = std::max(y_max, wy);
    }
  }
  const bool finite = std::isfinite(frame.x) && std::isfinite(frame.y) && std::isfinite(frame.c) &&
                      std::isfinite(frame.s) && std::isfinite(x0) && std::isfinite(x1) &&
                      std::isfinite(half) && std::isfinite(margin);
  return {x_min - margin, y_min - margin, x_max + margin, y_max + margin, finite};
}

// Appends to `near` (emptied first) every present entity of `view` (only the scenario's vehicles
// with `scenario_vehicles`) whose box centre may lie within `margin` metres of the rectangle
// [x0, x1] x [-half, half] of `frame`: those whose centre's frame coordinates lie in that
// rectangle widened by `margin` on every side (a superset). A box reaching into the rectangle
// has its centre within FollowView::max_reach() of it, a reference point in the rectangle within
// FollowView::max_offset(). For a finite rectangle, the entities FollowView::visit_band hands out
// for the bounds_of the rectangle (corridor_hazard visits them so, without the list).
[[gnu::hot]] void near_rectangle(const FollowView& view, const LocalFrame& frame, double x0,
                                 double x1, double half, double margin, std::vector<uint32_t>& near,
                                 bool scenario_vehicles = false) {
  near.clear();
  const RectangleBounds box = bounds_of(frame, x0, x1, half, margin);
  if (box.finite) {
    // Only the band of the rectangle, not its whole bounding box (a corridor at 45 degrees
    // covers a seventh of it): with dense traffic most of the box's entities are in other
    // lanes and roads.
    view.near_band(box.x_min, box.y_min, box.x_max, box.y_max, frame.x, frame.y, frame.c, frame.s,
                   x0 - margin, x1 + margin, half + margin, scenario_vehicles, near);
  } else if (scenario_vehicles) {
    view.near_scenario_vehicles(box.x_min, box.y_min, box.x_max, box.y_max, near);
  } else {
    view.near(box.x_min, box.y_min, box.x_max, box.y_max, near);
  }
}

// Whether the box of `other` may reach into [x0, x1] x [-half, half] of `frame`: its bounding
// rectangle in the frame's axes overlaps that rectangle. Rejects most of a grid query's entities
// (those of the neighbouring lanes too) before the exact test.
// `least` is then a bound below the least x of the box in the frame, as extent_in_band computes
// it: its bounding rectangle's, less kSlack and a margin for the rounding of coordinates far from
// the origin (the corners' coordinates are rounded near their magnitude).
bool may_reach(const LocalFrame& frame, const FollowTarget& other, double x0, double x1,
               double half, double& least) {
  const FlatBox& box = other.shape;
  double x = 0.0, y = 0.0;
  frame.to_local(box.cx, box.cy, x, y);
  // The box's axes in the frame: cos and sin of the heading difference.
  const double c = std::abs(box.cos_h * frame.c + box.sin_h * frame.s);
  const double s = std::abs(box.sin_h * frame.c - box.cos_h * frame.s);
  const double along = box.half_length * c + box.half_width * s + kSlack;
  const double across = box.half_length * s + box.half_width * c + kSlack;
  least = x - along -
          1e-9 * (std::abs(frame.x) + std::abs(frame.y) + std::abs(box.cx) + std::abs(box.cy));
  return x + along >= x0 && x - along <= x1 && std::abs(y) - across <= half;
}

bool may_reach(const LocalFrame& frame, const FollowTarget& other, double x0, double x1,
               double half) {
  double least = 0.0;
  return may_reach(frame, other, x0, x1, half, least);
}

}  // namespace

bool is_generated(const SimState& state, uint32_t index) {
  return state.traffic.lifetimes.count(index) != 0;
}

[[gnu::hot]] Hazard corridor_hazard(const Entity& me, uint32_t index, const FollowView& view,
                                    double reach, double wanted, std::vector<uint32_t>& near,
                                    const Hazard& followed) {
  const LocalFrame frame = frame_at(me, index, view);
  const double front = me.info.box.center_x + 0.5 * me.info.box.length;
  const double rear = me.info.box.center_x - 0.5 * me.info.box.length;
  const double half = 0.5 * me.info.box.width + kSideMargin;
  Hazard hazard;
  uint32_t chosen = kNoHazardEntity;
  // The result is the least gap (of equal gaps the lowest index) whatever the order the
  // entities are considered in: an entity skipped below could not have been chosen.
  const auto consider = [&](uint32_t j) {
    const FollowTarget& other = view.targets()[j];
    if (j == index || !other.present) {
      return;
    }
    // The box first (most of the grid's entities are in the neighbouring lanes, which it
    // rejects): it lies in the target's second cache line, the reference point in its first.
    double least = 0.0;
    if (!may_reach(frame, other, rear, front + reach, half, least)) {
      return;
    }
    const double dx = other.x - me.state().pose.x;
    const double dy = other.y - me.state().pose.y;
    const double far = front + reach + other.length + 10.0;
    if (dx * dx + dy * dy > far * far) {
      return;
    }
    // The exact test only for a box that can be nearer than the nearest so far (of an equal gap
    // its index may decide) and nearer than `wanted`: its gap is at least least - front.
    const double bound = least - front;
    if (bound >= wanted || bound > hazard.gap) {
      return;
    }
    double x_min = 0.0, x_max = 0.0;
    if (!extent_in_band(frame, other.shape, half, x_min, x_max) || x_max < rear ||
        x_min > front + reach) {
      return;
    }
    // Of equal gaps the lowest index, as a scan of the entities in order keeps.
    const double gap = std::max(0.0, x_min - front);
    if (gap < hazard.gap || (gap == hazard.gap && j < chosen)) {
      chosen = j;
      hazard.gap = gap;
    }
  };
  // A box reaching into the corridor has its centre within max_reach of it. The grid's runs of
  // entities are considered as the query hands them out (near_rectangle's, without the list).
  const double margin = view.max_reach() + kSlack;
  const RectangleBounds box = bounds_of(frame, rear, front + reach, half, margin);
  if (box.finite) {
    view.visit_band(box.x_min, box.y_min, box.x_max, box.y_max, frame.x, frame.y, frame.c, frame.s,
                    rear - margin, front + reach + margin, half + margin, false,
                    [&consider](const uint32_t* ids, size_t count) {
                      for (size_t k = 0; k < count; ++k) consider(ids[k]);
                    });
  } else {
    near_rectangle(view, frame, rear, front + reach, half, margin, near);
    for (const uint32_t j : near) consider(j);
  }
  // The speed (a cosine) of the one chosen only, not of every nearer one met before it. In
  // dense traffic that is often the caller's leader, whose speed the caller has (and whose box's
  // gap in the corridor is mostly a little below its gap along the lanes, so this one is read).
  hazard.entity = chosen;
  if (chosen == followed.entity && chosen != kNoHazardEntity) {
    hazard.speed = followed.speed;
  } else if (chosen != kNoHazardEntity) {
    const FollowTarget& other = view.targets()[chosen];
    hazard.speed = speed_along(other.speed, other.h, me.state().pose.h);
  }
  return hazard;
}

[[gnu::hot]] double keep_ahead_speed(const Entity& me, uint32_t index, const FollowView& view,
                                     std::vector<uint32_t>& near) {
  if (!view.has_scenario_vehicles()) {
    return 0.0;
  }
  const LocalFrame frame = frame_at(me, index, view);
  const double rear = me.info.box.center_x - 0.5 * me.info.box.length;
  const double half = 0.5 * me.info.box.width + kSideMargin;
  near_rectangle(view, frame, rear - kBehindReach, rear, half, view.max_reach() + kSlack, near,
                 true);
  double needed = 0.0;
  for (const uint32_t j : near) {
    const FollowTarget& other = view.targets()[j];
    if (j == index || !other.present || other.generated || !other.vehicle ||
        !may_reach(frame, other, rear - kBehindReach, rear, half)) {
      continue;
    }
    const double along = std::cos(other.h - me.state().pose.h);
    const double speed = other.speed * along;
    if (along < 0.7 || speed <= me.state().speed) {
      continue;  // not coming up behind us
    }
    double x_min = 0.0, x_max = 0.0;
    if (!extent_in_band(frame, other.shape, half, x_min, x_max) || x_max > rear ||
        rear - x_max > kBehindReach) {
      continue;
    }
    needed = std::max(needed, speed + 0.5);
  }
  return needed;
}

SignalAspect signal_aspect(std::string_view state) {
  std::string text;
  for (const char ch : state) {
    text += static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  }
  if (text.find("red") != std::string::npos || text.find("stop") != std::string::npos) {
    return SignalAspect::kStop;
  }
  if (text.find("yellow") != std::string::npos || text.find("amber") != std::string::npos) {
    return SignalAspect::kCaution;
  }
  // Bulb lists, red first: "on;off;off" red, "off;on;off" yellow, "on;on;off" red and yellow.
  std::vector<std::string> bulbs;
  size_t from = 0;
  for (size_t at = 0; at <= text.size(); ++at) {
    if (at == text.size() || text[at] == ';') {
      bulbs.push_back(text.substr(from, at - from));
      from = at + 1;
    }
  }
  if (bulbs.size() >= 3) {
    if (bulbs[0] == "on") {
      return SignalAspect::kStop;
    }
    if (bulbs[1] == "on") {
      return SignalAspect::kCaution;
    }
  }
  return SignalAspect::kGo;
}

WalkerMove walker_move(const Entity& me, uint32_t index, const FollowView& view, double pace,
                       std::vector<uint32_t>& near) {
  const LocalFrame frame = frame_at(me, index, view);
  WalkerMove move{0.0, pace};
  bool oncoming = false;  // coming towards us ahead or on our left
  bool oncoming_right = false;
  bool slower_ahead = false;
  bool beside_left = false;  // one going our way beside us: do not step into it
  bool beside_right = false;
  const double most = 0.5 * (view.max_length() + me.info.box.length);
  near_rectangle(view, frame, -most - 0.3, kWalkerLook + most, kWalkerBand + 0.5,
                 view.max_offset() + kSlack, near);
  for (const uint32_t j : near) {
    const FollowTarget& other = view.targets()[j];
    if (j == index || !other.present) {
      continue;
    }
    double x = 0.0, y = 0.0;
    frame.to_local(other.x, other.y, x, y);
    const double reach = 0.5 * (other.length + me.info.box.length);
    if (x < -reach - 0.3 || x > kWalkerLook + reach || std::abs(y) > kWalkerBand + 0.5) {
      continue;
    }
    const double along = std::cos(other.h - me.state().pose.h);
    const double their_speed = other.speed * along;
    // Across our way the other's box reaches its half width, more when it stands turned (a
    // walker that stopped while stepping aside): walkers nearer than kWalkerAbreast plus that
    // excess would touch.
    double abreast = kWalkerAbreast;
    if (view.has_shapes()) {
      const FlatBox& box = other.shape;
      abreast += box.half_length * std::abs(box.sin_h * frame.c - box.cos_h * frame.s) +
                 box.half_width * (std::abs(box.cos_h * frame.c + box.sin_h * frame.s) - 1.0);
    }
    if (along < -0.5) {
      // Both keep right until they have passed; of one coming on our right (it sees us on its
      // right too) both keep left, away from each other, where keeping right would walk them
      // into each other's way.
      if (x > -reach) {
        (y < 0.0 ? oncoming_right : oncoming) = true;
      }
    } else if (x > reach && their_speed < pace - 0.05) {
      slower_ahead = true;  // pass it on the left
    } else if (std::abs(x) <= reach + 0.3) {
      (y > 0.0 ? beside_left : beside_right) = true;
    }
    // Too close in front to walk on: slower than they go away from us, the more so the closer
    // (at the contact distance their speed, touching nothing), so that a gap opens again; held
    // at their speed a walker close behind one would keep the gap it had, and a sidestep turns
    // its box into the other's.
    if (x > 0.0 && x < kWalkerContact + reach && std::abs(y) < abreast) {
      const double room = std::clamp((x - reach) / kWalkerContact, 0.0, 1.0);
      move.speed = std::min(move.speed, std::max(0.0, their_speed) * room);
    }
  }
  if (oncoming) {
    move.lateral = -kWalkerStep;
  } else if (slower_ahead || oncoming_right) {
    move.lateral = kWalkerStep;
  }
  // Never sideways into one walking beside us (the oncoming rule would send both right).
  if (beside_right) {
    move.lateral = std::max(move.lateral, me.lateral_command);
  }
  if (beside_left) {
    move.lateral = std::min(move.lateral, me.lateral_command);
  }
  return move;
}

namespace {

// Distance (m) between the segments [a0, a1] and [b0, b1] (2D): zero when they cross, else the
// least distance of an end point to the other segment.
double segment_distance(double ax0, double ay0, double ax1, double ay1, double bx0, double by0,
                        double bx1, double by1) {
  const auto cross = [](double ux, double uy, double vx, double vy) { return ux * vy - uy * vx; };
  const double d1 = cross(ax1 - ax0, ay1 - ay0, bx0 - ax0, by0 - ay0);
  const double d2 = cross(ax1 - ax0, ay1 - ay0, bx1 - ax0, by1 - ay0);
  const double d3 = cross(bx1 - bx0, by1 - by0, ax0 - bx0, ay0 - by0);
  const double d4 = cross(bx1 - bx0, by1 - by0, ax1 - bx0, ay1 - by0);
  if (((d1 > 0.0) != (d2 > 0.0)) && ((d3 > 0.0) != (d4 > 0.0))) {
    return 0.0;
  }
  const auto to_segment = [](double px, double py, double x0, double y0, double x1, double y1) {
    const SegmentOffset offset = point_segment({px, py}, {x0, y0}, {x1, y1});
    return std::hypot(offset.dx, offset.dy);
  };
  return std::min(
      {to_segment(ax0, ay0, bx0, by0, bx1, by1), to_segment(ax1, ay1, bx0, by0, bx1, by1),
       to_segment(bx0, by0, ax0, ay0, ax1, ay1), to_segment(bx1, by1, ax0, ay0, ax1, ay1)});
}

}  // namespace

bool walker_waits(const Entity& me, uint32_t index, const FollowView& view, double length,
                  std::vector<uint32_t>& near) {
  constexpr double kClear = 1.5;     // m between a vehicle's side and the path
  constexpr double kWithin = 4.0;    // s ahead a vehicle's way is looked along
  constexpr double kFastest = 20.0;  // m/s: vehicles farther than kWithin at this are not looked at
  const LocalFrame frame = frame_at(me, index, view);
  near_rectangle(view, frame, 0.0, length, kClear, kFastest * kWithin + view.max_reach(), near);
  const double x0 = me.state().pose.x, y0 = me.state().pose.y;
  const double x1 = x0 + length * frame.c, y1 = y0 + length * frame.s;
  for (const uint32_t j : near) {
    const FollowTarget& other = view.targets()[j];
    if (j == index || !other.present || !other.vehicle) {
      continue;
    }
    // The stretch its box covers now and over the next kWithin seconds, along its heading.
    const FlatBox& box = other.shape;
    const double ahead = box.half_length + std::max(other.speed, 0.0) * kWithin;
    const double bx0 = box.cx - box.half_length * box.cos_h,
                 by0 = box.cy - box.half_length * box.sin_h;
    const double bx1 = box.cx + ahead * box.cos_h, by1 = box.cy + ahead * box.sin_h;
    if (segment_distance(x0, y0, x1, y1, bx0, by0, bx1, by1) < box.half_width + kClear) {
      return true;
    }
  }
  return false;
}

}  // namespace corsa::engine::detail
