// OpenDRIVE library figures. Per map: parse time, Map::build time (checks, lane
// graph, spatial index), and the time to sample every lane centre every 0.5 m; on Town04,
// 100k random world -> lane queries. Medians of several runs (the machine is shared and noisy).
// Times are CPU time of this process (CLOCK_PROCESS_CPUTIME_ID), so that other jobs on the two
// cores inflate them less than wall time; --wall reports wall-clock time instead.
//
//   corsa_bench_xodr [--runs N] [--wall] [MAP.xodr ...]    (default: every map in
//   ../shared/data/xodr)

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <string>
#include <vector>

#include "bench_util.h"
#include "corsa/core/atomic_file.h"
#include "corsa/core/random.h"
#include "corsa/xodr/map.h"
#include "corsa/xodr/parser.h"

namespace {

using corsa::bench::median;

using corsa::xodr::Map;

bool g_wall = false;  // set once from the command line, before any measurement

double now_ms() {
  if (g_wall) {
    return std::chrono::duration<double, std::milli>(
               std::chrono::steady_clock::now().time_since_epoch())
        .count();
  }
  return corsa::bench::process_cpu_ms();
}

template <typename F>
double median_ms(int runs, F&& body) {
  std::vector<double> times;
  for (int i = 0; i < runs; ++i) {
    const double start = now_ms();
    body();
    times.push_back(now_ms() - start);
  }
  return median(times);
}

/// Samples every lane centre every 0.5 m (world poses); returns the number of samples.
size_t sample_lane_centres(const Map& map) {
  std::vector<corsa::xodr::LaneSpan> spans;
  size_t samples = 0;
  double checksum = 0.0;
  for (size_t road = 0; road < map.road_count(); ++road) {
    const auto& r = map.road(road);
    for (size_t k = 0; k < r.lane_sections.size(); ++k) {
      const double s0 = r.lane_sections[k].s;
      const double s1 = map.section_end(road, k);
      for (double s = s0; s <= s1; s += 0.5) {
        map.lane_spans_in_section(road, k, s, spans);
        for (const auto& span : spans) {
          checksum += map.world_pose(road, s, span.t_center()).x;
          ++samples;
        }
      }
    }
  }
  return checksum == 0.123456789 ? 0 : samples;  // keep the work observable
}

void bench_map(const std::filesystem::path& path, int runs) {
  const std::string text = corsa::read_file(path);
  corsa::Diagnostics diagnostics;
  const double parse = median_ms(runs, [&] {
    corsa::Diagnostics d;
    (void)corsa::xodr::parse_xodr_text(text, path.string(), d);
  });
  const corsa::xodr::MapData data = corsa::xodr::parse_xodr_text(text, path.string(), diagnostics);
  const double build = median_ms(runs, [&] {
    corsa::Diagnostics d;
    (void)Map::build(data, d);
  });
  const Map map = Map::build(data, diagnostics);
  size_t samples = 0;
  const double sample =
      median_ms(std::max(3, runs / 3), [&] { samples = sample_lane_centres(map); });
  std::printf("%-55s %8.2f %8.2f %9.2f %9zu\n", path.filename().c_str(), parse, build, sample,
              samples);
}

void bench_locate(const std::filesystem::path& path, int runs) {
  corsa::Diagnostics diagnostics;
  const Map map = Map::load(path, diagnostics);
  // Points on lanes (random road, s, lane, t) plus 1 m of noise: what a simulation asks.
  corsa::RandomStream random(42);
  std::vector<std::pair<double, double>> points;
  std::vector<corsa::xodr::LaneSpan> spans;
  while (points.size() < 100000) {
    const size_t road = static_cast<size_t>(random.uniform_int(0, map.road_count() - 1));
    const double s = random.uniform(0.0, map.road(road).length);
    map.lane_spans(road, s, spans);
    if (spans.empty()) {
      continue;
    }
    const auto& span = spans[static_cast<size_t>(random.uniform_int(0, spans.size() - 1))];
    const auto pose = map.world_pose(road, s, span.t_center());
    points.emplace_back(pose.x + random.uniform(-1.0, 1.0), pose.y + random.uniform(-1.0, 1.0));
  }
  size_t found = 0;
  const double ms = median_ms(runs, [&] {
    found = 0;
    for (const auto& [x, y] : points) {
      found += map.locate(x, y).has_value() ? 1 : 0;
    }
  });
  std::printf("\n%s: 100000 world->lane queries near lanes: %.1f ms, %.0f queries/s (%zu found)\n",
              path.filename().c_str(), ms, 100000.0 / (ms / 1000.0), found);
  // Uniformly over the map's bounding box (many points off-road, the slower case).
  const auto& h = map.data().header;
  std::vector<std::pair<double, double>> uniform;
  for (int i = 0; i < 100000; ++i) {
    uniform.emplace_back(random.uniform(h.west, h.east), random.uniform(h.south, h.north));
  }
  const double ms_uniform = median_ms(runs, [&] {
    found = 0;
    for (const auto& [x, y] : uniform) {
      found += map.locate(x, y).has_value() ? 1 : 0;
    }
  });
  std::printf(
      "%s: 100000 world->lane queries uniform in the bounds: %.1f ms, %.0f queries/s "
      "(%zu within 5 m of a lane)\n",
      path.filename().c_str(), ms_uniform, 100000.0 / (ms_uniform / 1000.0), found);
}

}  // namespace

int main(int argc, char** argv) {
  int runs = 15;
  std::vector<std::filesystem::path> maps;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--wall") {
      g_wall = true;
    } else if (arg == "--runs" && i + 1 < argc) {
      runs = std::max(1, std::atoi(argv[++i]));
    } else {
      maps.emplace_back(arg);
    }
  }
  const std::filesystem::path shared = std::filesystem::path(CORSA_SHARED_DIR) / "data" / "xodr";
  if (maps.empty()) {
    for (const auto& entry : std::filesystem::directory_iterator(shared)) {
      if (entry.path().extension() == ".xodr") {
        maps.push_back(entry.path());
      }
    }
    std::sort(maps.begin(), maps.end());
  }
  std::printf("median of %d runs, milliseconds of %s time\n%-55s %8s %8s %9s %9s\n", runs,
              g_wall ? "wall" : "CPU", "map", "parse", "build", "sample.5m", "samples");
  for (const auto& path : maps) {
    bench_map(path, runs);
  }
  bench_locate(shared / "Town04.xodr", std::max(3, runs / 3));
  return 0;
}
