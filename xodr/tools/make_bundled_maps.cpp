// Writes Corsa's bundled maps: make_bundled_maps DIR  ->  DIR/motorway_2km.xodr,
// DIR/intersection_4way.xodr (the files committed in scenarios/maps/).

#include <exception>
#include <filesystem>
#include <iostream>

#include "bundled_maps.h"
#include "corsa/xodr/writer.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: corsa_make_bundled_maps OUTPUT_DIR\n";
    return 2;
  }
  try {
    const std::filesystem::path dir = argv[1];
    corsa::xodr::write_xodr(corsa::xodr::bundled::motorway(), dir / "motorway_2km.xodr");
    corsa::xodr::write_xodr(corsa::xodr::bundled::intersection(), dir / "intersection_4way.xodr");
  } catch (const std::exception& error) {
    std::cerr << error.what() << '\n';
    return 2;
  }
  return 0;
}
