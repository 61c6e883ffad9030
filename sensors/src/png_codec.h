#pragma once

// PNG files (ISO/IEC 15948, the W3C PNG specification) encoded and decoded directly with
// libdeflate. Encoding writes signature, IHDR, one IDAT, IEND; every row is stored with the Sub
// filter and deflated at libdeflate's level 1. Lossless, so the pixels are exactly the input; the
// same input always gives the same bytes. On the dataset's images it takes less CPU than OpenCV's
// libpng + zlib path at its fastest setting (about the same on a noisy camera frame) and writes
// smaller files (except the noisy camera frames, about 4% larger). Decoding reads the 8-bit RGB
// files the preview needs (any filter, any split of IDAT chunks) and leaves the rest to OpenCV.

#include <cstdint>
#include <opencv2/core.hpp>
#include <optional>
#include <span>
#include <string>
#include <string_view>

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

/// The pixels of an 8-bit RGB, non-interlaced PNG file as an OpenCV BGR image; nullopt for any
/// other kind of PNG, or for bytes that are not a valid PNG (bad chunk CRC, bad deflate data or
/// checksum, wrong data size): the caller then reads the file with OpenCV, which says why.
std::optional<cv::Mat> decode_png_rgb8(std::string_view file);

}  // namespace corsa::sensors::detail
