#pragma once

namespace corsa::sensors::detail {

/// The text of schemas/sensor-rig.xsd, compiled in at build time.
const char* rig_schema_text();

}  // namespace corsa::sensors::detail
