#include "corsa/sensors/rig.h"

#include <catch2/catch.hpp>
#include <filesystem>
#include <string>
#include <vector>

#include "corsa/core/diagnostic.h"

using corsa::InputError;
using namespace corsa::sensors;

namespace {

const char* const kRig = R"(<?xml version="1.0"?>
<SensorRig version="1" name="test">
  <RgbCamera name="front" entity="Ego" rate="20" width="640" height="480" fov="70"
             shutterSpeed="0.01" iso="400" gamma="2.0" k1="-0.1" k2="0.01" p1="0.001" p2="0">
    <Mount x="1.5" z="1.4" pitch="5"/>
  </RgbCamera>
  <DepthCamera name="depth" entity="Ego" maxRange="80"/>
  <SemanticCamera name="sem" entity="Ego"/>
  <InstanceCamera name="inst" entity="Ego"/>
  <BirdsEyeCamera name="bev" entity="Ego" extent="50" followHeading="false" style="rgb"/>
  <Lidar name="top" entity="Ego" channels="64" range="120" pointsPerSecond="1300000"
         rotationFrequency="10" upperFov="2" lowerFov="-24.8" noiseStddev="0.02">
    <Mount z="1.9"/>
  </Lidar>
</SensorRig>
)";

/// The diagnostic of parsing `xml`, which must fail.
corsa::Diagnostic failure(const std::string& xml) {
  try {
    parse_rig(xml, "rig.xml");
  } catch (const InputError& error) {
    return error.diagnostic();
  }
  FAIL("the rig was accepted");
  return {};
}

std::string rig_with(const std::string& sensor) {
  return "<SensorRig version=\"1\">\n" + sensor + "\n</SensorRig>\n";
}

}  // namespace

TEST_CASE("a rig file gives every sensor its options, mount and defaults", "[sensors][rig]") {
  const SensorRig rig = parse_rig(kRig, "rig.xml");
  REQUIRE(rig.sensors.size() == 6);
  CHECK(rig.name == "test");
  const SensorSpec& cam = rig.sensors[0];
  CHECK(cam.kind == SensorKind::kRgbCamera);
  CHECK(cam.rate_hz == 20.0);
  CHECK(cam.camera.width == 640);
  CHECK(cam.camera.fov_deg == 70.0);
  CHECK(cam.camera.k1 == -0.1);
  CHECK(cam.rgb.iso == 400.0);
  CHECK(cam.rgb.shutter_speed_s == 0.01);
  CHECK(cam.rgb.noise);
  CHECK(cam.mount.x == 1.5);
  CHECK(cam.mount.y == 0.0);
  CHECK(cam.mount.pitch_deg == 5.0);
  CHECK(cam.line == 3);
  const SensorSpec& depth = *rig.find("depth");
  CHECK(depth.kind == SensorKind::kDepthCamera);
  CHECK(depth.depth.max_range_m == 80.0);
  CHECK(depth.camera.width == 1280);  // schema default
  CHECK(depth.rate_hz == 10.0);
  CHECK(rig.find("sem")->kind == SensorKind::kSemanticCamera);
  CHECK(rig.find("inst")->kind == SensorKind::kInstanceCamera);
  const SensorSpec& bev = *rig.find("bev");
  CHECK_FALSE(bev.birds_eye.follow_heading);
  CHECK(bev.birds_eye.style == BirdsEyeStyle::kRgb);
  CHECK(bev.birds_eye.extent_m == 50.0);
  const SensorSpec& lidar = *rig.find("top");
  CHECK(lidar.lidar.channels == 64);
  CHECK(lidar.lidar.lower_fov_deg == -24.8);
  CHECK(lidar.lidar.azimuth_steps() == 2031);  // 1.3e6 / (64 * 10) = 2031.25
  CHECK(lidar.mount.z == 1.9);
  CHECK(rig.find("nothing") == nullptr);
}

TEST_CASE("an out-of-range rig option is reported at its line", "[sensors][rig][errors]") {
  const auto d = failure(rig_with("<Lidar name=\"l\" entity=\"Ego\"\n channels=\"500\"/>"));
  CHECK(d.file == "rig.xml");
  CHECK(d.line == 2);
  CHECK(d.message == "attribute 'channels' of <Lidar> is 500, above the maximum 256");
  CHECK(d.format() ==
        "rig.xml:2: error: attribute 'channels' of <Lidar> is 500, above the "
        "maximum 256 [in SensorRig/Lidar]");
}

TEST_CASE("bad rig values, names and structure give located messages", "[sensors][rig][errors]") {
  SECTION("exclusive bound") {
    const auto d = failure(rig_with("<RgbCamera name=\"c\" entity=\"E\" fov=\"170\"/>"));
    CHECK(d.line == 2);
    CHECK(d.message == "attribute 'fov' of <RgbCamera> is 170; it must be less than 170");
  }
  SECTION("not a number") {
    const auto d = failure(rig_with("<DepthCamera name=\"c\" entity=\"E\" maxRange=\"far\"/>"));
    CHECK(d.message == "attribute 'maxRange' of <DepthCamera> is 'far'; expected a number");
  }
  SECTION("not an integer") {
    const auto d = failure(rig_with("<SemanticCamera name=\"c\" entity=\"E\" width=\"6.5\"/>"));
    CHECK(d.message == "attribute 'width' of <SemanticCamera> is '6.5'; expected an integer");
  }
  SECTION("unknown attribute") {
    const auto d = failure(rig_with("<Lidar name=\"l\" entity=\"E\" beams=\"3\"/>"));
    CHECK(d.message == "unknown attribute 'beams' on <Lidar>");
  }
  SECTION("missing attribute") {
    const auto d = failure(rig_with("<Lidar name=\"l\"/>"));
    CHECK(d.message == "<Lidar> needs the attribute 'entity'");
  }
  SECTION("unknown element") {
    const auto d = failure(rig_with("\n<Radar name=\"r\" entity=\"E\"/>"));
    CHECK(d.line == 3);
    CHECK_THAT(d.message, Catch::StartsWith("element <Radar> is not allowed in <SensorRig>"));
  }
  SECTION("two mounts") {
    const auto d =
        failure(rig_with("<Lidar name=\"l\" entity=\"E\">\n<Mount/>\n<Mount/>\n</Lidar>"));
    CHECK(d.line == 4);
    CHECK_THAT(d.message, Catch::StartsWith("element <Mount> is not allowed in <Lidar>"));
  }
  SECTION("enumeration") {
    const auto d = failure(rig_with("<BirdsEyeCamera name=\"b\" entity=\"E\" style=\"fancy\"/>"));
    CHECK(d.message ==
          "attribute 'style' of <BirdsEyeCamera> is 'fancy'; expected one of 'semantic', 'rgb'");
  }
  SECTION("pattern") {
    const auto d = failure(rig_with("<Lidar name=\"a b\" entity=\"E\"/>"));
    CHECK_THAT(d.message, Catch::Contains("does not match the pattern"));
  }
  SECTION("duplicate sensor name") {
    const auto d =
        failure(rig_with("<Lidar name=\"l\" entity=\"E\"/>\n<Lidar name=\"l\" entity=\"E\"/>"));
    CHECK(d.line == 3);
    CHECK(d.message == "a sensor named 'l' is already in the rig");
  }
  SECTION("crossed LiDAR field of view") {
    const auto d =
        failure(rig_with("<Lidar name=\"l\" entity=\"E\" upperFov=\"-10\" lowerFov=\"5\"/>"));
    CHECK(d.message == "<Lidar> lowerFov (5) is above upperFov (-10)");
  }
  SECTION("wrong root and version") {
    CHECK(failure("<Rig/>").message == "expected the root element <SensorRig>");
    CHECK(failure("<SensorRig version=\"2\"/>").message ==
          "attribute 'version' of <SensorRig> is '2'; expected one of '1'");
  }
  SECTION("not XML") {
    const auto d = failure("<SensorRig version=\"1\">\n<Lidar>\n</SensorRig>");
    CHECK(d.line == 2);  // tinyxml2 locates a mismatched end tag at the unclosed element
    CHECK_THAT(d.message, Catch::StartsWith("not well-formed XML"));
  }
}

TEST_CASE("binding a rig to a scenario rejects unknown entities at the sensor's line",
          "[sensors][rig][errors]") {
  const SensorRig rig = parse_rig(kRig, "rig.xml");
  const std::vector<std::string> good{"Ego", "Npc1"};
  CHECK_NOTHROW(bind_rig(rig, good));
  const std::vector<std::string> bad{"Hero", "Npc1"};
  try {
    bind_rig(rig, bad);
    FAIL("accepted");
  } catch (const InputError& error) {
    CHECK(error.diagnostic().line == 3);
    CHECK(error.diagnostic().message ==
          "sensor 'front' is attached to entity 'Ego', which the scenario does not have "
          "(entities: Hero, Npc1)");
  }
}

TEST_CASE("loading a missing rig file names it", "[sensors][rig][errors]") {
  CHECK_THROWS_WITH(load_rig("/no/such/rig.xml"), Catch::StartsWith("/no/such/rig.xml: error:"));
}

TEST_CASE("the rig's quality applies to RGB cameras that do not name their own",
          "[sensors][rig][quality]") {
  const SensorRig rig = parse_rig(R"(<SensorRig version="1" quality="fast">
  <RgbCamera name="a" entity="E"/>
  <RgbCamera name="b" entity="E" quality="high"/>
</SensorRig>)",
                                  "rig.xml");
  CHECK(rig.quality == RenderQuality::kFast);
  CHECK(rig.find("a")->rgb.quality == RenderQuality::kFast);
  CHECK(rig.find("b")->rgb.quality == RenderQuality::kHigh);
  CHECK(parse_rig(rig_with("<RgbCamera name=\"c\" entity=\"E\"/>"), "rig.xml")
            .find("c")
            ->rgb.quality == RenderQuality::kDefault);
  CHECK(render_quality_name(RenderQuality::kHigh) == "high");
}

TEST_CASE("an RGB camera meters its exposure unless the rig fixes shutter or ISO",
          "[sensors][rig]") {
  const auto camera = [](const std::string& attributes) {
    const SensorRig rig =
        parse_rig(rig_with("<RgbCamera name=\"c\" entity=\"E\" " + attributes + "/>"), "rig.xml");
    return rig.find("c")->rgb;
  };
  CHECK(camera("").auto_exposure);
  const RgbOptions shutter = camera("shutterSpeed=\"0.01\"");
  CHECK_FALSE(shutter.auto_exposure);
  CHECK(shutter.shutter_speed_s == 0.01);
  CHECK(shutter.iso == 100.0);
  const RgbOptions iso = camera("iso=\"800\"");
  CHECK_FALSE(iso.auto_exposure);
  CHECK(iso.shutter_speed_s == 0.004);
  CHECK(iso.iso == 800.0);
}

TEST_CASE("a quality the rig does not know is an error at its line", "[sensors][rig][errors]") {
  const auto d = failure("<SensorRig version=\"1\"\n quality=\"ultra\">\n</SensorRig>\n");
  CHECK(d.file == "rig.xml");
  CHECK(d.line == 1);
  CHECK(d.message ==
        "attribute 'quality' of <SensorRig> is 'ultra'; expected one of 'fast', 'default', "
        "'high'");
  const auto camera = failure(rig_with("<RgbCamera name=\"c\" entity=\"E\" quality=\"best\"/>"));
  CHECK(camera.line == 2);
}

TEST_CASE("the rig asks for generated buildings with buildings=\"generate\"",
          "[sensors][rig][buildings]") {
  CHECK_FALSE(
      parse_rig(rig_with("<RgbCamera name=\"c\" entity=\"E\"/>"), "rig.xml").generate_buildings);
  CHECK_FALSE(
      parse_rig("<SensorRig version=\"1\" buildings=\"none\"/>", "rig.xml").generate_buildings);
  CHECK(
      parse_rig("<SensorRig version=\"1\" buildings=\"generate\"/>", "rig.xml").generate_buildings);
  const auto d = failure("<SensorRig version=\"1\"\n buildings=\"many\">\n</SensorRig>\n");
  CHECK(d.line == 1);
  CHECK(d.message ==
        "attribute 'buildings' of <SensorRig> is 'many'; expected one of 'none', 'generate'");
}

TEST_CASE("the rig parks vehicles where the map marks parking unless it says otherwise",
          "[sensors][rig][parked]") {
  const SensorRig plain = parse_rig(rig_with("<RgbCamera name=\"c\" entity=\"E\"/>"), "rig.xml");
  CHECK(plain.parked_vehicles == ParkedVehicles::kMap);
  CHECK(plain.parked_density == 0.6);
  const SensorRig kerb = parse_rig(
      "<SensorRig version=\"1\" parkedVehicles=\"kerb\" parkedDensity=\"0.3\"/>", "rig.xml");
  CHECK(kerb.parked_vehicles == ParkedVehicles::kKerb);
  CHECK(kerb.parked_density == 0.3);
  CHECK(
      parse_rig("<SensorRig version=\"1\" parkedVehicles=\"none\"/>", "rig.xml").parked_vehicles ==
      ParkedVehicles::kNone);
  const auto d = failure("<SensorRig version=\"1\"\n parkedVehicles=\"street\">\n</SensorRig>\n");
  CHECK(d.line == 1);
  CHECK(d.message ==
        "attribute 'parkedVehicles' of <SensorRig> is 'street'; expected one of 'none', 'map', "
        "'kerb'");
  const auto density = failure("<SensorRig version=\"1\" parkedDensity=\"1.5\"/>");
  CHECK(density.line == 1);
}

TEST_CASE("a rig names the user's models by category or by entity, beside the rig file",
          "[sensors][rig][model3d]") {
  const SensorRig rig = parse_rig(R"(<SensorRig version="1">
  <EntityModel category="car" file="models/sedan.glb"/>
  <RgbCamera name="front" entity="Ego"/>
  <EntityModel entity="Ego" file="/abs/ego.obj"/>
</SensorRig>)",
                                  "rigs/city.xml");
  REQUIRE(rig.entity_models.size() == 2);
  CHECK(rig.sensors.size() == 1);
  CHECK(rig.entity_models[0].category == "car");
  CHECK(rig.entity_models[0].entity.empty());
  CHECK(rig.entity_models[0].file == std::filesystem::path("rigs/models/sedan.glb"));
  CHECK(rig.entity_models[0].line == 2);
  CHECK(rig.entity_models[1].entity == "Ego");
  CHECK(rig.entity_models[1].file == std::filesystem::path("/abs/ego.obj"));
  const std::vector<std::string> names = {"Ego"};
  CHECK_NOTHROW(bind_rig(rig, names));
}

TEST_CASE(
    "an entity model with both or neither of category and entity, an unknown category or "
    "an unknown entity is an error at its line",
    "[sensors][rig][model3d][errors]") {
  auto d = failure(R"(<SensorRig version="1">
  <EntityModel category="car" entity="Ego" file="a.obj"/>
</SensorRig>)");
  CHECK(d.line == 2);
  CHECK_THAT(d.message, Catch::Contains("either a category or an entity"));
  d = failure(R"(<SensorRig version="1">

  <EntityModel file="a.obj"/>
</SensorRig>)");
  CHECK(d.line == 3);
  d = failure(R"(<SensorRig version="1">
  <EntityModel category="spaceship" file="a.obj"/>
</SensorRig>)");
  CHECK(d.line == 2);
  CHECK_THAT(d.message, Catch::Contains("spaceship"));
  const SensorRig rig = parse_rig(R"(<SensorRig version="1">
  <EntityModel entity="Egg" file="a.obj"/>
</SensorRig>)",
                                  "rig.xml");
  const std::vector<std::string> names = {"Ego", "Target"};
  try {
    bind_rig(rig, names);
    FAIL("an unknown entity was accepted");
  } catch (const InputError& error) {
    CHECK(error.diagnostic().line == 2);
    CHECK_THAT(error.diagnostic().message, Catch::Contains("'Egg'") && Catch::Contains("Ego"));
  }
}
