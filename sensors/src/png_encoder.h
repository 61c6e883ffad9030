#pragma once

// PNG files (ISO/IEC 15948, the W3C PNG specification) encoded directly: signature, IHDR, one
// IDAT, IEND. Every row is stored with the Sub filter and the rows are deflated by libdeflate at a
// fast level. Lossless, so the pixels are exactly the input; the same input always gives the same
// bytes. Faster than OpenCV's libpng + zlib path at its own fastest setting, with smaller files
// (libdeflate's fast matcher finds more than zlib's level 1).

#include <cstdint>
#include <span>
#include <string>

namespace corsa::sensors::detail {

/// The pixel layouts the dataset writes.
enum class PngPixels {
  kRgb8,    ///< three bytes a pixel, R G B
  kGray8,   ///< one byte a pixel
  kGray16,  ///< one uint16_t a pixel in host order (stored big-endian, as PNG requires)
};

/// The bytes of a PNG file of `width` x `height` pixels read row after row from `pixels` (its
/// size must be width x height x the layout's bytes a pixel; the caller checks it).
std::string encode_png(int width, int height, PngPixels layout, std::span<const uint8_t> pixels);

}  // namespace corsa::sensors::detail
