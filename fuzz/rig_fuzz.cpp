// libFuzzer target: any bytes as a sensor rig file (schemas/sensor-rig.xsd), read by tinyxml2,
// checked by core's XSD-subset validator and the rig's own limits, then bound to a scenario's
// entities. Bad input must end in corsa::InputError, never a crash, a hang or a sanitizer report.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "corsa/core/diagnostic.h"
#include "corsa/sensors/rig.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const std::vector<std::string> kEntities{"Ego", "Cutter", "Pedestrian"};
  try {
    const corsa::sensors::SensorRig rig = corsa::sensors::parse_rig(
        std::string_view(reinterpret_cast<const char*>(data), size), "fuzz_rig.xml");
    for (const auto& sensor : rig.sensors) {
      (void)rig.find(sensor.name);
      if (sensor.kind == corsa::sensors::SensorKind::kLidar) (void)sensor.lidar.azimuth_steps();
    }
    corsa::sensors::bind_rig(rig, kEntities);
  } catch (const corsa::InputError&) {
    // Expected for bad input.
  }
  return 0;
}
