// NGII conversion figures: per area, the time to read the layers (shapelib, CP949,
// PROJ), to convert them (corrections, grouping, fitting, junctions, marks, signals), to write
// the OpenDRIVE text, and the whole pipeline as `corsa convert ngii` runs it (read + convert +
// Map::build check + write to memory). Medians of several runs of process CPU time (the machine
// is shared and noisy; wall time of the whole pipeline is printed too). Targets: K-City under
// 1 s, Sangam under 2 s (whole pipeline).
//
//   corsa_bench_ngii [--runs N] [AREA_DIR ...]   (default: both areas in ../shared/data/ngii)

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <string>
#include <vector>

#include "bench_util.h"
#include "corsa/ngii/convert.h"
#include "corsa/xodr/map.h"
#include "corsa/xodr/writer.h"

namespace {

using corsa::bench::median;

using Clock = std::chrono::steady_clock;

/// Median CPU time (ms) of `runs` calls; the median wall time goes to `wall` when given. The
/// conversion is single-threaded, so CPU time is what it costs; wall time on the shared machine
/// also counts the other processes' turns.
template <typename F>
double median_ms(int runs, F&& body, double* wall = nullptr) {
  std::vector<double> cpu;
  std::vector<double> walls;
  for (int i = 0; i < runs; ++i) {
    const auto start = Clock::now();
    const double cpu_start = corsa::bench::process_cpu_ms();
    body();
    cpu.push_back(corsa::bench::process_cpu_ms() - cpu_start);
    walls.push_back(std::chrono::duration<double, std::milli>(Clock::now() - start).count());
  }
  if (wall != nullptr) {
    *wall = median(walls);
  }
  return median(cpu);
}

void bench_area(const std::filesystem::path& dir, int runs) {
  corsa::ngii::Layers layers;
  const double read = median_ms(runs, [&] {
    corsa::Diagnostics diagnostics;
    layers = corsa::ngii::read_layers(dir, diagnostics);
  });
  corsa::ngii::Conversion conversion;
  const double convert = median_ms(runs, [&] {
    corsa::Diagnostics diagnostics;
    conversion = corsa::ngii::convert(layers, {}, diagnostics);
  });
  const double check = median_ms(runs, [&] {
    corsa::Diagnostics diagnostics;
    corsa::xodr::Map::build(conversion.map, diagnostics);
  });
  size_t bytes = 0;
  const double write =
      median_ms(runs, [&] { bytes = corsa::xodr::write_xodr_text(conversion.map).size(); });
  double whole_wall = 0.0;
  const double whole = median_ms(
      runs,
      [&] {
        corsa::Diagnostics diagnostics;
        const auto l = corsa::ngii::read_layers(dir, diagnostics);
        const auto c = corsa::ngii::convert(l, {}, diagnostics);
        corsa::xodr::Map::build(c.map, diagnostics);
        bytes = corsa::xodr::write_xodr_text(c.map).size();
      },
      &whole_wall);
  const auto& s = conversion.summary;
  std::printf("%-22s %6zu %6zu %6zu %5zu %8.1f %8.1f %8.1f %8.1f %8.1f %8.1f %7.2f\n",
              dir.filename().c_str(), s.links_read, s.roads, s.lanes,
              s.junctions + s.direct_junctions, read, convert, check, write, whole, whole_wall,
              static_cast<double>(bytes) / 1e6);
}

}  // namespace

int main(int argc, char** argv) {
  int runs = 5;
  std::vector<std::filesystem::path> areas;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--runs" && i + 1 < argc) {
      runs = std::max(1, std::atoi(argv[++i]));
    } else {
      areas.emplace_back(arg);
    }
  }
  if (areas.empty()) {
    const std::filesystem::path root = std::filesystem::path(CORSA_SHARED_DIR) / "data" / "ngii";
    areas = {root / "kcity", root / "seoul_sangam_testbed"};
  }
  std::printf(
      "median of %d runs, CPU ms (whole = read + convert + Map::build + write; wall: "
      "the same in wall-clock ms)\n",
      runs);
  std::printf("%-22s %6s %6s %6s %5s %8s %8s %8s %8s %8s %8s %7s\n", "area", "links", "roads",
              "lanes", "junc", "read", "convert", "build", "write", "whole", "wall", "MB");
  for (const auto& area : areas) {
    bench_area(area, runs);
  }
  return 0;
}
