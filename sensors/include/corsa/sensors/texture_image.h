#pragma once

// A picture used as a surface texture: linear RGB with a box-filtered mip chain, read at
// texture coordinates with the level chosen from the pixel footprint (trilinear), so that
// distant textured surfaces average instead of aliasing.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "corsa/sensors/color.h"

namespace corsa::sensors {

class TextureImage {
 public:
  /// Reads an image file (PNG, JPEG, BMP, TGA, ... whatever OpenCV reads). Throws
  /// corsa::InputError naming the file when it is missing or cannot be decoded.
  static std::shared_ptr<const TextureImage> load(const std::filesystem::path& path);
  /// Decodes an image held in memory (a texture embedded in a GLB/FBX); `name` is for messages.
  static std::shared_ptr<const TextureImage> decode(std::span<const uint8_t> bytes,
                                                    const std::string& name);
  /// From 8-bit sRGB pixels, `channels` (3 or 4: RGB or RGBA; alpha is ignored) per pixel, rows
  /// top down.
  static std::shared_ptr<const TextureImage> from_srgb8(int width, int height, int channels,
                                                        std::span<const uint8_t> pixels,
                                                        std::string name);

  int width() const { return levels_.front().width; }
  int height() const { return levels_.front().height; }
  const std::string& name() const { return name_; }

  /// Linear colour at texture coordinates (u, v) (repeating; v = 0 at the bottom row, as
  /// glTF/OBJ give it after assimp's flip), `texels` the footprint of the pixel in texels of the
  /// full-size image (1 or less: the full-size level).
  Color sample(double u, double v, double texels) const;

 private:
  struct Level {
    int width = 0;
    int height = 0;
    std::vector<float> rgb;  ///< linear, row-major, rows top down
  };
  Color bilinear(const Level& level, double u, double v) const;
  std::vector<Level> levels_;
  std::string name_;
};

}  // namespace corsa::sensors
