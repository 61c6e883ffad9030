#pragma once

// What is drawn over the map at the picture's final resolution: road ids, the scale bar, the
// north arrow. Private to corsa_render.

#include <opencv2/core.hpp>

#include "corsa/render/map_render.h"
#include "corsa/xodr/map.h"

namespace corsa::render::detail {

/// Each road's id at its reference line's middle (roads in junctions left out), dark text with
/// a light halo.
void draw_road_ids(cv::Mat& bgr, const xodr::Map& map, const MapPicture& frame);
/// A bar of a round length (1, 2 or 5 times a power of ten metres) at the bottom left, split in
/// four black and white quarters, with its length written above.
void draw_scale_bar(cv::Mat& bgr, double scale, int margin);
/// An arrow pointing to +y (north in the map frame) with an "N", at the top right.
void draw_north_arrow(cv::Mat& bgr, int margin);

}  // namespace corsa::render::detail
