#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>

#include "corsa/core/diagnostic.h"
#include "corsa/sensors/buildings.h"
#include "corsa/sensors/georeference.h"
#include "corsa/sensors/model_io.h"
#include "corsa/sensors/rig.h"
#include "corsa/sensors/scene.h"
#include "corsa/sensors/texture_image.h"
#include "corsa/sensors/writers.h"
#include "temp_dir.h"

using namespace corsa::sensors;
namespace fs = std::filesystem;

namespace {

const fs::path kModels = fs::path(CORSA_SOURCE_DIR) / "scenarios" / "models";

Bounds bounds_of(const std::vector<StaticMesh>& meshes) {
  Bounds b;
  for (const auto& m : meshes) {
    for (const auto& v : m.vertices) {
      b.min = {std::min(b.min.x, v.x), std::min(b.min.y, v.y), std::min(b.min.z, v.z)};
      b.max = {std::max(b.max.x, v.x), std::max(b.max.y, v.y), std::max(b.max.z, v.z)};
    }
  }
  return b;
}

}  // namespace

TEST_CASE("an extruded footprint has outward walls and a roof", "[sensors][models]") {
  Footprint f;
  f.name = "L";
  f.height = 12.0;
  f.ring = {{0, 0}, {0, 10}, {5, 10}, {5, 5}, {10, 5}, {10, 0}};  // clockwise L shape
  const StaticMesh m = extrude_footprint(f);
  CHECK(m.triangles.size() == 6 * 2 + 4);  // two per wall, n - 2 for the roof
  double roof_area = 0.0;
  for (const auto& t : m.triangles) {
    const Vec3 a = m.vertices[t[0]], b = m.vertices[t[1]], c = m.vertices[t[2]];
    const Vec3 n = cross(b - a, c - a);
    const Vec3 centre = (a + b + c) * (1.0 / 3.0);
    if (a.z == 12.0 && b.z == 12.0 && c.z == 12.0) {
      CHECK(n.z > 0.0);
      roof_area += 0.5 * norm(n);
    } else {
      // Outward: moving along the normal leaves the footprint's bounding square or the notch.
      const Vec3 probe = centre + normalized(n) * 0.1;
      const bool outside = probe.x < 0 || probe.y < 0 || probe.x > 10 || probe.y > 10 ||
                           (probe.x > 5 && probe.y > 5);
      CHECK(outside);
    }
  }
  CHECK(roof_area == Approx(75.0));
  CHECK_THROWS_AS(extrude_footprint(Footprint{"bad", {{0, 0}, {1, 1}}, 3.0, 0.0, {}}),
                  std::invalid_argument);
}

TEST_CASE("the bundled FBX, GLB and OBJ building models load alike", "[sensors][models]") {
  const ModelPlacement here;  // already in local metres
  const auto fbx = load_model(kModels / "street_district.fbx", here);
  const auto glb = load_model(kModels / "street_district.glb", here);
  const auto obj = load_model(kModels / "street_district.obj", here);
  REQUIRE(fbx.size() == 26);
  CHECK(glb.size() == 26);
  CHECK(obj.size() == 26);
  const Bounds a = bounds_of(fbx), b = bounds_of(glb), c = bounds_of(obj);
  for (const Bounds* other : {&b, &c}) {
    CHECK(other->min.x == Approx(a.min.x).margin(1e-3));
    CHECK(other->max.y == Approx(a.max.y).margin(1e-3));
    CHECK(other->min.y == Approx(a.min.y).margin(1e-3));
    CHECK(other->max.z == Approx(a.max.z).margin(1e-3));
  }
  CHECK(a.min.z == Approx(0.0).margin(1e-6));  // z up after the glTF y-up conversion too
  CHECK(b.min.z == Approx(0.0).margin(1e-6));
  CHECK(a.max.x <= 300.0 + 1e-6);
  CHECK(a.min.y < -14.0);  // buildings on both sides of the street
  CHECK(a.max.y > 14.0);
  CHECK(fbx[0].classes == std::vector<SemanticClass>{SemanticClass::kBuilding});
  REQUIRE(fbx[0].color);
  Scene scene;
  for (auto& mesh : glb) {
    CHECK(scene.add_static_mesh(mesh) >= kStaticInstanceBase);
  }
  scene.commit();
  // Looking north from the middle of the street hits a building.
  const auto hit = scene.intersect({40.0, 0.0, 2.0}, {0.0, 1.0, 0.0}, 100.0);
  REQUIRE(hit);
  CHECK(hit->semantic == SemanticClass::kBuilding);
  CHECK(hit->normal.y == Approx(-1.0));
}

TEST_CASE("models are placed through PROJ from WGS84 into the map's CRS", "[sensors][models]") {
  // Seoul City Hall in UTM-K (EPSG:5179: origin 38N 127.5E, false easting 1e6, northing 2e6).
  const CrsTransform to_utmk("EPSG:4326", "EPSG:5179");
  CHECK(to_utmk.source_is_geographic());
  const Vec3 anchor_map = to_utmk.apply({126.978, 37.5665, 0.0});
  CHECK(anchor_map.x == Approx(953900.0).margin(300.0));
  CHECK(anchor_map.y == Approx(1952000.0).margin(300.0));

  ModelPlacement p;
  p.model_crs = "EPSG:4326";
  p.map_crs = "EPSG:5179";
  p.anchor = Vec3{126.978, 37.5665, 0.0};
  p.offset = {0.0, 0.0, 35.0};
  const auto placed = load_model(kModels / "street_district.glb", p);
  const auto local = load_model(kModels / "street_district.glb", ModelPlacement{});
  REQUIRE(placed.size() == local.size());
  // A vertex v metres east/north of the anchor lands where PROJ puts the geographic point
  // v metres east/north of it (to a few centimetres over 300 m).
  const Vec3 v = local[5].vertices[2];
  const double metres_per_deg_lat = 110950.0;  // at 37.6 degrees
  const double metres_per_deg_lon = 111320.0 * std::cos(37.5665 * M_PI / 180.0);
  const Vec3 expected =
      to_utmk.apply({126.978 + v.x / metres_per_deg_lon, 37.5665 + v.y / metres_per_deg_lat, 0.0});
  CHECK(placed[5].vertices[2].x == Approx(expected.x).margin(0.5));
  CHECK(placed[5].vertices[2].y == Approx(expected.y).margin(0.5));
  CHECK(placed[5].vertices[2].z == Approx(v.z + 35.0));
  const GeoLocation where = geolocation_of("EPSG:5179", anchor_map);
  CHECK(where.latitude_deg == Approx(37.5665).margin(1e-7));
  CHECK(where.longitude_deg == Approx(126.978).margin(1e-7));
}

TEST_CASE("scale, heading and offset place a model", "[sensors][models]") {
  corsa::test::TempDir dir;
  Footprint f{"cube", {{0, 0}, {1, 0}, {1, 1}, {0, 1}}, 1.0, 0.0, {}};
  write_model({extrude_footprint(f)}, dir.path() / "cube.obj", "obj");
  ModelPlacement p;
  p.scale = 2.0;
  p.heading = M_PI / 2.0;
  p.offset = {100.0, 200.0, 3.0};
  const auto m = load_model(dir.path() / "cube.obj", p);
  REQUIRE(m.size() == 1);
  const Bounds b = bounds_of(m);
  CHECK(b.min.x == Approx(98.0));
  CHECK(b.max.x == Approx(100.0));
  CHECK(b.min.y == Approx(200.0));
  CHECK(b.max.y == Approx(202.0));
  CHECK(b.max.z == Approx(5.0));
}

TEST_CASE("a broken or missing model file is reported with its name", "[sensors][models]") {
  corsa::test::TempDir dir;
  const fs::path broken = dir.path() / "broken.fbx";
  std::ofstream(broken) << "Kaydara FBX Binary  \0 this is not really an FBX file";
  try {
    load_model(broken, {});
    FAIL("accepted");
  } catch (const corsa::InputError& error) {
    CHECK(error.diagnostic().file == broken.string());
    CHECK_THAT(error.diagnostic().message, Catch::StartsWith("cannot read the model"));
  }
  CHECK_THROWS_WITH(
      load_model(dir.path() / "none.glb", {}),
      Catch::StartsWith((dir.path() / "none.glb").string() + ": error: cannot open file"));
  const fs::path empty = dir.path() / "empty.obj";
  std::ofstream(empty) << "# no faces\nv 0 0 0\n";
  CHECK_THROWS_AS(load_model(empty, {}), corsa::InputError);
  ModelPlacement bad_crs;
  bad_crs.model_crs = "EPSG:999999";
  bad_crs.map_crs = "EPSG:5179";
  CHECK_THROWS_WITH(load_model(kModels / "street_district.obj", bad_crs),
                    Catch::Contains("cannot transform coordinates from 'EPSG:999999'"));
}

namespace {

/// A 2 x 1 x 0.5 box as an OBJ with texture coordinates and a material whose texture is `png`.
void write_textured_box(const fs::path& dir, const std::string& png) {
  std::ofstream mtl(dir / "box.mtl");
  mtl << "newmtl skin\nKd 0.8 0.8 0.8\nmap_Kd " << png << "\n";
  std::ofstream obj(dir / "box.obj");
  obj << "mtllib box.mtl\n";
  for (int i = 0; i < 8; ++i) {
    obj << "v " << (i & 1 ? 1.0 : -1.0) << " " << (i & 2 ? 0.5 : -0.5) << " " << (i & 4 ? 0.5 : 0.0)
        << "\n";
  }
  obj << "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nusemtl skin\n";
  const int faces[6][4] = {{1, 3, 4, 2}, {5, 6, 8, 7}, {1, 2, 6, 5},
                           {3, 7, 8, 4}, {1, 5, 7, 3}, {2, 4, 8, 6}};
  for (const auto& f : faces) {
    obj << "f " << f[0] << "/1 " << f[1] << "/2 " << f[2] << "/3 " << f[3] << "/4\n";
  }
}

}  // namespace

TEST_CASE("an entity's model3d is loaded with its texture and stretched onto its box",
          "[sensors][model][model3d]") {
  corsa::test::TempDir dir;
  const std::vector<uint8_t> red(4 * 4 * 3, 0);
  std::vector<uint8_t> pixels = red;
  for (size_t i = 0; i < pixels.size(); i += 3) {
    pixels[i] = 200;
  }
  write_png_rgb8(dir.path() / "red.png", 4, 4, pixels);
  write_textured_box(dir.path(), "red.png");
  std::vector<corsa::Diagnostic> warnings;
  corsa::Diagnostics diagnostics([&](const corsa::Diagnostic& d) { warnings.push_back(d); });
  ModelShapeSource source(dir.path(), diagnostics);
  corsa::engine::EntitySnapshot car;
  car.name = "car";
  car.model3d = "box.obj";
  car.box = {1.4, 0.0, 0.75, 4.6, 1.9, 1.5};
  StaticMesh mesh;
  REQUIRE(source.shape_of(car, mesh));
  CHECK(warnings.empty());
  Bounds b = bounds_of({mesh});
  CHECK(b.min.x == Approx(1.4 - 2.3));
  CHECK(b.max.x == Approx(1.4 + 2.3));
  CHECK(b.max.y == Approx(0.95));
  CHECK(b.min.z == Approx(0.0).margin(1e-9));
  CHECK(b.max.z == Approx(1.5));
  REQUIRE(mesh.materials.size() == 1);
  REQUIRE(mesh.materials[0].image != nullptr);
  CHECK(mesh.materials[0].image->sample(0.5, 0.5, 1.0).r > 0.5);
  CHECK(mesh.uvs.size() == mesh.vertices.size());
  CHECK(mesh.classes == std::vector<SemanticClass>{SemanticClass::kCar});
}

TEST_CASE("a missing texture or an unreadable model is a located warning and a stand-in",
          "[sensors][model][model3d]") {
  corsa::test::TempDir dir;
  write_textured_box(dir.path(), "missing.png");
  std::ofstream(dir.path() / "broken.glb") << "not a model";
  std::vector<corsa::Diagnostic> warnings;
  corsa::Diagnostics diagnostics([&](const corsa::Diagnostic& d) { warnings.push_back(d); });
  ModelShapeSource source(dir.path(), diagnostics);
  corsa::engine::EntitySnapshot e;
  e.name = "a";
  e.model3d = "box.obj";
  e.box = {0.0, 0.0, 0.75, 4.0, 2.0, 1.5};
  StaticMesh mesh;
  REQUIRE(source.shape_of(e, mesh));  // the colour stands in for the texture
  REQUIRE(warnings.size() == 1);
  CHECK_THAT(warnings[0].message, Catch::Contains("missing.png"));
  e.model3d = "broken.glb";
  CHECK_FALSE(source.shape_of(e, mesh));  // the generated shape will stand in
  CHECK_FALSE(source.shape_of(e, mesh));
  REQUIRE(warnings.size() == 2);  // once per file
  CHECK_THAT(warnings[1].file, Catch::Contains("broken.glb"));
  CHECK_THAT(warnings[1].message, Catch::Contains("stands in"));
}

namespace {

/// A plain 4 x 2 x 1 OBJ box (no material), as a user's stand-in model.
void write_plain_box(const fs::path& file) {
  std::ofstream obj(file);
  for (int i = 0; i < 8; ++i) {
    obj << "v " << (i & 1 ? 2.0 : -2.0) << " " << (i & 2 ? 1.0 : -1.0) << " " << (i & 4 ? 1.0 : 0.0)
        << "\n";
  }
  const int faces[6][4] = {{1, 3, 4, 2}, {5, 6, 8, 7}, {1, 2, 6, 5},
                           {3, 7, 8, 4}, {1, 5, 7, 3}, {2, 4, 8, 6}};
  for (const auto& f : faces) {
    obj << "f " << f[0] << " " << f[1] << " " << f[2] << " " << f[3] << "\n";
  }
}

corsa::engine::EntitySnapshot category_entity(const std::string& name,
                                              corsa::engine::EntityCategory c) {
  corsa::engine::EntitySnapshot e;
  e.name = name;
  e.category = c;
  e.box = {1.4, 0.0, 0.75, 4.6, 1.9, 1.5};
  return e;
}

}  // namespace

TEST_CASE("the rig's entity models shape entities without model3d by name, then by category",
          "[sensors][model][model3d]") {
  using corsa::engine::EntityCategory;
  corsa::test::TempDir dir;
  fs::create_directories(dir.path() / "rig" / "models");
  write_plain_box(dir.path() / "rig" / "models" / "car.obj");
  write_plain_box(dir.path() / "rig" / "models" / "ego.obj");
  write_plain_box(dir.path() / "own.obj");
  const fs::path rig_file = dir.path() / "rig" / "rig.xml";
  const SensorRig rig = parse_rig(R"(<SensorRig version="1">
  <EntityModel category="car" file="models/car.obj"/>
  <EntityModel entity="Ego" file="models/ego.obj"/>
</SensorRig>)",
                                  rig_file.string());
  std::vector<corsa::Diagnostic> warnings;
  corsa::Diagnostics diagnostics([&](const corsa::Diagnostic& d) { warnings.push_back(d); });
  ModelShapeSource source(dir.path(), diagnostics, rig.entity_models, rig.file);
  StaticMesh mesh;
  REQUIRE(source.shape_of(category_entity("Target", EntityCategory::kCar), mesh));
  CHECK_THAT(mesh.name, Catch::EndsWith("car.obj"));
  const Bounds b = bounds_of({mesh});  // the 4 x 2 x 1 model stretched onto the box
  CHECK(b.min.x == Approx(1.4 - 2.3));
  CHECK(b.max.y == Approx(0.95));
  CHECK(b.max.z == Approx(1.5));
  CHECK(mesh.classes == std::vector<SemanticClass>{SemanticClass::kCar});
  // The entity's own name wins over its category, and its own model3d over both.
  REQUIRE(source.shape_of(category_entity("Ego", EntityCategory::kCar), mesh));
  CHECK_THAT(mesh.name, Catch::EndsWith("ego.obj"));
  auto own = category_entity("Other", EntityCategory::kCar);
  own.model3d = "own.obj";
  REQUIRE(source.shape_of(own, mesh));
  CHECK_THAT(mesh.name, Catch::EndsWith("own.obj"));
  // Categories the rig does not name keep their generated shapes.
  CHECK_FALSE(source.shape_of(category_entity("Walker", EntityCategory::kPedestrian), mesh));
  CHECK_FALSE(source.shape_of(category_entity("Box", EntityCategory::kVan), mesh));
  CHECK(warnings.empty());
}

TEST_CASE(
    "a missing or unreadable entity model of the rig is a warning at its element and the "
    "generated shape stands in",
    "[sensors][model][model3d][errors]") {
  using corsa::engine::EntityCategory;
  corsa::test::TempDir dir;
  std::ofstream(dir.path() / "broken.glb") << "not a model";
  const fs::path rig_file = dir.path() / "rig.xml";
  const SensorRig rig = parse_rig(R"(<SensorRig version="1">
  <EntityModel category="car" file="nothere.obj"/>
  <EntityModel category="pedestrian" file="broken.glb"/>
</SensorRig>)",
                                  rig_file.string());
  std::vector<corsa::Diagnostic> warnings;
  corsa::Diagnostics diagnostics([&](const corsa::Diagnostic& d) { warnings.push_back(d); });
  ModelShapeSource source(dir.path(), diagnostics, rig.entity_models, rig.file);
  StaticMesh mesh;
  CHECK_FALSE(source.shape_of(category_entity("a", EntityCategory::kCar), mesh));
  CHECK_FALSE(source.shape_of(category_entity("b", EntityCategory::kCar), mesh));
  CHECK_FALSE(source.shape_of(category_entity("c", EntityCategory::kPedestrian), mesh));
  REQUIRE(warnings.size() == 2);  // once per file
  CHECK(warnings[0].file == rig_file.string());
  CHECK(warnings[0].line == 2);
  CHECK_THAT(warnings[0].message, Catch::Contains("nothere.obj") && Catch::Contains("stand in"));
  CHECK(warnings[1].line == 3);
  CHECK_THAT(warnings[1].message, Catch::Contains("broken.glb"));
}
