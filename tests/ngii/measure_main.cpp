// corsa_ngii_measure AREA_DIR MAP.xodr: the figures of ngii_measure.h for one converted area
// (docs/ngii.md "Results"). Reads the raw layers and the written map; prints "name value" lines.

#include <cstdio>
#include <exception>

#include "ngii_measure.h"

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: corsa_ngii_measure AREA_DIR MAP.xodr\n");
    return 2;
  }
  try {
    corsa::Diagnostics diagnostics;
    const corsa::ngii::Layers layers = corsa::ngii::read_layers(argv[1], diagnostics);
    const corsa::xodr::Map map = corsa::xodr::Map::load(argv[2], diagnostics);
    std::fputs(corsa::test::format_figures(corsa::test::measure_ngii(layers, map)).c_str(), stdout);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  }
  return 0;
}
