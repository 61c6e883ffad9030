// The RGB camera's visibility filter (sensors/src/camera_denoise.cpp, a private stage): interior
// pixels are filtered four at a time, the others one by one, and both must give the same bits.

#include <catch2/catch.hpp>
#include <cstring>
#include <vector>

#include "camera_frame.h"

namespace corsa::sensors::detail {
namespace {

/// A frame of `width` x `height` pixels whose columns repeat every 4 pixels: every surface pixel
/// at the same point (so a neighbour's weight depends only on its normal), normals and
/// visibilities cycling with the column, one sky pixel in each period on odd rows.
struct PeriodicFrame {
  int width = 0;
  int height = 0;
  std::vector<PixelGeometry> geometry;
  std::vector<PixelVisibility> visibility;
  std::vector<PixelVisibility> scratch;
  ShadingContext shading;
  Pass pass;

  PeriodicFrame(int w, int h) : width(w), height(h) {
    const size_t n = static_cast<size_t>(w) * h;
    geometry.resize(n);
    visibility.resize(n);
    scratch.resize(n);
    const float normals[4][3] = {
        {0.0f, 0.0f, 1.0f}, {0.0f, 0.6f, 0.8f}, {0.8f, 0.0f, 0.6f}, {0.0f, -0.28f, 0.96f}};
    for (int row = 0; row < h; ++row) {
      for (int col = 0; col < w; ++col) {
        const int k = col % 4;
        PixelGeometry& g = geometry[static_cast<size_t>(row) * w + col];
        g.surface_id = row % 2 == 1 && k == 3 ? 0u : 5u;
        g.distance = g.surface_id == 0 ? std::numeric_limits<float>::infinity() : 7.5f;
        std::memcpy(g.normal, normals[k], sizeof g.normal);
        PixelVisibility& v = visibility[static_cast<size_t>(row) * w + col];
        v.sun = k % 2 == 0 ? 1.0f : 0.0f;
        v.sky[0] = 0.1f * static_cast<float>(k + row % 3);
        v.sky[1] = 0.3f + 0.05f * static_cast<float>(k);
        v.sky[2] = 0.9f - 0.2f * static_cast<float>(k);
        v.lights = k == 1 ? 0.25f : 0.75f;
      }
    }
    pass.width = w;
    pass.height = h;
    pass.geometry = &geometry;
    pass.visibility = &visibility;
    pass.visibility_scratch = &scratch;
    pass.shading = &shading;
  }

  const PixelVisibility& at(int row, int col) const {
    return visibility[static_cast<size_t>(row) * width + col];
  }
};

bool same_bits(const PixelVisibility& a, const PixelVisibility& b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

}  // namespace

TEST_CASE("the visibility filter gives a pixel the same bits in a group of four as alone",
          "[camera][filter]") {
  // 27 columns: at the filter's second step (2 pixels apart) columns 2-21 are filtered in
  // groups of four and 22-24 one by one; 18 and 22 see the same neighbourhood (period 4).
  PeriodicFrame frame(27, 9);
  frame.shading.quality.sky_rays = 0;  // steps 1 and 2
  filter_visibility(frame.pass);
  for (int row = 2; row < 7; ++row) {
    CAPTURE(row);
    CHECK(same_bits(frame.at(row, 18), frame.at(row, 22)));
    CHECK(same_bits(frame.at(row, 17), frame.at(row, 21)));
  }
  // The sky is never filtered.
  CHECK(frame.at(3, 19).sky[2] == Approx(0.9f - 0.2f * 3.0f));
}

TEST_CASE("the visibility filter averages a noisy visibility over one flat surface",
          "[camera][filter]") {
  PeriodicFrame frame(32, 16);
  for (size_t i = 0; i < frame.geometry.size(); ++i) {
    PixelGeometry& g = frame.geometry[i];
    g.surface_id = 5;
    g.distance = 7.5f;
    g.normal[0] = 0.0f;
    g.normal[1] = 0.0f;
    g.normal[2] = 1.0f;
    // A checkerboard of lit and shadowed sky rays.
    const int row = static_cast<int>(i) / frame.width;
    const int col = static_cast<int>(i) % frame.width;
    frame.visibility[i].sky[0] = (row + col) % 2 == 0 ? 1.0f : 0.0f;
  }
  frame.shading.quality.sky_rays = 1;  // steps 1, 2 and 4
  filter_visibility(frame.pass);
  for (int row = 4; row < 12; ++row) {
    for (int col = 4; col < 28; ++col) {
      CAPTURE(row, col);
      CHECK(frame.at(row, col).sky[0] == Approx(0.5f).margin(0.1f));
    }
  }
}

}  // namespace corsa::sensors::detail
