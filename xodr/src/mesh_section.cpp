// Cross-section evaluation of one lane section and the adaptive s sampling of the road mesh.

#include "mesh_section.h"

#include <algorithm>
#include <cmath>

namespace corsa::xodr::detail {
namespace {

/// Breakpoints closer than this (m) are merged, and intervals are not split below it: files
/// often place records a rounding error apart, and a sub-millimetre slice only makes slivers.
constexpr double kMinStep = 1e-3;
/// Deepest bisection of one interval between knots (2^-40 of it is far below kMinStep).
constexpr int kMaxDepth = 40;
/// The largest deviation may fall between the probes (at 1/4, 1/2, 3/4 of an interval): on
/// clothoids and cubics it exceeds the largest probe by a few per cent at most.
constexpr double kProbeMargin = 0.9;
/// A record start whose left and right limits put some border further apart than this (m) is a
/// jump: the mesh gets an edge there instead of bisecting towards it.
constexpr double kJump = 1e-5;

double distance_to_segment(const Vec3& p, const Vec3& a, const Vec3& b) {
  const double abx = b.x - a.x;
  const double aby = b.y - a.y;
  const double abz = b.z - a.z;
  const double apx = p.x - a.x;
  const double apy = p.y - a.y;
  const double apz = p.z - a.z;
  const double length2 = abx * abx + aby * aby + abz * abz;
  double u = length2 > 0.0 ? (apx * abx + apy * aby + apz * abz) / length2 : 0.0;
  u = std::clamp(u, 0.0, 1.0);
  const double dx = apx - u * abx;
  const double dy = apy - u * aby;
  const double dz = apz - u * abz;
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}

/// Rows evaluated while sampling, in an append-only store addressed by index.
class RowStore {
 public:
  RowStore(const SectionView& view) : view_(view), borders_(view.borders()) {
    // On roads with a lateral shape the lane middles are checked too (the surface between two
    // borders is not flat there).
    points_ = borders_ + (view.has_shape() ? view.lanes() : 0);
  }

  size_t add(double s) {
    const size_t index = s_.size();
    s_.push_back(s);
    frames_.push_back(view_.frame(s));
    t_.resize(t_.size() + borders_);
    double* t = t_.data() + index * borders_;
    view_.border_ts(s, t);
    p_.resize(p_.size() + points_);
    Vec3* p = p_.data() + index * points_;
    for (size_t j = 0; j < borders_; ++j) {
      p[j] = view_.surface(frames_[index], t[j]);
    }
    for (size_t i = 0; borders_ + i < points_; ++i) {
      p[borders_ + i] = view_.surface(frames_[index], 0.5 * (t[i] + t[i + 1]));
    }
    return index;
  }

  double s(size_t row) const { return s_[row]; }

  /// Largest distance between the same point of two rows.
  double distance(size_t a, size_t b) const {
    const Vec3* pa = p_.data() + a * points_;
    const Vec3* pb = p_.data() + b * points_;
    double worst = 0.0;
    for (size_t j = 0; j < points_; ++j) {
      worst = std::max(worst, std::hypot(pa[j].x - pb[j].x, pa[j].y - pb[j].y, pa[j].z - pb[j].z));
    }
    return worst;
  }

  /// Largest distance of row `probe`'s points from the segments joining rows a and b.
  double deviation(size_t a, size_t b, size_t probe) const {
    const Vec3* pa = p_.data() + a * points_;
    const Vec3* pb = p_.data() + b * points_;
    const Vec3* pm = p_.data() + probe * points_;
    double worst = 0.0;
    for (size_t j = 0; j < points_; ++j) {
      worst = std::max(worst, distance_to_segment(pm[j], pa[j], pb[j]));
    }
    return worst;
  }

  void emit(size_t row, SectionSamples& out) const {
    out.s.push_back(s_[row]);
    out.frames.push_back(frames_[row]);
    out.t.insert(out.t.end(), t_.begin() + static_cast<std::ptrdiff_t>(row * borders_),
                 t_.begin() + static_cast<std::ptrdiff_t>((row + 1) * borders_));
  }

 private:
  const SectionView& view_;
  size_t borders_ = 0;
  size_t points_ = 0;
  std::vector<double> s_;
  std::vector<RoadFrame> frames_;
  std::vector<double> t_;
  std::vector<Vec3> p_;
};

struct Refiner {
  RowStore& rows;
  SectionSamples& out;
  double tolerance = 0.1;
  double max_segment = 0.0;

  /// Emits the rows after `a` up to and including `b`; `m` is the row at their middle. The
  /// quarter points are probed as well as the middle, so that an S-shaped stretch whose middle
  /// happens to lie on the chord is still split.
  void refine(size_t a, size_t m, size_t b, int depth) {
    const double sa = rows.s(a);
    const double sb = rows.s(b);
    const size_t q1 = rows.add(0.5 * (sa + rows.s(m)));
    const size_t q3 = rows.add(0.5 * (rows.s(m) + sb));
    const bool too_long = max_segment > 0.0 && sb - sa > max_segment;
    const double error =
        std::max({rows.deviation(a, b, q1), rows.deviation(a, b, m), rows.deviation(a, b, q3)});
    const bool can_split = sb - sa >= 4.0 * kMinStep && depth < kMaxDepth;
    if ((error > kProbeMargin * tolerance || too_long) && can_split) {
      refine(a, q1, m, depth + 1);
      refine(m, q3, b, depth + 1);
      return;
    }
    rows.emit(b, out);
  }
};

/// A record start where the samples need a row, and whether the cross-section jumps there.
struct Knot {
  double s = 0.0;
  bool jump = false;
};

/// The record starts, each checked for a jump (its left and right limits differ by more than
/// kJump somewhere across the road), merged where closer than kMinStep (a jump is kept over a
/// smooth knot; s0 and s1 stay).
std::vector<Knot> find_knots(const SectionView& view, RowStore& rows) {
  std::vector<Knot> knots;
  for (double s : view.record_starts()) {
    Knot knot{s, false};
    if (s > 0.0) {
      const size_t left = rows.add(s - kJumpEpsilon);
      const size_t right = rows.add(s);
      knot.jump = rows.distance(left, right) > kJump;
    }
    if (!knots.empty() && s < knots.back().s + kMinStep) {
      Knot& last = knots.back();
      if (s == view.s1()) {
        last.s = s;  // the end stays the end
        last.jump = last.jump || knot.jump;
      } else if (knot.jump && !last.jump && last.s != view.s0()) {
        last = knot;
      }
      continue;
    }
    knots.push_back(knot);
  }
  if (knots.size() == 1) {
    knots.push_back(Knot{view.s1(), false});  // a section shorter than kMinStep
  }
  return knots;
}

}  // namespace

SectionView::SectionView(const Map& map, uint32_t road, uint32_t section)
    : map_(map),
      road_(map.road(road)),
      section_(road_.lane_sections[section]),
      road_index_(road),
      section_index_(section) {
  s0_ = std::min(section_.s, road_.length);
  s1_ = std::min(map.section_end(road, section), road_.length);
  for (const Lane& lane : section_.lanes) {
    if (lane.id != 0 && lane_count_ < kMaxLanesPerSection) {
      span_lanes_[lane_count_++] = &lane;
    }
  }
}

RoadFrame SectionView::frame(double s) const {
  const RefPoint ref = map_.reference(road_index_, s);
  RoadFrame f;
  f.s = s;
  f.x = ref.x;
  f.y = ref.y;
  f.cos_h = std::cos(ref.hdg);
  f.sin_h = std::sin(ref.hdg);
  f.z = road_.elevation.empty() ? 0.0 : map_.elevation(road_index_, s);
  if (!road_.superelevation.empty()) {
    const double roll = map_.superelevation(road_index_, s);
    f.cos_r = std::cos(roll);
    f.sin_r = std::sin(roll);
  }
  return f;
}

void SectionView::border_ts(double s, double* out) const {
  LaneSpan spans[kMaxLanesPerSection];
  // At the section's end the laneOffset of this section applies, not a record that starts
  // exactly there with the next section (CARLA does this; lanes would jump by metres).
  const double offset = section_lane_offset(map_, road_index_, section_index_, s);
  const size_t n = compute_spans(section_, s, offset, spans);
  // Left lanes (id > 0) have their outer border on the left, right lanes on the right; the
  // spans are contiguous, so span i's right border is span i + 1's left border.
  out[0] = n == 0 ? offset : (spans[0].id > 0 ? spans[0].t_outer : spans[0].t_inner);
  for (size_t i = 0; i < n; ++i) {
    out[i + 1] = spans[i].id > 0 ? spans[i].t_inner : spans[i].t_outer;
  }
}

Vec3 SectionView::surface(const RoadFrame& f, double t) const {
  const double horizontal = t * f.cos_r;
  Vec3 p;
  p.x = f.x - f.sin_h * horizontal;
  p.y = f.y + f.cos_h * horizontal;
  p.z = f.z + t * f.sin_r;
  if (has_shape()) {
    p.z += map_.shape_height(road_index_, f.s, t);
  }
  return p;
}

double SectionView::lane_height(size_t i, double s, bool left) const {
  const Lane& l = lane(i);
  if (l.heights.empty()) {
    return 0.0;
  }
  // A left lane's inner border is its right one; a right lane's inner border is its left one.
  const bool inner = left == (l.id < 0);
  const auto value = [inner](const LaneHeight& h) { return inner ? h.inner : h.outer; };
  const double ds = s - section_.s;
  const size_t k = record_index(l.heights, ds, [](const LaneHeight& h) { return h.s_offset; });
  const LaneHeight& here = l.heights[k];
  if (k + 1 >= l.heights.size() || ds <= here.s_offset) {
    return value(here);
  }
  // Linear between records, so that a change of height is a ramp rather than a step (a step
  // would open a crack across the lane).
  const LaneHeight& next = l.heights[k + 1];
  const double span = next.s_offset - here.s_offset;
  const double w = span > 0.0 ? std::clamp((ds - here.s_offset) / span, 0.0, 1.0) : 1.0;
  return value(here) + w * (value(next) - value(here));
}

std::vector<double> SectionView::record_starts() const {
  std::vector<double> s{s0_, s1_};
  const auto add = [&](double value) {
    if (value > s0_ && value < s1_) {
      s.push_back(value);
    }
  };
  for (const Geometry& g : road_.plan_view) {
    add(g.s);
  }
  for (const auto* records : {&road_.elevation, &road_.superelevation, &road_.lane_offsets}) {
    for (const Poly3& p : *records) {
      add(p.s);
    }
  }
  for (const ShapeRecord& shape : road_.shapes) {
    add(shape.s);
  }
  for (const Lane& lane : section_.lanes) {
    for (const auto* records : {&lane.widths, &lane.borders}) {
      for (const Poly3& p : *records) {
        add(section_.s + p.s);
      }
    }
    for (const LaneHeight& h : lane.heights) {
      add(section_.s + h.s_offset);
    }
  }
  std::sort(s.begin(), s.end());
  s.erase(std::unique(s.begin(), s.end()), s.end());
  return s;
}

SectionSamples sample_section(const SectionView& view, double tolerance, double max_segment) {
  SectionSamples out;
  out.borders = view.borders();
  RowStore rows(view);
  const std::vector<Knot> knots = find_knots(view, rows);
  Refiner refiner{rows, out, tolerance, max_segment};
  // A jump on s0 gets both limits: the left one meets the previous section's last row.
  size_t previous = rows.add(knots.front().jump ? knots.front().s - kJumpEpsilon : knots.front().s);
  rows.emit(previous, out);
  if (knots.front().jump) {
    previous = rows.add(knots.front().s);
    rows.emit(previous, out);
  }
  for (size_t k = 1; k < knots.size(); ++k) {
    const Knot& knot = knots[k];
    const size_t end = rows.add(knot.jump ? knot.s - kJumpEpsilon : knot.s);
    const size_t middle = rows.add(0.5 * (rows.s(previous) + rows.s(end)));
    refiner.refine(previous, middle, end, 0);
    previous = end;
    if (knot.jump && k + 1 < knots.size()) {
      previous = rows.add(knot.s);  // the right limit
      rows.emit(previous, out);
    }
  }
  return out;
}

}  // namespace corsa::xodr::detail
