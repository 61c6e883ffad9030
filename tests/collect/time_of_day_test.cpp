// The time of day of a dataset: a time without a zone is local solar time at the map's place,
// an explicit zone is honoured, and a map without a usable geoReference says (once) where the sun
// is computed. Noon must be day on CARLA's Town03 and on a converted NGII map of K-City (it was
// night on both: the clock was read as UTC).

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <regex>
#include <string>
#include <vector>

#include "corsa/collect/dataset_run.h"
#include "corsa/core/atomic_file.h"
#include "run_corsa.h"
#include "temp_dir.h"

namespace {

namespace fs = std::filesystem;

std::string world_position(double x, double y) {
  return "<WorldPosition x=\"" + std::to_string(x) + "\" y=\"" + std::to_string(y) + "\" h=\"0\"/>";
}

// A scenario with Ego standing at `position` (an OpenSCENARIO Position's content) of `map`
// without any EnvironmentAction (the default: 12:00 without a zone), or with a TimeOfDay
// `date_time`.
fs::path write_scenario(const fs::path& dir, const fs::path& map, const std::string& position,
                        const std::string& date_time = {}) {
  std::string init = "<Private entityRef=\"Ego\"><PrivateAction><TeleportAction><Position>" +
                     position + "</Position></TeleportAction></PrivateAction></Private>";
  if (!date_time.empty()) {
    init =
        "<GlobalAction><EnvironmentAction><Environment name=\"e\"><TimeOfDay animation=\"false\" "
        "dateTime=\"" +
        date_time +
        "\"/><Weather cloudState=\"free\"/><RoadCondition frictionScaleFactor=\"1\"/>"
        "</Environment></EnvironmentAction></GlobalAction>" +
        init;
  }
  const std::string text =
      "<?xml version=\"1.0\"?>\n<OpenSCENARIO><FileHeader revMajor=\"1\" revMinor=\"3\" "
      "date=\"2024-01-01T00:00:00\" description=\"sky\" author=\"Corsa tests\"/>"
      "<CatalogLocations/><RoadNetwork><LogicFile filepath=\"" +
      fs::absolute(map).string() +
      "\"/></RoadNetwork><Entities><ScenarioObject name=\"Ego\"><Vehicle name=\"car\" "
      "vehicleCategory=\"car\"><Performance maxSpeed=\"50\" maxAcceleration=\"5\" "
      "maxDeceleration=\"8\"/><BoundingBox><Center x=\"1.4\" y=\"0\" z=\"0.75\"/><Dimensions "
      "width=\"1.8\" length=\"4.5\" height=\"1.5\"/></BoundingBox><Axles><FrontAxle "
      "maxSteering=\"0.5\" wheelDiameter=\"0.6\" trackWidth=\"1.6\" positionX=\"2.8\" "
      "positionZ=\"0.3\"/><RearAxle maxSteering=\"0\" wheelDiameter=\"0.6\" trackWidth=\"1.6\" "
      "positionX=\"0\" positionZ=\"0.3\"/></Axles><Properties/></Vehicle></ScenarioObject>"
      "</Entities><Storyboard><Init><Actions>" +
      init + "</Actions></Init><StopTrigger/></Storyboard></OpenSCENARIO>\n";
  const fs::path file = dir / ("sky_" + std::to_string(std::hash<std::string>{}(text)) + ".xosc");
  corsa::write_file_atomic(file, text);
  return file;
}

struct Shot {
  double brightness = 0.0;  ///< mean 8-bit value of the first camera frame
  std::vector<std::string> warnings;
};

Shot shoot(const fs::path& scenario, const fs::path& out, const std::string& time_of_day = {}) {
  corsa::collect::DatasetRunOptions options;
  options.run.scenario = scenario;
  options.run.simulation.duration = 0.05;
  options.rig = fs::path(CORSA_SOURCE_DIR) / "tests/collect/fixtures/sky_rig.xml";
  options.output = out;
  if (!time_of_day.empty()) {
    corsa::engine::parse_time_of_day(time_of_day, options.environment);
  }
  Shot shot;
  corsa::Diagnostics diagnostics(
      [&shot](const corsa::Diagnostic& d) { shot.warnings.push_back(d.format()); });
  corsa::collect::run_dataset(options, diagnostics);
  const cv::Mat image = cv::imread((out / "cam/000000.png").string(), cv::IMREAD_COLOR);
  REQUIRE(!image.empty());
  shot.brightness = cv::mean(image)[0] / 3.0 + cv::mean(image)[1] / 3.0 + cv::mean(image)[2] / 3.0;
  return shot;
}

// On the reference line of the map's first road.
std::string on_first_road(const fs::path& map) {
  const std::string text = corsa::read_file(map);
  std::smatch m;
  REQUIRE(std::regex_search(text, m, std::regex("<road [^>]*id=\"([^\"]+)\"")));
  return "<RoadPosition roadId=\"" + m[1].str() + "\" s=\"1\" t=\"0\"/>";
}

size_t count_containing(const std::vector<std::string>& lines, const std::string& text) {
  size_t n = 0;
  for (const std::string& line : lines) {
    n += line.find(text) != std::string::npos ? 1 : 0;
  }
  return n;
}

}  // namespace

TEST_CASE("Noon without a zone is day on Town03, placed by its origin-only geoReference",
          "[collect][time-of-day]") {
  corsa::test::TempDir dir;
  const fs::path town03 = fs::path(CORSA_SHARED_DIR) / "data/xodr/Town03.xodr";
  const fs::path scenario = write_scenario(dir.path(), town03, world_position(0.0, 0.0));
  const Shot noon = shoot(scenario, dir.path() / "noon");
  const Shot night = shoot(scenario, dir.path() / "night", "23:00");
  INFO(noon.brightness << " at noon, " << night.brightness << " at 23:00");
  CHECK(noon.brightness > 100.0);
  CHECK(night.brightness < 20.0);
  // CARLA's "+lat_0=49 +lon_0=8" names no projection: read as a transverse Mercator, said once.
  CHECK(count_containing(noon.warnings, "names no projection") == 1);
  CHECK(count_containing(noon.warnings, "the sun is computed at 49.00 N, 8.00 E") == 1);
}

TEST_CASE("Town04's default geoReference is honoured at 0 N, 0 E and said once",
          "[collect][time-of-day]") {
  corsa::test::TempDir dir;
  const fs::path town04 = fs::path(CORSA_SHARED_DIR) / "data/xodr/Town04.xodr";
  const fs::path scenario = write_scenario(dir.path(), town04, world_position(0.0, 0.0));
  // On the equator on 21 June the sun sets at about 18:04 apparent solar time (NOAA): 17:30 is
  // day, 18:30 (-6.9 degrees) is night.
  const Shot day = shoot(scenario, dir.path() / "day", "17:30");
  const Shot dusk = shoot(scenario, dir.path() / "dusk", "18:30");
  INFO(day.brightness << " at 17:30, " << dusk.brightness << " at 18:30");
  CHECK(day.brightness > 60.0);
  CHECK(dusk.brightness < day.brightness / 2.0);
  CHECK(count_containing(day.warnings, "a default origin?") == 1);
}

TEST_CASE("Noon without a zone is day on a converted K-City map; 12:00Z is evening there",
          "[collect][time-of-day]") {
  corsa::test::TempDir dir;
  const fs::path map = dir.path() / "kcity.xodr";
  const auto converted = corsa::test::run_corsa(
      {"convert", "ngii", std::string(CORSA_SHARED_DIR) + "/data/ngii/kcity", "-o", map.string()});
  INFO(converted.err);
  REQUIRE(converted.exit_code == 0);
  const std::string on_road = on_first_road(map);
  const fs::path solar = write_scenario(dir.path(), map, on_road);
  const Shot noon = shoot(solar, dir.path() / "noon");
  CHECK(noon.brightness > 100.0);
  CHECK(count_containing(noon.warnings, "the sun is computed") == 0);  // placed by its CRS
  // An explicit zone is honoured: 12:00 UTC is 21:00 in Korea, dark.
  const fs::path utc = write_scenario(dir.path(), map, on_road, "2024-06-21T12:00:00Z");
  CHECK(shoot(utc, dir.path() / "utc").brightness < 20.0);
  const fs::path kst = write_scenario(dir.path(), map, on_road, "2024-06-21T12:00:00+09:00");
  CHECK(shoot(kst, dir.path() / "kst").brightness > 100.0);
  // --time-of-day with a zone too.
  CHECK(shoot(solar, dir.path() / "cli", "12:00Z").brightness < 20.0);
  // The map is placed through its header <offset> (its UTM origin): at K-City, 37.24 N, the sun
  // at 18:30 on 21 June stands 8.4 degrees up (NOAA; tests/sensors/solar_test.cpp). Without
  // the offset the map landed on the equator, where it had set (-6.9 degrees): a night frame.
  const Shot evening = shoot(solar, dir.path() / "evening", "18:30");
  const Shot late = shoot(solar, dir.path() / "late", "22:00");
  INFO(evening.brightness << " at 18:30, " << late.brightness << " at 22:00");
  CHECK(evening.brightness > 60.0);
  CHECK(late.brightness < 20.0);
}

TEST_CASE("A map that cannot be placed says once where the sun is computed",
          "[collect][time-of-day]") {
  corsa::test::TempDir dir;
  const fs::path plain = fs::path(CORSA_SOURCE_DIR) / "tests/engine/fixtures/straight.xodr";
  const Shot shot =
      shoot(write_scenario(dir.path(), plain, world_position(50.0, 0.0)), dir.path() / "a");
  CHECK(count_containing(shot.warnings, "the sun is computed at 37.57 N, 126.98 E (Seoul)") == 1);
  CHECK(count_containing(shot.warnings, "local solar time") == 1);
  CHECK(shot.brightness > 100.0);  // still noon there
}
