// End to end: `corsa map mesh` and `corsa map render` (the latter runs in the plugin).

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "run_corsa.h"
#include "temp_dir.h"

using corsa::test::run_corsa;
using corsa::test::slurp;
using corsa::test::TempDir;

namespace {

std::string map_file(const std::string& name) {
  return std::string(CORSA_SHARED_DIR) + "/data/xodr/" + name;
}

}  // namespace

TEST_CASE("corsa map mesh writes an OBJ with its materials", "[xodr][mesh][cli][e2e]") {
  TempDir dir;
  const std::string obj = (dir.path() / "town.obj").string();
  const auto result = run_corsa({"map", "mesh", map_file("fabriksgatan.xodr"), "-o", obj});
  INFO(result.err);
  REQUIRE(result.exit_code == 0);
  CHECK_THAT(result.out, Catch::Contains("wrote " + obj));
  CHECK_THAT(result.out, Catch::Contains("triangles"));
  CHECK_THAT(slurp(obj), Catch::StartsWith("# Corsa road mesh"));
  CHECK_THAT(slurp(obj), Catch::Contains("mtllib town.mtl\n"));
  CHECK_THAT(slurp(dir.path() / "town.mtl"), Catch::Contains("newmtl driving"));
}

TEST_CASE("corsa map mesh writes binary or ASCII PLY with a tolerance", "[xodr][mesh][cli][e2e]") {
  TempDir dir;
  const std::string coarse = (dir.path() / "coarse.ply").string();
  const std::string fine = (dir.path() / "fine.ply").string();
  REQUIRE(run_corsa({"map", "mesh", map_file("velodrome.xodr"), "-o", coarse, "--tolerance", "0.5",
                     "--ascii", "--no-marks"})
              .exit_code == 0);
  REQUIRE(
      run_corsa({"map", "mesh", map_file("velodrome.xodr"), "-o", fine, "--no-marks"}).exit_code ==
      0);
  CHECK_THAT(slurp(coarse), Catch::Contains("format ascii 1.0"));
  CHECK_THAT(slurp(fine), Catch::Contains("format binary_little_endian 1.0"));
  const auto faces = [](const std::string& text) {
    const size_t at = text.find("element face ");
    return std::stol(text.substr(at + 13));
  };
  // The banked loop at 0.1 m needs more rows than at 0.5 m.
  CHECK(faces(slurp(coarse)) > 0);
  CHECK(faces(slurp(fine)) > faces(slurp(coarse)));
}

TEST_CASE("corsa map mesh refuses bad usage and bad maps with exit 2", "[xodr][mesh][cli][e2e]") {
  TempDir dir;
  const std::string map = map_file("straight_500m.xodr");
  SECTION("no output") {
    const auto result = run_corsa({"map", "mesh", map});
    CHECK(result.exit_code == 2);
    CHECK_THAT(result.err, Catch::Contains("-o"));
  }
  SECTION("unknown format") {
    const auto result = run_corsa({"map", "mesh", map, "-o", (dir.path() / "m.stl").string()});
    CHECK(result.exit_code == 2);
    CHECK_THAT(result.err, Catch::Contains(".obj or .ply"));
  }
  SECTION("bad tolerance") {
    const auto result =
        run_corsa({"map", "mesh", map, "-o", (dir.path() / "m.ply").string(), "--tolerance", "0"});
    CHECK(result.exit_code == 2);
    CHECK_THAT(result.err, Catch::Contains("--tolerance"));
  }
  SECTION("a truncated map") {
    const auto bad = dir.path() / "bad.xodr";
    const std::string text = slurp(map);
    std::ofstream(bad) << text.substr(0, text.size() / 2);
    const auto result =
        run_corsa({"map", "mesh", bad.string(), "-o", (dir.path() / "m.obj").string()});
    CHECK(result.exit_code == 2);
    CHECK_THAT(result.err, Catch::Contains("bad.xodr:"));
    CHECK_THAT(result.err, Catch::Contains("error"));
  }
  CHECK(dir.entries() <= 1);  // nothing written but the truncated input
}

TEST_CASE("corsa map render draws a PNG of the requested size", "[xodr][render][cli][e2e]") {
  TempDir dir;
  const std::string png = (dir.path() / "map.png").string();
  const auto result = run_corsa(
      {"map", "render", map_file("Ex_LHT-Complex-X-Junction.xodr"), "-o", png, "--size", "200"});
  INFO(result.err);
  REQUIRE(result.exit_code == 0);
  CHECK_THAT(result.out, Catch::Contains("200 x 200 pixels"));
  const cv::Mat image = cv::imread(png, cv::IMREAD_COLOR);
  CHECK(image.cols == 200);
  CHECK(image.rows == 200);
  const auto scaled = run_corsa({"map", "render", map_file("straight_500m.xodr"), "-o",
                                 (dir.path() / "s.png").string(), "--scale", "2", "--road-ids"});
  CHECK(scaled.exit_code == 0);
  CHECK_THAT(scaled.out, Catch::Contains("2.000 m per pixel"));
}

TEST_CASE("corsa map render refuses bad usage with exit 2", "[xodr][render][cli][e2e]") {
  TempDir dir;
  const std::string map = map_file("straight_500m.xodr");
  const std::string png = (dir.path() / "m.png").string();
  for (const auto& args : std::vector<std::vector<std::string>>{
           {"map", "render", map},
           {"map", "render", map, "-o", (dir.path() / "m.jpg").string()},
           {"map", "render", map, "-o", png, "--size", "10"},
           {"map", "render", map, "-o", png, "--size", "300", "--scale", "1"},
           {"map", "render", map, "-o", png, "--scale", "0.0001"},
           {"map", "render", (dir.path() / "missing.xodr").string(), "-o", png}}) {
    const auto result = run_corsa(args);
    INFO(args.back() << ": " << result.err);
    CHECK(result.exit_code == 2);
    CHECK_THAT(result.err, Catch::Contains("error"));
  }
  CHECK(dir.entries() == 0);
  const auto help = run_corsa({"map", "render", "--help"});
  CHECK(help.exit_code == 0);
  CHECK_THAT(help.out, Catch::StartsWith("usage: corsa map render"));
}
