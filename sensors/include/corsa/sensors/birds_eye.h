#pragma once

// Bird's-eye camera: an orthographic view straight down, centred on the sensor's position,
// image up along the sensor's heading (followHeading) or north. Semantic style colours every
// pixel by its class; rgb style shades with the sun (no shadows).

#include <cstdint>
#include <vector>

#include "corsa/sensors/environment.h"
#include "corsa/sensors/rig.h"
#include "corsa/sensors/scene.h"

namespace corsa::sensors {

struct BirdsEyeImage {
  int width = 0;
  int height = 0;
  std::vector<uint8_t> rgb;       ///< 3 bytes per pixel
  std::vector<uint8_t> semantic;  ///< class ids
  std::vector<uint32_t> instance;
};

/// `lighting` is needed for the rgb style (null: semantic colours are used).
BirdsEyeImage render_birds_eye(const Scene& scene, const BirdsEyeOptions& options,
                               const Rigid& world_from_body, const Lighting* lighting);

}  // namespace corsa::sensors
