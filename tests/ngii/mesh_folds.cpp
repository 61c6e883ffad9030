#include "mesh_folds.h"

#include <cstdio>
#include <cstdlib>

#include "corsa/core/diagnostic.h"
#include "corsa/xodr/road_mesh.h"

namespace corsa::test {

size_t folded_roads(const xodr::Map& map) {
  xodr::MeshOptions options;
  options.tolerance = kFoldTolerance;
  corsa::Diagnostics diagnostics;
  (void)xodr::build_road_mesh(map, options, diagnostics);
  size_t folds = 0;
  for (const auto& d : diagnostics.all()) {
    if (d.message.find("folds over itself") == std::string::npos) {
      continue;
    }
    ++folds;
    if (std::getenv("CORSA_MEASURE_LIST") != nullptr) {
      std::fprintf(stderr, "fold: %s\n", d.message.c_str());
    }
  }
  return folds;
}

}  // namespace corsa::test
