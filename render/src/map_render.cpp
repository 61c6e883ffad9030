// render_map: the road mesh rasterised from above at 2-3x the final resolution (so that shared
// triangle edges leave no seams), road marks drawn at least a pixel wide, then averaged down
// (anti-aliasing) and the overlays drawn at full resolution.

#include "corsa/render/map_render.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "corsa/core/strings.h"
#include "corsa/xodr/map.h"
#include "corsa/xodr/palette.h"
#include "corsa/xodr/road_marks.h"
#include "corsa/xodr/road_mesh.h"
#include "overlay.h"

namespace corsa::render {
using namespace corsa::xodr;
namespace {

const cv::Scalar kBackground(226, 234, 232);  // BGR: a pale grey-green ground
/// Junction surfaces are blended towards this (BGR: a slate blue) so that junctions stand out.
const cv::Scalar kJunctionTint(150, 110, 80);
constexpr double kJunctionTintWeight = 0.3;
/// Mesh tolerance in final pixels: well under a pixel, so curves look smooth.
constexpr double kTolerancePixels = 0.3;
/// Smallest side (pixels) of a picture drawn at a given scale: room for the overlays.
constexpr int kMinScaledSide = 192;
/// Sub-pixel bits of the rasteriser's coordinates.
constexpr int kShift = 4;

struct Bounds {
  double x0 = std::numeric_limits<double>::max();
  double y0 = std::numeric_limits<double>::max();
  double x1 = std::numeric_limits<double>::lowest();
  double y1 = std::numeric_limits<double>::lowest();

  void add(const Vec3& p) {
    x0 = std::min(x0, p.x);
    y0 = std::min(y0, p.y);
    x1 = std::max(x1, p.x);
    y1 = std::max(y1, p.y);
  }
  bool empty() const { return x0 > x1; }
};

Bounds mesh_bounds(const RoadMesh& mesh) {
  Bounds bounds;
  for (const Vec3& p : mesh.vertices) {
    bounds.add(p);
  }
  if (bounds.empty()) {
    bounds = Bounds{-50.0, -50.0, 50.0, 50.0};  // nothing to draw: an empty 100 m square
  }
  return bounds;
}

/// Picture size, scale and placement (the map centred), with the margin in pixels.
MapPicture choose_frame(const Bounds& b, const RenderOptions& options, const std::string& file,
                        int& margin) {
  const double w = std::max(b.x1 - b.x0, 1.0);
  const double h = std::max(b.y1 - b.y0, 1.0);
  MapPicture frame;
  if (options.scale > 0.0) {
    margin = 32;
    frame.scale = options.scale;
    const double width = std::ceil(w / frame.scale) + 2.0 * margin;
    const double height = std::ceil(h / frame.scale) + 2.0 * margin;
    if (width > kMaxPictureSide || height > kMaxPictureSide) {
      throw InputError(
          make_error(file, 0,
                     "at " + corsa::format_double(options.scale) +
                         " m per pixel the picture would be " + corsa::format_fixed(width, 0) +
                         " x " + corsa::format_fixed(height, 0) + " pixels; the most is " +
                         std::to_string(kMaxPictureSide) + " a side (use a larger --scale)"));
    }
    frame.width = std::max(kMinScaledSide, static_cast<int>(width));
    frame.height = std::max(kMinScaledSide, static_cast<int>(height));
  } else {
    const int size = options.size;
    margin = std::max(16, size / 40);
    frame.scale = std::max(w, h) / (size - 2 * margin);
    // A long thin map still gets room for the scale bar and the north arrow.
    const int shorter = std::max(
        size / 4, static_cast<int>(std::lround(std::min(w, h) / frame.scale)) + 2 * margin);
    frame.width = w >= h ? size : std::min(size, shorter);
    frame.height = w >= h ? std::min(size, shorter) : size;
  }
  frame.left = 0.5 * (b.x0 + b.x1) - 0.5 * frame.width * frame.scale;
  frame.top = 0.5 * (b.y0 + b.y1) + 0.5 * frame.height * frame.scale;
  return frame;
}

cv::Scalar bgr_of(Rgb c) { return cv::Scalar(c.b, c.g, c.r); }

cv::Scalar lane_color(const TriangleInfo& info) {
  const cv::Scalar base = bgr_of(lane_type_color(info.lane_type));
  if (!info.in_junction || !is_drivable(info.lane_type)) {
    return base;  // only the junction's carriageway is tinted; sidewalks stay sidewalks
  }
  return base * (1.0 - kJunctionTintWeight) + kJunctionTint * kJunctionTintWeight;
}

/// Draws on the supersampled canvas, map coordinates in.
class Canvas {
 public:
  Canvas(const MapPicture& frame, int factor)
      : frame_(frame),
        factor_(factor),
        image_(frame.height * factor, frame.width * factor, CV_8UC3, kBackground) {}

  cv::Point point(const Vec3& p) const {
    const double unit = (1 << kShift) * factor_;
    return cv::Point(static_cast<int>(std::lround(frame_.column_of(p.x) * unit)),
                     static_cast<int>(std::lround(frame_.row_of(p.y) * unit)));
  }

  void triangle(const Vec3& a, const Vec3& b, const Vec3& c, const cv::Scalar& color) {
    const cv::Point points[] = {point(a), point(b), point(c)};
    cv::fillConvexPoly(image_, points, 3, color, cv::LINE_8, kShift);
  }

  /// A road mark: its own strip when it is at least two canvas pixels wide, else a line of at
  /// least most of a final pixel, so that thin marks on a large map still show.
  void mark(const MarkLine& line) {
    const cv::Scalar color = bgr_of(mark_color_rgb(line.color));
    const double width_px = line.width / frame_.scale * factor_;
    if (width_px >= 2.0) {
      for (size_t k = 1; k < line.center.size(); ++k) {
        const cv::Point quad[] = {point(line.left[k - 1]), point(line.left[k]),
                                  point(line.right[k]), point(line.right[k - 1])};
        cv::fillConvexPoly(image_, quad, 4, color, cv::LINE_8, kShift);
      }
      return;
    }
    std::vector<cv::Point> points;
    points.reserve(line.center.size());
    for (const Vec3& p : line.center) {
      points.push_back(point(p));
    }
    const int thickness = std::max(1, static_cast<int>(std::lround(0.8 * factor_)));
    cv::polylines(image_, points, false, color, thickness, cv::LINE_8, kShift);
  }

  /// The canvas averaged down to the final size.
  cv::Mat finish() const {
    if (factor_ == 1) {
      return image_;
    }
    cv::Mat out;
    cv::resize(image_, out, cv::Size(frame_.width, frame_.height), 0, 0, cv::INTER_AREA);
    return out;
  }

 private:
  const MapPicture& frame_;
  int factor_ = 1;
  cv::Mat image_;
};

/// Lane surfaces in three passes so that what matters lies on top: other lane types first
/// (sidewalks, shoulders, ...), then driving lanes, then the driving lanes of junctions.
void draw_lanes(Canvas& canvas, const RoadMesh& mesh) {
  for (int pass = 0; pass < 3; ++pass) {
    for (size_t i = 0; i < mesh.triangles.size(); ++i) {
      const TriangleInfo& info = mesh.info[i];
      if (info.kind != SurfaceKind::kLane) {
        continue;
      }
      const int wanted = !is_drivable(info.lane_type) ? 0 : info.in_junction ? 2 : 1;
      if (wanted != pass || (info.in_junction && info.lane_type == LaneType::kNone)) {
        continue;  // lanes of type none inside junctions are spacers between connecting roads
      }
      const auto& t = mesh.triangles[i];
      const Vec3& a = mesh.vertices[t[0]];
      const Vec3& b = mesh.vertices[t[1]];
      const Vec3& c = mesh.vertices[t[2]];
      const double area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
      if (std::abs(area) < 1e-9) {
        continue;  // vertical (curb faces) or degenerate: nothing to see from above
      }
      canvas.triangle(a, b, c, lane_color(info));
    }
  }
}

}  // namespace

MapPicture render_map(const Map& map, const RenderOptions& options,
                      corsa::Diagnostics& diagnostics) {
  if (options.scale < 0.0 || !std::isfinite(options.scale)) {
    throw std::invalid_argument("render scale must be a positive number of metres per pixel");
  }
  if (options.scale == 0.0 && (options.size < kMinPictureSide || options.size > kMaxPictureSide)) {
    throw std::invalid_argument("render size must be between " + std::to_string(kMinPictureSide) +
                                " and " + std::to_string(kMaxPictureSide) + " pixels");
  }
  // A coarse mesh for the extent, then the real one at a fraction of a pixel.
  MeshOptions coarse;
  coarse.tolerance = 0.5;
  coarse.road_marks = false;
  corsa::Diagnostics ignored;
  int margin = 0;
  MapPicture picture = choose_frame(mesh_bounds(build_road_mesh(map, coarse, ignored)), options,
                                    map.data().source_file, margin);
  MeshOptions fine;
  fine.tolerance = std::clamp(kTolerancePixels * picture.scale, 0.005, 2.0);
  fine.road_marks = false;
  const RoadMesh mesh = build_road_mesh(map, fine, diagnostics);
  const std::vector<MarkLine> marks = build_road_marks(map, fine, diagnostics);

  // Supersampling: 3x for small pictures, 2x up to 4096 px, none beyond (memory).
  const int longer = std::max(picture.width, picture.height);
  const int factor = longer <= 1024 ? 3 : longer <= 4096 ? 2 : 1;
  Canvas canvas(picture, factor);
  draw_lanes(canvas, mesh);
  for (const MarkLine& line : marks) {
    canvas.mark(line);
  }
  cv::Mat bgr = canvas.finish();
  if (options.road_ids) {
    detail::draw_road_ids(bgr, map, picture);
  }
  detail::draw_scale_bar(bgr, picture.scale, margin);
  detail::draw_north_arrow(bgr, margin);

  cv::Mat rgb;
  cv::cvtColor(bgr, rgb, cv::COLOR_BGR2RGB);
  picture.rgb.assign(rgb.data, rgb.data + rgb.total() * rgb.elemSize());
  return picture;
}

}  // namespace corsa::render
