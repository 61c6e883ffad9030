#include "overlay.h"

#include <cmath>
#include <opencv2/imgproc.hpp>
#include <string>

namespace corsa::render::detail {
using namespace corsa::xodr;
namespace {

const cv::Scalar kInk(40, 40, 40);
const cv::Scalar kPaper(250, 250, 250);

/// Text with a light halo so that it reads on any lane colour.
void halo_text(cv::Mat& bgr, const std::string& text, cv::Point at, double font_scale) {
  cv::putText(bgr, text, at, cv::FONT_HERSHEY_SIMPLEX, font_scale, kPaper, 3, cv::LINE_AA);
  cv::putText(bgr, text, at, cv::FONT_HERSHEY_SIMPLEX, font_scale, kInk, 1, cv::LINE_AA);
}

/// Largest 1, 2 or 5 x 10^k not above `limit`.
double round_length(double limit) {
  const double power = std::pow(10.0, std::floor(std::log10(limit)));
  for (double step : {5.0, 2.0, 1.0}) {
    if (step * power <= limit) {
      return step * power;
    }
  }
  return power;
}

std::string length_text(double metres) {
  if (metres >= 1000.0) {
    return std::to_string(static_cast<long>(std::lround(metres / 1000.0))) + " km";
  }
  if (metres >= 1.0) {
    return std::to_string(static_cast<long>(std::lround(metres))) + " m";
  }
  return std::to_string(static_cast<long>(std::lround(metres * 100.0))) + " cm";
}

double font_scale_for(const cv::Mat& bgr) {
  // About 12 px tall text on a 2048 px picture, never below 9 px.
  return std::max(0.35, std::min(bgr.cols, bgr.rows) / 2048.0 * 0.45);
}

}  // namespace

void draw_road_ids(cv::Mat& bgr, const Map& map, const MapPicture& frame) {
  const double font_scale = font_scale_for(bgr) * 0.9;
  for (size_t r = 0; r < map.road_count(); ++r) {
    const Road& road = map.road(r);
    if (road.in_junction()) {
      continue;
    }
    const RefPoint middle = map.reference(r, 0.5 * road.length);
    int baseline = 0;
    const cv::Size size =
        cv::getTextSize(road.id, cv::FONT_HERSHEY_SIMPLEX, font_scale, 1, &baseline);
    const cv::Point at(static_cast<int>(std::lround(frame.column_of(middle.x))) - size.width / 2,
                       static_cast<int>(std::lround(frame.row_of(middle.y))) + size.height / 2);
    halo_text(bgr, road.id, at, font_scale);
  }
}

void draw_scale_bar(cv::Mat& bgr, double scale, int margin) {
  const double font_scale = font_scale_for(bgr);
  const double target_px = std::max(60.0, bgr.cols * 0.18);
  const double metres = round_length(target_px * scale);
  const int length = static_cast<int>(std::lround(metres / scale));
  const int thickness = std::max(4, margin / 5);
  const int x0 = margin;
  const int y1 = bgr.rows - margin / 2;
  const int y0 = y1 - thickness;
  // Quarters, alternately dark and light, inside a dark frame.
  for (int q = 0; q < 4; ++q) {
    const int qa = x0 + length * q / 4;
    const int qb = x0 + length * (q + 1) / 4;
    cv::rectangle(bgr, cv::Point(qa, y0), cv::Point(qb, y1), q % 2 == 0 ? kInk : kPaper,
                  cv::FILLED);
  }
  cv::rectangle(bgr, cv::Point(x0, y0), cv::Point(x0 + length, y1), kInk, 1);
  halo_text(bgr, length_text(metres), cv::Point(x0, y0 - 4), font_scale);
}

void draw_north_arrow(cv::Mat& bgr, int margin) {
  const double font_scale = font_scale_for(bgr);
  const int height = std::max(24, margin * 2);
  const int cx = bgr.cols - margin - height / 4;
  const int tip = margin / 2 + static_cast<int>(std::lround(26 * font_scale));
  const cv::Point arrow[] = {cv::Point(cx, tip), cv::Point(cx + height / 4, tip + height),
                             cv::Point(cx, tip + height * 3 / 4),
                             cv::Point(cx - height / 4, tip + height)};
  cv::fillConvexPoly(bgr, arrow, 4, kPaper, cv::LINE_AA);
  const cv::Point right_half[] = {arrow[0], arrow[1], arrow[2]};
  cv::fillConvexPoly(bgr, right_half, 3, kInk, cv::LINE_AA);
  cv::polylines(bgr, std::vector<cv::Point>(arrow, arrow + 4), true, kInk, 1, cv::LINE_AA);
  int baseline = 0;
  const cv::Size size = cv::getTextSize("N", cv::FONT_HERSHEY_SIMPLEX, font_scale, 1, &baseline);
  halo_text(bgr, "N", cv::Point(cx - size.width / 2, tip - 4), font_scale);
}

}  // namespace corsa::render::detail
