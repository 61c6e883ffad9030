// The band query of the packed point grid (state/packed_point_grid.h) handed out in runs
// (visit_band, which the corridors of generated traffic read without a list): the same ids in
// the same order as the list query_band appends.

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <vector>

#include "corsa/core/random.h"
#include "state/packed_point_grid.h"

TEST_CASE("The band visit hands out what the band query lists, in its order, in runs",
          "[engine][traffic]") {
  corsa::RandomStream random(41);
  corsa::engine::detail::PackedPointGrid grid(8.0);
  for (int layout = 0; layout < 4; ++layout) {
    grid.clear();
    // Dense and sparse layouts; one pile of points in a single cell, more than a run holds (128);
    // with points nowhere (NaN) in the overflow list in two of them.
    const uint32_t count = layout % 2 == 0 ? 2000 : 120;
    for (uint32_t i = 0; i < count; ++i) {
      const bool pile = i % 4 == 0;
      grid.add(pile ? random.uniform(0.0, 5.0) : random.uniform(-300.0, 300.0),
               pile ? random.uniform(-2.0, 2.0) : random.uniform(-200.0, 200.0), i);
    }
    if (layout >= 2) {
      grid.add(std::nan(""), 1.0, count);
      grid.add(2.0, std::nan(""), count + 1);
    }
    grid.finish();
    size_t visited = 0, most_runs = 0;
    for (int q = 0; q < 150; ++q) {
      const bool at_pile = q % 3 == 0;
      const double x = at_pile ? -1.0 : random.uniform(-320.0, 320.0);
      const double y = at_pile ? 0.0 : random.uniform(-220.0, 220.0);
      // The band at the pile takes all of it (h = 0: x from -3 to 9, y from -3 to 3).
      const double h = at_pile ? 0.0 : random.uniform(-3.2, 3.2), c = std::cos(h), s = std::sin(h);
      const double along_min = at_pile ? -2.0 : random.uniform(-10.0, 0.0);
      const double along_max = at_pile ? 10.0 : random.uniform(0.0, 60.0);
      const double half = at_pile ? 3.0 : random.uniform(0.5, 12.0);
      const double reach = std::abs(along_min) + along_max + half;
      std::vector<uint32_t> listed = {99999};  // appended to what the list held
      grid.query_band(x - reach, y - reach, x + reach, y + reach, x, y, c, s, along_min, along_max,
                      half, listed);
      std::vector<uint32_t> handed = {99999};
      size_t runs = 0;
      grid.visit_band(x - reach, y - reach, x + reach, y + reach, x, y, c, s, along_min, along_max,
                      half, [&](const uint32_t* ids, size_t n) {
                        CHECK(n > 0);  // no empty runs
                        CHECK(n <= 128);
                        handed.insert(handed.end(), ids, ids + n);
                        ++runs;
                      });
      CHECK(handed == listed);
      most_runs = std::max(most_runs, runs);
      visited += handed.size() - 1;
    }
    CHECK(visited > 150);  // the bands hold points: the comparisons are not of nothing
    // The piles of 500 points (dense layouts) go out in several runs.
    CHECK(most_runs >= (layout % 2 == 0 ? 4u : 1u));
  }
}
