#include <cmath>
#include <cstdlib>
#include <mutex>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>

#include "corsa/core/atomic_file.h"
#include "corsa/core/diagnostic.h"
#include "corsa/sensors/semantic.h"
#include "corsa/sensors/writers.h"
#include "png_codec.h"

namespace corsa::sensors {
namespace {

void check_size(const std::filesystem::path& path, int width, int height, size_t have,
                size_t per_pixel) {
  if (width <= 0 || height <= 0 ||
      have != static_cast<size_t>(width) * static_cast<size_t>(height) * per_pixel) {
    throw std::invalid_argument("image data for " + path.string() + " does not match its size");
  }
}

void encode_and_write(const std::filesystem::path& path, const char* ext, const cv::Mat& image,
                      const std::vector<int>& params) {
  std::vector<uchar> bytes;
  bool ok = false;
  std::string why;
  try {
    ok = cv::imencode(ext, image, bytes, params);
  } catch (const cv::Exception& error) {
    why = error.what();
  }
  if (!ok || bytes.empty()) {
    throw InputError(make_error(path.string(), 0,
                                std::string("cannot encode the image as ") + ext +
                                    (why.empty() ? std::string() : ": " + why)));
  }
  write_file_atomic(
      path, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()), true);
}

void write_dataset_png(const std::filesystem::path& path, int width, int height,
                       detail::PngPixels layout, std::span<const uint8_t> pixels) {
  write_file_atomic(path, detail::encode_png(width, height, layout, pixels), true);
}

}  // namespace

void write_png_rgb8(const std::filesystem::path& path, int width, int height,
                    std::span<const uint8_t> rgb) {
  check_size(path, width, height, rgb.size(), 3);
  write_dataset_png(path, width, height, detail::PngPixels::kRgb8, rgb);
}

void write_png_gray8(const std::filesystem::path& path, int width, int height,
                     std::span<const uint8_t> values) {
  check_size(path, width, height, values.size(), 1);
  write_dataset_png(path, width, height, detail::PngPixels::kGray8, values);
}

void write_png_gray16(const std::filesystem::path& path, int width, int height,
                      std::span<const uint16_t> values) {
  check_size(path, width, height, values.size(), 1);
  write_dataset_png(path, width, height, detail::PngPixels::kGray16,
                    {reinterpret_cast<const uint8_t*>(values.data()), values.size() * 2});
}

void write_exr_float(const std::filesystem::path& path, int width, int height,
                     std::span<const float> values) {
  check_size(path, width, height, values.size(), 1);
  // See writers.h: OpenCV reads OPENCV_IO_ENABLE_OPENEXR once, at its first EXR operation.
  static std::once_flag enable_exr;
  std::call_once(enable_exr, [] { setenv("OPENCV_IO_ENABLE_OPENEXR", "1", 1); });
  const cv::Mat image(height, width, CV_32FC1, const_cast<float*>(values.data()));
  // Run-length compression, lossless: OpenEXR's default ZIP costs ~10x the CPU (about 90 ms for
  // a 1280x720 frame) to save a third of a file whose float mantissas hardly compress; RLE still
  // packs the runs of zeros (sky, beyond maxRange).
  encode_and_write(path, ".exr", image,
                   {cv::IMWRITE_EXR_TYPE, cv::IMWRITE_EXR_TYPE_FLOAT, cv::IMWRITE_EXR_COMPRESSION,
                    cv::IMWRITE_EXR_COMPRESSION_RLE});
}

std::vector<uint16_t> depth_to_millimetres(std::span<const float> depth_m) {
  std::vector<uint16_t> out(depth_m.size());
  for (size_t i = 0; i < depth_m.size(); ++i) {
    const double mm = std::round(static_cast<double>(depth_m[i]) * 1000.0);
    out[i] = mm > 0.0 && mm <= 65535.0 ? static_cast<uint16_t>(mm) : 0;
  }
  return out;
}

std::vector<uint16_t> instance_to_u16(std::span<const uint32_t> ids) {
  std::vector<uint16_t> out(ids.size());
  for (size_t i = 0; i < ids.size(); ++i) {
    out[i] = static_cast<uint16_t>(std::min<uint32_t>(ids[i], 65535u));
  }
  return out;
}

std::vector<uint8_t> colorize_semantic(std::span<const uint8_t> classes) {
  std::vector<uint8_t> out(classes.size() * 3);
  for (size_t i = 0; i < classes.size(); ++i) {
    const Rgb8 c = semantic_color(static_cast<SemanticClass>(classes[i]));
    out[3 * i] = c.r;
    out[3 * i + 1] = c.g;
    out[3 * i + 2] = c.b;
  }
  return out;
}

}  // namespace corsa::sensors
