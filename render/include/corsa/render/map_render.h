#pragma once

// Top-down picture of an OpenDRIVE map for people: lanes filled by type, junction areas tinted,
// road marks painted, optional road ids, a scale bar and a north arrow, anti-aliased.
//
// Module render (library corsa_render), above xodr. It uses OpenCV inside (rasterising, PNG),
// which is why it is a module of its own, linked into the plugin and not into the `corsa`
// executable (apps/corsa/plugin_api.h); this header exposes no OpenCV type.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "corsa/core/diagnostic.h"

namespace corsa::xodr {
class Map;
}

namespace corsa::render {

struct RenderOptions {
  /// Pixels along the picture's longer side, margins included (used when `scale` is 0).
  int size = 2048;
  /// Metres per pixel; 0: chosen so that the map fits `size`.
  double scale = 0.0;
  /// Writes each road's id at its middle (roads inside junctions left out).
  bool road_ids = false;
};

/// Largest picture side (pixels) render_map accepts.
inline constexpr int kMaxPictureSide = 16384;
/// Smallest `size`.
inline constexpr int kMinPictureSide = 64;

/// An RGB picture and where it lies on the map. North (+y) is up.
struct MapPicture {
  int width = 0;
  int height = 0;
  std::vector<uint8_t> rgb;  ///< width * height * 3 bytes, rows top to bottom
  double scale = 0.0;        ///< metres per pixel
  double left = 0.0;         ///< map x (m) of the picture's left edge
  double top = 0.0;          ///< map y (m) of the picture's top edge

  /// Pixel column and row (fractional; a pixel's centre is at +0.5) of map point (x, y).
  double column_of(double x) const { return (x - left) / scale; }
  double row_of(double y) const { return (top - y) / scale; }
};

/// Draws `map`. Throws InputError (naming the map file) when the picture would exceed
/// kMaxPictureSide on a side, and std::invalid_argument for options out of range (size below
/// kMinPictureSide, negative scale). Road-mesh warnings go to `diagnostics`. Deterministic.
MapPicture render_map(const xodr::Map& map, const RenderOptions& options,
                      corsa::Diagnostics& diagnostics);

/// PNG bytes of the picture.
std::string encode_png(const MapPicture& picture);
/// Writes the PNG atomically (corsa::AtomicFile); throws InputError on an I/O error.
void write_png(const MapPicture& picture, const std::filesystem::path& path);

}  // namespace corsa::render
