// Two parts of the RGB camera on synthetic inputs, on one thread, so that their CPU time and
// their instruction counts can be compared between builds:
//   - the visibility filter (camera_denoise.cpp) of a 1280x720 frame at `default` quality
//     (steps 1, 2 and 4): sky in the top rows, a road plane and walls, noisy visibilities;
//   - the road's asphalt (patterns.cpp) over a road plane seen from 1.45 m with a 90 degree
//     lens: the lower half of a 1280x720 image, footprints as the camera computes them.
// Prints the median CPU time of RUNS runs of each and a checksum of the results (the same
// checksum: the same values). Instruction counts:
//   valgrind --tool=callgrind --toggle-collect='*filter_visibility*' corsa_bench_camera_parts 1
//   valgrind --tool=callgrind --toggle-collect='*sample_surface*' corsa_bench_camera_parts 1
// (the asphalt count includes building the noise tile once, about 0.34 G instructions).
//
// Usage: corsa_bench_camera_parts [RUNS]   (default 7)

#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <vector>

#include "camera_frame.h"
#include "material_defaults.h"
#include "surface.h"

namespace {

using namespace corsa::sensors;
using namespace corsa::sensors::detail;

constexpr int kWidth = 1280;
constexpr int kHeight = 720;

double cpu_ms() { return 1000.0 * static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

/// A deterministic value in [0, 1) for integer i (a 32-bit hash).
float unit(uint32_t i) {
  i ^= i >> 16;
  i *= 0x7feb352dU;
  i ^= i >> 15;
  i *= 0x846ca68bU;
  i ^= i >> 16;
  return static_cast<float>(i >> 8) / 16777216.0f;
}

void fill_geometry(std::vector<PixelGeometry>& geometry) {
  for (int row = 0; row < kHeight; ++row) {
    for (int col = 0; col < kWidth; ++col) {
      PixelGeometry& g = geometry[static_cast<size_t>(row) * kWidth + col];
      g = PixelGeometry{};
      if (row < 200) {
        g.distance = INFINITY;  // sky
        continue;
      }
      const bool wall = col < 400 || col > 900;
      g.surface_id = wall ? 7u + static_cast<uint32_t>(col / 97) : 3u;
      g.position[0] = static_cast<float>(col) * 0.05f;
      g.position[1] = static_cast<float>(row) * 0.05f;
      g.position[2] = wall ? static_cast<float>(col / 97) : 0.0f;
      g.normal[0] = wall ? 1.0f : 0.0f;
      g.normal[2] = wall ? 0.0f : 1.0f;
      g.distance = 5.0f + static_cast<float>(kHeight - row) * 0.1f;
    }
  }
}

double time_filter(int runs, double& checksum) {
  const size_t n = static_cast<size_t>(kWidth) * kHeight;
  std::vector<PixelGeometry> geometry(n);
  std::vector<PixelVisibility> visibility(n), scratch(n);
  fill_geometry(geometry);
  ShadingContext shading;
  shading.quality.sky_rays = 1;
  Pass p;
  p.width = kWidth;
  p.height = kHeight;
  p.geometry = &geometry;
  p.visibility = &visibility;
  p.visibility_scratch = &scratch;
  p.shading = &shading;
  std::vector<double> times;
  checksum = 0.0;
  for (int r = 0; r < runs; ++r) {
    for (size_t i = 0; i < n; ++i) {
      PixelVisibility& v = visibility[i];
      v.sun = unit(static_cast<uint32_t>(5 * i)) < 0.5f ? 0.0f : 1.0f;
      v.sky[0] = v.sky[1] = v.sky[2] = unit(static_cast<uint32_t>(5 * i + 1));
      v.lights = unit(static_cast<uint32_t>(5 * i + 2));
    }
    const double t0 = cpu_ms();
    filter_visibility(p);
    times.push_back(cpu_ms() - t0);
    for (const PixelVisibility& v : visibility) {
      checksum += v.sun + v.sky[0] + v.sky[1] + v.sky[2] + v.lights;
    }
  }
  return median(times);
}

double time_asphalt(int runs, double& checksum) {
  const Material m = default_material(SemanticClass::kRoad);
  const double fx = kWidth / 2.0;  // 90 degree lens
  const double height = 1.45;      // m, the camera above the road
  std::vector<double> times;
  checksum = 0.0;
  for (int r = 0; r < runs; ++r) {
    const double t0 = cpu_ms();
    double sum = 0.0;
    for (int row = 1; row <= kHeight / 2; ++row) {
      for (int col = 0; col < kWidth; ++col) {
        const double down = row / fx, side = (col - fx) / fx;  // ray (side, 1, -down)
        const double ahead = height / down;
        const double length = std::sqrt(side * side + 1.0 + down * down);
        TexturePoint tp;
        tp.position = {ahead * side, ahead, 0.0};
        tp.normal = {0.0, 0.0, 1.0};
        tp.footprint = ahead * length / fx / std::sqrt(std::max(down / length, 0.05));
        const SurfaceSample s = sample_surface(m, tp);
        sum += s.albedo.r + s.albedo.g + s.albedo.b + s.roughness;
      }
    }
    times.push_back(cpu_ms() - t0);
    checksum = sum;
  }
  return median(times);
}

}  // namespace

int main(int argc, char** argv) {
  const int runs = argc > 1 ? std::max(1, std::atoi(argv[1])) : 7;
  const tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
  double filter_sum = 0.0, asphalt_sum = 0.0;
  const double filter_ms = time_filter(runs, filter_sum);
  const double asphalt_ms = time_asphalt(runs, asphalt_sum);
  std::printf("visibility filter, 1280x720 at default, one thread: %.1f ms CPU (checksum %.9g)\n",
              filter_ms, filter_sum);
  std::printf("asphalt over a road plane, %d pixels: %.1f ms CPU (checksum %.17g)\n",
              kWidth * kHeight / 2, asphalt_ms, asphalt_sum);
  return 0;
}
