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
/// A planView joint turning more than this (rad) or jumping more than this (m) is a kink: the
/// mesh gets an edge there instead of bisecting towards it.
constexpr double kKinkTurn = 1e-4;
constexpr double kKinkGap = 1e-4;

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

  size_t add(double s) { return add(view_.frame(s)); }

  size_t add(const RoadFrame& frame) {
    const size_t index = s_.size();
    const double s = frame.s;
    s_.push_back(s);
    frames_.push_back(frame);
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
    if ((error > tolerance || too_long) && can_split) {
      refine(a, q1, m, depth + 1);
      refine(m, q3, b, depth + 1);
      return;
    }
    rows.emit(b, out);
  }
};

}  // namespace

SectionView::SectionView(const Map& map, uint32_t road, uint32_t section)
    : map_(map), road_(map.road(road)), section_(road_.lane_sections[section]), road_index_(road) {
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
  const size_t n = compute_spans(section_, s, map_.lane_offset(road_index_, s), spans);
  // Left lanes (id > 0) have their outer border on the left, right lanes on the right; the
  // spans are contiguous, so span i's right border is span i + 1's left border.
  out[0] = n == 0 ? map_.lane_offset(road_index_, s)
                  : (spans[0].id > 0 ? spans[0].t_outer : spans[0].t_inner);
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

RoadFrame SectionView::frame_before(const Knot& knot) const {
  RoadFrame f = frame(knot.s);
  const Geometry& previous = road_.plan_view[static_cast<size_t>(knot.kink_geometry) - 1];
  const RefPoint ref = evaluate_geometry(previous, knot.s - previous.s);
  f.x = ref.x;
  f.y = ref.y;
  f.cos_h = std::cos(ref.hdg);
  f.sin_h = std::sin(ref.hdg);
  return f;
}

std::vector<Knot> SectionView::knots() const {
  // Kinks are hard knots: always kept, and snapped to s0 / s1 when that close to them.
  std::vector<Knot> hard;
  for (size_t g = 1; g < road_.plan_view.size(); ++g) {
    const Geometry& previous = road_.plan_view[g - 1];
    const Geometry& here = road_.plan_view[g];
    const RefPoint end = evaluate_geometry(previous, here.s - previous.s);
    const double turn = std::remainder(here.hdg - end.hdg, 2.0 * 3.14159265358979323846);
    const bool kink =
        std::abs(turn) > kKinkTurn || std::hypot(here.x - end.x, here.y - end.y) > kKinkGap;
    if (kink && here.s > s0_ - kMinStep && here.s < s1_ + kMinStep) {
      const double at = here.s < s0_ + kMinStep ? s0_ : here.s > s1_ - kMinStep ? s1_ : here.s;
      hard.push_back(Knot{at, static_cast<int>(g)});
    }
  }
  std::vector<double> soft;
  for (const Geometry& g : road_.plan_view) {
    soft.push_back(g.s);
  }
  for (const auto* records : {&road_.elevation, &road_.superelevation, &road_.lane_offsets}) {
    for (const Poly3& p : *records) {
      soft.push_back(p.s);
    }
  }
  for (const ShapeRecord& shape : road_.shapes) {
    soft.push_back(shape.s);
  }
  for (const Lane& lane : section_.lanes) {
    for (const auto* records : {&lane.widths, &lane.borders}) {
      for (const Poly3& p : *records) {
        soft.push_back(section_.s + p.s);
      }
    }
    for (const LaneHeight& h : lane.heights) {
      soft.push_back(section_.s + h.s_offset);
    }
  }
  std::vector<Knot> all = hard;
  all.push_back(Knot{s0_, -1});
  all.push_back(Knot{s1_, -1});
  for (double value : soft) {
    if (value > s0_ && value < s1_) {
      all.push_back(Knot{value, -1});
    }
  }
  // By s; at equal s the kink first, so that it is the one kept.
  std::sort(all.begin(), all.end(), [](const Knot& a, const Knot& b) {
    return a.s != b.s ? a.s < b.s : a.kink_geometry > b.kink_geometry;
  });
  std::vector<Knot> out;
  for (const Knot& knot : all) {
    if (!out.empty() && knot.s < out.back().s + kMinStep) {
      // Too close to the previous knot: a kink replaces a soft knot (s0 stays s0, s1 stays s1).
      if (knot.kink_geometry >= 0 && out.back().kink_geometry < 0 && out.back().s != s0_) {
        out.back() = knot;
      } else if (knot.s == s1_) {
        // The end is always a knot of its own.
        if (out.size() > 1) {
          out.back().s = s1_;
        } else {
          out.push_back(knot);
        }
      }
      continue;
    }
    out.push_back(knot);
  }
  return out;
}

SectionSamples sample_section(const SectionView& view, double tolerance, double max_segment) {
  SectionSamples out;
  out.borders = view.borders();
  RowStore rows(view);
  const std::vector<Knot> knots = view.knots();
  Refiner refiner{rows, out, tolerance, max_segment};
  // The first row: at a kink on s0 both limits (the previous section ends on the left limit).
  size_t previous = rows.add(knots.front().kink_geometry >= 0 ? view.frame_before(knots.front())
                                                              : view.frame(knots.front().s));
  rows.emit(previous, out);
  if (knots.front().kink_geometry >= 0) {
    previous = rows.add(knots.front().s);
    rows.emit(previous, out);
  }
  for (size_t k = 1; k < knots.size(); ++k) {
    const Knot& knot = knots[k];
    const bool kink = knot.kink_geometry >= 0;
    const size_t end = rows.add(kink ? view.frame_before(knot) : view.frame(knot.s));
    const size_t middle = rows.add(0.5 * (knots[k - 1].s + knot.s));
    refiner.refine(previous, middle, end, 0);
    previous = end;
    if (kink && k + 1 < knots.size()) {
      previous = rows.add(knot.s);  // the right limit, after the wedge
      rows.emit(previous, out);
    }
  }
  return out;
}

}  // namespace corsa::xodr::detail
