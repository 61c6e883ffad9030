// The top-down map picture: its size and scale, the colours at known places, marks, PNG.

#include <catch2/catch.hpp>
#include <cmath>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "corsa/core/diagnostic.h"
#include "corsa/render/map_render.h"
#include "corsa/xodr/palette.h"
#include "mesh_test_util.h"

using namespace corsa::xodr;
using namespace corsa::render;
using namespace corsa::xodr::mesh_test;

namespace {

Rgb pixel(const MapPicture& picture, double x, double y) {
  const int col = static_cast<int>(std::floor(picture.column_of(x)));
  const int row = static_cast<int>(std::floor(picture.row_of(y)));
  REQUIRE(col >= 0);
  REQUIRE(row >= 0);
  REQUIRE(col < picture.width);
  REQUIRE(row < picture.height);
  const size_t at =
      (static_cast<size_t>(row) * static_cast<size_t>(picture.width) + static_cast<size_t>(col)) *
      3;
  return Rgb{picture.rgb[at], picture.rgb[at + 1], picture.rgb[at + 2]};
}

bool near(Rgb a, Rgb b, int tolerance) {
  return std::abs(a.r - b.r) <= tolerance && std::abs(a.g - b.g) <= tolerance &&
         std::abs(a.b - b.b) <= tolerance;
}

std::string text(Rgb c) {
  return std::to_string(c.r) + "," + std::to_string(c.g) + "," + std::to_string(c.b);
}

MapPicture render(const Map& map, RenderOptions options) {
  corsa::Diagnostics diagnostics;
  return render_map(map, options, diagnostics);
}

}  // namespace

TEST_CASE("the picture has the requested size on its longer side", "[xodr][render]") {
  const Map map = load(shared_map("borregasave.xodr"));  // wider than tall
  RenderOptions options;
  options.size = 300;
  const MapPicture picture = render(map, options);
  CHECK(picture.width == 300);
  CHECK(picture.height < 300);
  CHECK(picture.height > 100);
  CHECK(picture.rgb.size() == static_cast<size_t>(picture.width * picture.height * 3));
  options.size = 64;
  CHECK(render(map, options).width == 64);
}

TEST_CASE("lanes, junctions and the ground have their colours where they are", "[xodr][render]") {
  const Map map = load(shared_map("Ex_LHT-Complex-X-Junction.xodr"));
  RenderOptions options;
  options.size = 400;
  const MapPicture picture = render(map, options);
  size_t roads = 0;
  size_t junctions = 0;
  for (size_t r = 0; r < map.road_count(); ++r) {
    const Road& road = map.road(r);
    // The middle of the first driving lane at the middle of the road.
    const double s = 0.5 * road.length;
    std::vector<LaneSpan> spans;
    map.lane_spans(r, s, spans);
    for (const LaneSpan& span : spans) {
      const Lane* lane = map.lane(LaneRef{static_cast<uint32_t>(r),
                                          static_cast<uint32_t>(map.section_index(r, s)), span.id});
      if (lane == nullptr || lane->type != LaneType::kDriving || span.width() < 3.0) {
        continue;
      }
      const WorldPose p = map.world_pose(r, s, span.t_center() + 0.6);  // off the lane's marks
      const Rgb c = pixel(picture, p.x, p.y);
      INFO("road " << road.id << " lane " << span.id << " colour " << text(c));
      if (road.in_junction()) {
        // Tinted: bluer than the plain driving grey (connecting lanes overlap each other).
        CHECK(c.b > c.r + 10);
        ++junctions;
      } else {
        CHECK(near(c, lane_type_color(LaneType::kDriving), 6));
        ++roads;
      }
      break;
    }
  }
  CHECK(roads == 4);
  CHECK(junctions > 4);
  // A corner of the map between the arms is bare ground.
  const Rgb ground = pixel(picture, picture.left + 0.3 * picture.width * picture.scale,
                           picture.top - 0.3 * picture.height * picture.scale);
  CHECK(near(ground, Rgb{232, 234, 226}, 4));
}

TEST_CASE("road marks are painted in their colour, at least a pixel wide", "[xodr][render]") {
  const Map map = build({make_road("1", {geometry(0, 0, 0, 0, 60.0)},
                                   {{0, LaneType::kNone, 0.0, {}, {}, {mark("solid", "yellow")}},
                                    {1, LaneType::kDriving, 3.5},
                                    {-1, LaneType::kDriving, 3.5, {}, {}, {mark("solid")}}})});
  RenderOptions options;
  options.scale = 0.05;  // a 0.12 m line is 2.4 pixels
  const MapPicture fine = render(map, options);
  CHECK(fine.scale == 0.05);
  CHECK(near(pixel(fine, 30.0, 0.0), mark_color_rgb(MarkColor::kYellow), 12));
  CHECK(near(pixel(fine, 30.0, -3.5), mark_color_rgb(MarkColor::kWhite), 12));
  CHECK(near(pixel(fine, 30.0, -1.7), lane_type_color(LaneType::kDriving), 4));
  // Far out, 0.5 m a pixel: the 0.12 m line still shows, as a blend brighter than asphalt.
  options.scale = 0.5;
  const MapPicture coarse = render(map, options);
  const Rgb line = pixel(coarse, 30.0, -3.5);
  INFO(text(line));
  CHECK(line.r > lane_type_color(LaneType::kDriving).r + 30);
}

TEST_CASE("a picture too large for its scale is refused with the map's name", "[xodr][render]") {
  const Map map = load(shared_map("Town03.xodr"));
  RenderOptions options;
  options.scale = 0.01;
  try {
    render(map, options);
    FAIL("no error");
  } catch (const corsa::InputError& error) {
    CHECK_THAT(error.diagnostic().file, Catch::Contains("Town03.xodr"));
    CHECK_THAT(error.diagnostic().message, Catch::Contains("16384"));
  }
  options.scale = 0.0;
  options.size = 10;
  CHECK_THROWS_AS(render(map, options), std::invalid_argument);
  options.scale = -1.0;
  CHECK_THROWS_AS(render(map, options), std::invalid_argument);
}

TEST_CASE("the PNG decodes to the same picture, byte for byte every time", "[xodr][render]") {
  const Map map = load(shared_map("fabriksgatan.xodr"));
  RenderOptions options;
  options.size = 256;
  options.road_ids = true;
  const MapPicture picture = render(map, options);
  const std::string png = encode_png(picture);
  CHECK(png.substr(1, 3) == "PNG");
  const std::vector<uchar> bytes(png.begin(), png.end());
  const cv::Mat decoded = cv::imdecode(bytes, cv::IMREAD_COLOR);
  REQUIRE(decoded.cols == picture.width);
  REQUIRE(decoded.rows == picture.height);
  size_t differ = 0;
  for (int row = 0; row < decoded.rows; ++row) {
    for (int col = 0; col < decoded.cols; ++col) {
      const cv::Vec3b bgr = decoded.at<cv::Vec3b>(row, col);
      const size_t at = (static_cast<size_t>(row) * static_cast<size_t>(picture.width) +
                         static_cast<size_t>(col)) *
                        3;
      differ += (bgr[2] != picture.rgb[at] || bgr[1] != picture.rgb[at + 1] ||
                 bgr[0] != picture.rgb[at + 2])
                    ? 1
                    : 0;
    }
  }
  CHECK(differ == 0);
  CHECK(encode_png(render(map, options)) == png);
}
