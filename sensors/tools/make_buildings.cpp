// corsa_make_buildings: writes the bundled building models of scenarios/models/ (a street of
// extruded footprints as ASCII FBX, glTF binary and OBJ) so that the model import path runs on real
// files. Usage: corsa_make_buildings OUTPUT_DIR [SEED]
//
// The models are in local metres (x east, y north, z up; the GLB y-up as glTF requires) around an
// anchor given in scenarios/models/README.md; sensors::load_model places them with a
// ModelPlacement (model CRS EPSG:4326 + anchor).

#include <cstdlib>
#include <filesystem>
#include <iostream>

#include "corsa/core/diagnostic.h"
#include "corsa/sensors/buildings.h"
#include "corsa/sensors/model_io.h"

int main(int argc, char** argv) {
  using namespace corsa::sensors;
  if (argc < 2) {
    std::cerr << "usage: corsa_make_buildings OUTPUT_DIR [SEED]\n";
    return 2;
  }
  const std::filesystem::path out = argv[1];
  const uint64_t seed = argc > 2 ? std::strtoull(argv[2], nullptr, 10) : 2024;
  try {
    std::filesystem::create_directories(out);
    std::vector<StaticMesh> meshes;
    for (const Footprint& f : street_district(300.0, 12.0, seed)) {
      meshes.push_back(extrude_footprint(f));
    }
    write_model(meshes, out / "street_district.fbx", "fbxa");
    write_model(meshes, out / "street_district.glb", "glb2", true);
    write_model(meshes, out / "street_district.obj", "obj");
    std::cout << "wrote " << meshes.size() << " buildings to " << out.string() << "\n";
  } catch (const corsa::InputError& error) {
    std::cerr << error.what() << "\n";
    return 2;
  }
  return 0;
}
