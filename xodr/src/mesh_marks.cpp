// Road marks of one lane section (OpenDRIVE 1.8 §11.8): each roadMark record becomes one or
// two painted lines along its lane's outer border, solid or cut into dashes, sampled on the
// section's rows plus the dash ends.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>

#include "corsa/core/strings.h"
#include "mesh_builder.h"

namespace corsa::xodr::detail {
namespace {

/// A lane narrower than this (m) carries no mark: its outer border lies on its neighbour's,
/// whose own mark is the one to see.
constexpr double kMinMarkedWidth = 1e-3;
/// Dashes and lines shorter than this (m) are left out.
constexpr double kMinMarkLength = 0.01;

/// Paint pattern of one line: `dash` metres painted then `gap` metres bare, from the record's
/// start; dash 0 is a continuous line.
struct Pattern {
  double dash = 0.0;
  double gap = 0.0;
};
constexpr Pattern kSolid{0.0, 0.0};
/// Keyword `broken`: 3 m of paint, 9 m of gap (the usual rural/motorway lane line; files that
/// need other lengths give them in <type>/<line>, which the model does not keep).
constexpr Pattern kBroken{3.0, 9.0};
/// Keyword `botts dots`: raised pavement markers, about 0.15 m across, every 1.2 m.
constexpr Pattern kBottsDots{0.15, 1.05};

struct Style {
  int lines = 0;  ///< 0: nothing painted
  std::array<Pattern, 2> patterns{};
  bool known = true;
};

Style style_of(const std::string& type_text) {
  const std::string type = corsa::to_lower(corsa::trim(type_text));
  const auto word = [](std::string_view w, Pattern& out) {
    if (w == "solid") {
      out = kSolid;
      return true;
    }
    if (w == "broken") {
      out = kBroken;
      return true;
    }
    return false;
  };
  Style style;
  if (type == "none" || type == "grass" || type == "curb" || type == "edge" || type.empty()) {
    return style;
  }
  if (type == "botts dots") {
    style.lines = 1;
    style.patterns[0] = kBottsDots;
    return style;
  }
  const auto words = corsa::split(type, ' ');
  if (words.size() == 1 && word(words[0], style.patterns[0])) {
    style.lines = 1;
    return style;
  }
  if (words.size() == 2 && word(words[0], style.patterns[0]) && word(words[1], style.patterns[1])) {
    style.lines = 2;
    return style;
  }
  style.known = false;  // custom, or a name the standard does not have
  return style;
}

/// One sample of a mark line: its s and the section row it is, if it is one.
struct MarkSample {
  double s = 0.0;
  size_t row = SIZE_MAX;
};

class MarkSampler {
 public:
  MarkSampler(const SectionView& view, const SectionSamples& samples)
      : view_(view), samples_(samples), t_(view.borders()) {}

  /// Frame and border ts of a sample: its row's, or evaluated.
  const double* at(const MarkSample& sample, RoadFrame& frame) {
    if (sample.row != SIZE_MAX) {
      frame = samples_.frames[sample.row];
      return samples_.row_t(sample.row);
    }
    frame = view_.frame(sample.s);
    view_.border_ts(sample.s, t_.data());
    return t_.data();
  }

  /// Samples of one dash: its ends and every row between them (both limits of a kink inside).
  /// An end on a kink takes the limit on the dash's side.
  std::vector<MarkSample> dash_samples(double d0, double d1) const {
    const auto& s = samples_.s;
    auto it = std::upper_bound(s.begin(), s.end(), d0);
    std::vector<MarkSample> out;
    const bool start_is_row = it != s.begin() && *(it - 1) == d0;
    out.push_back(
        MarkSample{d0, start_is_row ? static_cast<size_t>(it - s.begin()) - 1 : SIZE_MAX});
    for (; it != s.end() && *it < d1; ++it) {
      out.push_back(MarkSample{*it, static_cast<size_t>(it - s.begin())});
    }
    const bool end_is_row = it != s.end() && *it == d1;
    out.push_back(MarkSample{d1, end_is_row ? static_cast<size_t>(it - s.begin()) : SIZE_MAX});
    return out;
  }

 private:
  const SectionView& view_;
  const SectionSamples& samples_;
  std::vector<double> t_;
};

/// Where one record's marks go: the border, the lane (for its width and height) and the side.
struct MarkPlace {
  size_t border = 0;
  bool has_lane = false;  ///< false for the centre lane
  size_t lane = 0;        ///< span index
  bool left_side = true;  ///< the lane's outer border is its left one
  double outward = 1.0;   ///< +1: the second line of a double mark lies at larger t
};

struct LineSpec {
  MarkLine prototype;
  double offset = 0.0;  ///< of the line's middle from the border (m, along t)
  double lift = 0.0;
};

void emit_dash(const SectionView& view, MarkSampler& sampler, const MarkPlace& place,
               const LineSpec& spec, double d0, double d1, std::vector<MarkLine>& out) {
  MarkLine line = spec.prototype;
  const auto flush = [&]() {
    if (line.center.size() >= 2) {
      out.push_back(line);
    }
    line.center.clear();
    line.left.clear();
    line.right.clear();
    line.s.clear();
  };
  const double half = 0.5 * spec.prototype.width;
  for (const MarkSample& sample : sampler.dash_samples(d0, d1)) {
    const double s = sample.s;
    RoadFrame f;
    const double* t = sampler.at(sample, f);
    if (place.has_lane && std::abs(t[place.lane] - t[place.lane + 1]) < kMinMarkedWidth) {
      flush();
      continue;
    }
    const Vec3 middle_point = view.surface(f, t[place.border] + spec.offset);
    if (!line.s.empty() && s - line.s.back() < 2.0 * kJumpEpsilon &&
        std::hypot(middle_point.x - line.center.back().x, middle_point.y - line.center.back().y) >
            spec.prototype.width) {
      flush();  // the border jumps sideways here (a gap in the file): the line breaks too
    }
    const double z =
        spec.lift + (place.has_lane ? view.lane_height(place.lane, s, place.left_side) : 0.0);
    const double middle = t[place.border] + spec.offset;
    line.s.push_back(s);
    for (auto [points, tt] : {std::pair{&line.center, middle}, std::pair{&line.left, middle + half},
                              std::pair{&line.right, middle - half}}) {
      Vec3 p = view.surface(f, tt);
      p.z += z;
      points->push_back(p);
    }
  }
  flush();
}

void emit_record(const SectionView& view, MarkSampler& sampler, const MarkPlace& place,
                 const Style& style, const LineSpec& base, double a, double b,
                 std::vector<MarkLine>& out) {
  for (int l = 0; l < style.lines; ++l) {
    LineSpec spec = base;
    if (style.lines == 2) {
      // The first named line lies inside (centre lane: on the left), one line width from the
      // border, the second as far outside: lines `width` apart.
      spec.offset = (l == 0 ? -1.0 : 1.0) * place.outward * base.prototype.width;
    }
    const Pattern& pattern = style.patterns[static_cast<size_t>(l)];
    if (pattern.dash <= 0.0) {
      emit_dash(view, sampler, place, spec, a, b, out);
      continue;
    }
    for (double d0 = a; d0 < b - kMinMarkLength; d0 += pattern.dash + pattern.gap) {
      emit_dash(view, sampler, place, spec, d0, std::min(d0 + pattern.dash, b), out);
    }
  }
}

MarkPlace place_of(const SectionView& view, const Lane& lane) {
  MarkPlace place;
  size_t left_lanes = 0;
  for (size_t i = 0; i < view.lanes(); ++i) {
    left_lanes += view.lane(i).id > 0 ? 1 : 0;
    if (&view.lane(i) == &lane) {
      place.has_lane = true;
      place.lane = i;
      place.left_side = lane.id > 0;
      place.border = lane.id > 0 ? i : i + 1;
      place.outward = lane.id > 0 ? 1.0 : -1.0;
    }
  }
  if (!place.has_lane) {
    place.border = left_lanes;  // the centre lane: between the left and the right lanes
    place.outward = -1.0;       // double centre lines: first on the left (§11.8)
  }
  return place;
}

}  // namespace

void section_mark_lines(const SectionView& view, const SectionSamples& samples,
                        const MeshOptions& options, corsa::Diagnostics& diagnostics,
                        std::vector<MarkLine>& out) {
  MarkSampler sampler(view, samples);
  const std::string& file = view.map().data().source_file;
  for (const Lane& lane : view.section().lanes) {
    if (lane.road_marks.empty()) {
      continue;
    }
    const MarkPlace place = place_of(view, lane);
    for (size_t k = 0; k < lane.road_marks.size(); ++k) {
      const RoadMark& mark = lane.road_marks[k];
      const double a = std::clamp(view.section().s + mark.s_offset, view.s0(), view.s1());
      const double b =
          k + 1 < lane.road_marks.size()
              ? std::clamp(view.section().s + lane.road_marks[k + 1].s_offset, view.s0(), view.s1())
              : view.s1();
      const Style style = style_of(mark.type);
      if (!style.known) {
        diagnostics.add_once("road mark type " + mark.type,
                             corsa::make_warning(file, lane.line,
                                                 "road mark type '" + mark.type +
                                                     "' is not drawn in the road mesh"));
      }
      if (style.lines == 0 || b - a < kMinMarkLength) {
        continue;
      }
      LineSpec spec;
      spec.prototype.road_index = view.road_index();
      spec.prototype.lane_id = lane.id;
      spec.prototype.lane_type = lane.type;
      spec.prototype.in_junction = view.road().in_junction();
      spec.prototype.color = mark_color_from_name(mark.color);
      if (spec.prototype.color == MarkColor::kNone) {
        diagnostics.add_once(
            "road mark colour " + mark.color,
            corsa::make_warning(file, lane.line,
                                "road mark colour '" + mark.color + "' is not known; drawn white"));
        spec.prototype.color = MarkColor::kWhite;
      }
      spec.prototype.width = mark.width > 0.0 ? mark.width : 0.12;
      spec.lift = mark.height > 0.0 ? mark.height : options.mark_lift;
      emit_record(view, sampler, place, style, spec, a, b, out);
    }
  }
}

void mesh_mark_line(const MarkLine& line, MeshBuilder& builder) {
  TriangleInfo info;
  info.road_index = line.road_index;
  info.lane_id = line.lane_id;
  info.lane_type = line.lane_type;
  info.kind = SurfaceKind::kRoadMark;
  info.in_junction = line.in_junction;
  info.color = line.color;
  uint32_t left0 = builder.add_vertex(line.left[0]);
  uint32_t right0 = builder.add_vertex(line.right[0]);
  for (size_t k = 1; k < line.center.size(); ++k) {
    const uint32_t left1 = builder.add_vertex(line.left[k]);
    const uint32_t right1 = builder.add_vertex(line.right[k]);
    // Marks fold only where their lane does, which the lane surface already reports.
    builder.add_upward(right0, right1, left1, info, nullptr, -1.0);
    builder.add_upward(right0, left1, left0, info, nullptr, -1.0);
    left0 = left1;
    right0 = right1;
  }
}

}  // namespace corsa::xodr::detail

namespace corsa::xodr {

MarkColor mark_color_from_name(std::string_view name) {
  const std::string color = corsa::to_lower(corsa::trim(name));
  if (color == "standard" || color == "white") {
    return MarkColor::kWhite;
  }
  static constexpr std::pair<std::string_view, MarkColor> kColors[] = {
      {"yellow", MarkColor::kYellow}, {"blue", MarkColor::kBlue},
      {"green", MarkColor::kGreen},   {"red", MarkColor::kRed},
      {"orange", MarkColor::kOrange}, {"violet", MarkColor::kViolet},
      {"black", MarkColor::kBlack},
  };
  for (const auto& [text, value] : kColors) {
    if (color == text) {
      return value;
    }
  }
  return MarkColor::kNone;
}

}  // namespace corsa::xodr
