// PNG encoding and decoding with libdeflate (see png_codec.h).

#include "png_codec.h"

#include <libdeflate.h>

#include <algorithm>
#include <cstdlib>
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

uint32_t get_be32(const uint8_t* p) {
  return uint32_t{p[0]} << 24 | uint32_t{p[1]} << 16 | uint32_t{p[2]} << 8 | uint32_t{p[3]};
}

// The PNG predictor of §9.4: the one of a (left), b (up), c (up-left) nearest to a + b - c.
uint8_t paeth(uint8_t a, uint8_t b, uint8_t c) {
  const int p = int{a} + int{b} - int{c};
  const int pa = std::abs(p - int{a});
  const int pb = std::abs(p - int{b});
  const int pc = std::abs(p - int{c});
  return pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
}

// Undoes the filters of §9.2 in place on rows of `row_bytes` bytes (after each row's type byte),
// `bpp` bytes a pixel; false on an unknown filter type.
bool unfilter_rows(uint8_t* data, size_t row_bytes, size_t rows, size_t bpp) {
  const uint8_t* previous = nullptr;
  for (size_t y = 0; y < rows; ++y) {
    const uint8_t type = data[y * (row_bytes + 1)];
    uint8_t* row = data + y * (row_bytes + 1) + 1;
    switch (type) {
      case 0:
        break;
      case 1:
        for (size_t i = bpp; i < row_bytes; ++i) {
          row[i] = static_cast<uint8_t>(row[i] + row[i - bpp]);
        }
        break;
      case 2:
        for (size_t i = 0; previous != nullptr && i < row_bytes; ++i) {
          row[i] = static_cast<uint8_t>(row[i] + previous[i]);
        }
        break;
      case 3:
        for (size_t i = 0; i < row_bytes; ++i) {
          const int left = i >= bpp ? row[i - bpp] : 0;
          const int up = previous != nullptr ? previous[i] : 0;
          row[i] = static_cast<uint8_t>(row[i] + (left + up) / 2);
        }
        break;
      case 4:
        for (size_t i = 0; i < row_bytes; ++i) {
          const uint8_t left = i >= bpp ? row[i - bpp] : 0;
          const uint8_t up = previous != nullptr ? previous[i] : 0;
          const uint8_t up_left = i >= bpp && previous != nullptr ? previous[i - bpp] : 0;
          row[i] = static_cast<uint8_t>(row[i] + paeth(left, up, up_left));
        }
        break;
      default:
        return false;
    }
    previous = row;
  }
  return true;
}

struct DeflateDecompressorDeleter {
  void operator()(libdeflate_decompressor* d) const { libdeflate_free_decompressor(d); }
};

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

std::optional<cv::Mat> decode_png_rgb8(std::string_view file) {
  const auto* bytes = reinterpret_cast<const uint8_t*>(file.data());
  if (file.size() < 8 + 25 || file.substr(0, 8) != std::string_view("\x89PNG\r\n\x1a\n", 8)) {
    return std::nullopt;
  }
  size_t width = 0;
  size_t height = 0;
  std::vector<uint8_t> deflated;
  bool ended = false;
  for (size_t at = 8; at + 12 <= file.size() && !ended;) {
    const size_t size = get_be32(bytes + at);
    if (size > file.size() - at - 12) {
      return std::nullopt;
    }
    const std::string_view type = file.substr(at + 4, 4);
    const uint8_t* data = bytes + at + 8;
    if (libdeflate_crc32(0, bytes + at + 4, size + 4) != get_be32(data + size)) {
      return std::nullopt;
    }
    if (type == "IHDR") {
      // 8-bit truecolour, deflate, adaptive filters, no interlace: the files encode_png writes.
      if (size != 13 || data[8] != 8 || data[9] != 2 || data[10] != 0 || data[11] != 0 ||
          data[12] != 0) {
        return std::nullopt;
      }
      width = get_be32(data);
      height = get_be32(data + 4);
    } else if (type == "IDAT") {
      deflated.insert(deflated.end(), data, data + size);
    } else if (type == "IEND") {
      ended = true;
    }
    at += 12 + size;
  }
  constexpr size_t kMaxSide = 1 << 16;  // far beyond any camera; keeps the sizes below in range
  if (!ended || width == 0 || height == 0 || width > kMaxSide || height > kMaxSide) {
    return std::nullopt;
  }
  const size_t row_bytes = 3 * width;
  std::vector<uint8_t> filtered((row_bytes + 1) * height);
  const std::unique_ptr<libdeflate_decompressor, DeflateDecompressorDeleter> decompressor(
      libdeflate_alloc_decompressor());
  if (!decompressor) {
    throw std::bad_alloc();
  }
  // Without an "actual size" out-parameter libdeflate succeeds only when the data fills the
  // buffer exactly, and it checks the zlib stream's Adler-32.
  if (libdeflate_zlib_decompress(decompressor.get(), deflated.data(), deflated.size(),
                                 filtered.data(), filtered.size(), nullptr) != LIBDEFLATE_SUCCESS ||
      !unfilter_rows(filtered.data(), row_bytes, height, 3)) {
    return std::nullopt;
  }
  cv::Mat bgr(static_cast<int>(height), static_cast<int>(width), CV_8UC3);
  for (size_t y = 0; y < height; ++y) {
    const uint8_t* rgb = filtered.data() + y * (row_bytes + 1) + 1;
    uint8_t* out = bgr.ptr<uint8_t>(static_cast<int>(y));
    for (size_t x = 0; x < width; ++x) {
      out[3 * x] = rgb[3 * x + 2];
      out[3 * x + 1] = rgb[3 * x + 1];
      out[3 * x + 2] = rgb[3 * x];
    }
  }
  return bgr;
}

}  // namespace corsa::sensors::detail
