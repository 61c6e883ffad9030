// PNG encoding with libdeflate (see png_encoder.h).

#include "png_encoder.h"

#include <libdeflate.h>

#include <algorithm>
#include <cstring>
#include <memory>
#include <new>
#include <vector>

namespace corsa::sensors::detail {
namespace {

// libdeflate's level 1: on the dataset's images (camera frames with sensor noise, class and
// instance images, depth in millimetres) it takes well under the CPU of zlib's level 1 and gives
// smaller files; higher levels save a few per cent of size for several times the CPU.
constexpr int kPngDeflateLevel = 1;

void put_be32(std::string& out, uint32_t v) {
  const char bytes[4] = {static_cast<char>(v >> 24), static_cast<char>(v >> 16),
                         static_cast<char>(v >> 8), static_cast<char>(v)};
  out.append(bytes, 4);
}

// A chunk: length, type, data, CRC-32 of type and data (PNG specification §5.3).
void put_chunk(std::string& out, const char type[4], const uint8_t* data, size_t size) {
  put_be32(out, static_cast<uint32_t>(size));
  const size_t type_at = out.size();
  out.append(type, 4);
  if (size > 0) {
    out.append(reinterpret_cast<const char*>(data), size);
  }
  const uint32_t crc = libdeflate_crc32(0, out.data() + type_at, size + 4);
  put_be32(out, crc);
}

// The filtered image data (§7.3, §9): each row is its filter type byte (1, Sub) and then each
// byte minus the byte one pixel to its left (modulo 256; the first pixel is kept). 16-bit samples
// are laid out big-endian first, so the Sub differences are of the stored bytes.
std::vector<uint8_t> sub_filtered_rows(int width, int height, PngPixels layout,
                                       std::span<const uint8_t> pixels) {
  const size_t bytes_per_pixel = layout == PngPixels::kRgb8     ? 3
                                 : layout == PngPixels::kGray16 ? 2
                                                                : 1;
  const size_t row_bytes = static_cast<size_t>(width) * bytes_per_pixel;
  std::vector<uint8_t> out((row_bytes + 1) * static_cast<size_t>(height));
  std::vector<uint8_t> swapped(layout == PngPixels::kGray16 ? row_bytes : 0);
  for (size_t y = 0; y < static_cast<size_t>(height); ++y) {
    const uint8_t* row = pixels.data() + y * row_bytes;
    if (layout == PngPixels::kGray16) {
      for (size_t i = 0; i < row_bytes; i += 2) {
        swapped[i] = row[i + 1];
        swapped[i + 1] = row[i];
      }
      row = swapped.data();
    }
    uint8_t* filtered = out.data() + y * (row_bytes + 1);
    filtered[0] = 1;  // Sub
    std::memcpy(filtered + 1, row, bytes_per_pixel);
    for (size_t i = bytes_per_pixel; i < row_bytes; ++i) {
      filtered[1 + i] = static_cast<uint8_t>(row[i] - row[i - bytes_per_pixel]);
    }
  }
  return out;
}

struct DeflateCompressorDeleter {
  void operator()(libdeflate_compressor* c) const { libdeflate_free_compressor(c); }
};

}  // namespace

std::string encode_png(int width, int height, PngPixels layout, std::span<const uint8_t> pixels) {
  const std::vector<uint8_t> filtered = sub_filtered_rows(width, height, layout, pixels);
  const std::unique_ptr<libdeflate_compressor, DeflateCompressorDeleter> compressor(
      libdeflate_alloc_compressor(kPngDeflateLevel));
  if (!compressor) {
    throw std::bad_alloc();
  }
  std::vector<uint8_t> deflated(libdeflate_zlib_compress_bound(compressor.get(), filtered.size()));
  const size_t deflated_size = libdeflate_zlib_compress(
      compressor.get(), filtered.data(), filtered.size(), deflated.data(), deflated.size());
  if (deflated_size == 0) {  // cannot happen with a buffer of the bound's size
    throw std::bad_alloc();
  }

  // IHDR (§11.2.2): width, height, bit depth, colour type (0 greyscale, 2 truecolour),
  // compression 0 (deflate), filter method 0 (adaptive, per-row types), no interlace.
  std::string header;
  put_be32(header, static_cast<uint32_t>(width));
  put_be32(header, static_cast<uint32_t>(height));
  header.push_back(static_cast<char>(layout == PngPixels::kGray16 ? 16 : 8));
  header.push_back(static_cast<char>(layout == PngPixels::kRgb8 ? 2 : 0));
  header.append(3, '\0');

  std::string out;
  out.reserve(8 + 25 + 12 + deflated_size + 12);
  out.append("\x89PNG\r\n\x1a\n", 8);
  put_chunk(out, "IHDR", reinterpret_cast<const uint8_t*>(header.data()), header.size());
  // A chunk's length is at most 2^31 - 1 (§5.3); the data may be split over consecutive IDATs.
  constexpr size_t kMaxIdat = size_t{1} << 30;
  for (size_t at = 0; at < deflated_size; at += kMaxIdat) {
    put_chunk(out, "IDAT", deflated.data() + at, std::min(kMaxIdat, deflated_size - at));
  }
  put_chunk(out, "IEND", nullptr, 0);
  return out;
}

}  // namespace corsa::sensors::detail
