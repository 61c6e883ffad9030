// Road mesh figures: per map, the time to build the full mesh (lanes and road marks)
// at 0.1 m chord tolerance, its size, and the time to write it as binary PLY to memory; then the
// top-down picture of Town03 and Town04 at 2048 px. Medians of several runs (the machine is
// shared and noisy). Target: Town04's full mesh under 120 ms.
//
//   corsa_bench_xodr_mesh [--runs N] [MAP.xodr ...]    (default: every map in ../shared/data/xodr)

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "bench_util.h"
#include "corsa/render/map_render.h"
#include "corsa/xodr/map.h"
#include "corsa/xodr/mesh_io.h"
#include "corsa/xodr/road_mesh.h"

namespace {

using corsa::bench::median;

using Clock = std::chrono::steady_clock;

template <typename F>
double median_ms(int runs, F&& body) {
  std::vector<double> times;
  for (int i = 0; i < runs; ++i) {
    const auto start = Clock::now();
    body();
    times.push_back(std::chrono::duration<double, std::milli>(Clock::now() - start).count());
  }
  return median(times);
}

void bench_map(const std::filesystem::path& path, int runs) {
  corsa::Diagnostics diagnostics;
  const corsa::xodr::Map map = corsa::xodr::Map::load(path, diagnostics);
  corsa::xodr::RoadMesh mesh;
  const double full = median_ms(runs, [&] { mesh = corsa::xodr::build_road_mesh(map); });
  corsa::xodr::MeshOptions lanes_only;
  lanes_only.road_marks = false;
  const double lanes = median_ms(runs, [&] { corsa::xodr::build_road_mesh(map, lanes_only); });
  size_t marks = 0;
  for (const auto& info : mesh.info) {
    marks += info.kind == corsa::xodr::SurfaceKind::kRoadMark ? 1 : 0;
  }
  size_t bytes = 0;
  const double ply = median_ms(runs, [&] {
    bytes = corsa::xodr::mesh_to_ply(mesh, corsa::xodr::PlyEncoding::kBinary).size();
  });
  std::printf("%-52s %8zu %8zu %8zu %9.2f %9.2f %8.2f %8.1f\n", path.filename().c_str(),
              mesh.triangles.size(), marks, mesh.vertices.size(), full, lanes, ply,
              static_cast<double>(bytes) / 1e6);
}

void bench_render(const std::filesystem::path& path, int runs) {
  corsa::Diagnostics diagnostics;
  const corsa::xodr::Map map = corsa::xodr::Map::load(path, diagnostics);
  corsa::render::RenderOptions options;
  options.size = 2048;
  std::string png;
  const double draw = median_ms(runs, [&] {
    png = corsa::render::encode_png(corsa::render::render_map(map, options, diagnostics));
  });
  std::printf("render %-30s 2048 px: %8.1f ms (PNG %.2f MB)\n", path.filename().c_str(), draw,
              static_cast<double>(png.size()) / 1e6);
}

}  // namespace

int main(int argc, char** argv) {
  int runs = 7;
  std::vector<std::filesystem::path> maps;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--runs" && i + 1 < argc) {
      runs = std::max(1, std::atoi(argv[++i]));
    } else {
      maps.emplace_back(arg);
    }
  }
  const auto shared = std::filesystem::path(CORSA_SHARED_DIR) / "data" / "xodr";
  if (maps.empty()) {
    for (const auto& entry : std::filesystem::directory_iterator(shared)) {
      if (entry.path().extension() == ".xodr") {
        maps.push_back(entry.path());
      }
    }
    std::sort(maps.begin(), maps.end());
  }
  std::printf("road mesh at 0.1 m tolerance, median of %d runs (ms)\n", runs);
  std::printf("%-52s %8s %8s %8s %9s %9s %8s %8s\n", "map", "tris", "marks", "verts", "full",
              "lanes", "ply", "ply MB");
  for (const auto& path : maps) {
    bench_map(path, runs);
  }
  for (const char* name : {"Town03.xodr", "Town04.xodr"}) {
    bench_render(shared / name, std::max(1, runs / 2));
  }
  return 0;
}
