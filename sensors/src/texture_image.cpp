#include "corsa/sensors/texture_image.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <iterator>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "corsa/core/diagnostic.h"

namespace corsa::sensors {
namespace {

// Textures larger than this are reduced when read: a 4k texture would cost 200 MB of float
// mips for detail no camera pixel resolves at driving distances.
constexpr int kMaxSize = 2048;

std::array<float, 256> srgb_table() {
  std::array<float, 256> t{};
  for (int i = 0; i < 256; ++i) {
    t[i] = static_cast<float>(linear_from_srgb8(static_cast<uint8_t>(i)));
  }
  return t;
}

double wrap01(double x) { return x - std::floor(x); }

}  // namespace

std::shared_ptr<const TextureImage> TextureImage::from_srgb8(int width, int height, int channels,
                                                             std::span<const uint8_t> pixels,
                                                             std::string name) {
  if (width <= 0 || height <= 0 || (channels != 3 && channels != 4) ||
      pixels.size() != static_cast<size_t>(width) * height * channels) {
    throw std::invalid_argument("texture '" + name + "': pixel data does not match its size");
  }
  auto image = std::shared_ptr<TextureImage>(new TextureImage());
  image->name_ = std::move(name);
  static const std::array<float, 256> table = srgb_table();
  Level base;
  base.width = width;
  base.height = height;
  base.rgb.resize(static_cast<size_t>(width) * height * 3);
  for (size_t i = 0; i < static_cast<size_t>(width) * height; ++i) {
    for (int k = 0; k < 3; ++k) {
      base.rgb[3 * i + k] = table[pixels[channels * i + k]];
    }
  }
  image->levels_.push_back(std::move(base));
  // Box-filtered mip chain: each level averages 2 x 2 texels of the one above (a lone odd
  // row or column is folded into its neighbour), down to 1 x 1.
  while (image->levels_.back().width > 1 || image->levels_.back().height > 1) {
    const Level& up = image->levels_.back();
    Level down;
    down.width = std::max(1, up.width / 2);
    down.height = std::max(1, up.height / 2);
    down.rgb.assign(static_cast<size_t>(down.width) * down.height * 3, 0.0f);
    for (int y = 0; y < up.height; ++y) {
      const int dy = std::min(y / 2, down.height - 1);
      for (int x = 0; x < up.width; ++x) {
        const int dx = std::min(x / 2, down.width - 1);
        for (int k = 0; k < 3; ++k) {
          down.rgb[3 * (static_cast<size_t>(dy) * down.width + dx) + k] +=
              up.rgb[3 * (static_cast<size_t>(y) * up.width + x) + k];
        }
      }
    }
    const float scale =
        static_cast<float>(down.width * down.height) / static_cast<float>(up.width * up.height);
    for (float& v : down.rgb) {
      v *= scale;
    }
    image->levels_.push_back(std::move(down));
  }
  return image;
}

std::shared_ptr<const TextureImage> TextureImage::decode(std::span<const uint8_t> bytes,
                                                         const std::string& name) {
  cv::Mat image;
  try {
    const cv::Mat raw(1, static_cast<int>(bytes.size()), CV_8UC1,
                      const_cast<uint8_t*>(bytes.data()));
    image = cv::imdecode(raw, cv::IMREAD_COLOR);
  } catch (const cv::Exception&) {
    image = cv::Mat();
  }
  if (image.empty()) {
    throw InputError(make_error(name, 0, "cannot decode the texture image"));
  }
  while (image.cols > kMaxSize || image.rows > kMaxSize) {
    cv::Mat half;
    cv::resize(image, half, cv::Size(std::max(1, image.cols / 2), std::max(1, image.rows / 2)), 0,
               0, cv::INTER_AREA);
    image = half;
  }
  cv::Mat rgb;
  cv::cvtColor(image, rgb, cv::COLOR_BGR2RGB);
  if (!rgb.isContinuous()) {
    rgb = rgb.clone();
  }
  return from_srgb8(rgb.cols, rgb.rows, 3,
                    std::span<const uint8_t>(rgb.data, static_cast<size_t>(rgb.total()) * 3), name);
}

std::shared_ptr<const TextureImage> TextureImage::load(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw InputError(make_error(path.string(), 0, "cannot open the texture image"));
  }
  const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)),
                                   std::istreambuf_iterator<char>());
  return decode(bytes, path.string());
}

Color TextureImage::bilinear(const Level& level, double u, double v) const {
  // Texel centres at (i + 0.5) / size; v = 0 is the bottom row.
  const double x = wrap01(u) * level.width - 0.5;
  const double y = (1.0 - wrap01(v)) * level.height - 0.5;
  const double fx = std::floor(x);
  const double fy = std::floor(y);
  const double ax = x - fx;
  const double ay = y - fy;
  auto wrap = [](int i, int n) { return ((i % n) + n) % n; };
  const int x0 = wrap(static_cast<int>(fx), level.width);
  const int x1 = wrap(static_cast<int>(fx) + 1, level.width);
  const int y0 = wrap(static_cast<int>(fy), level.height);
  const int y1 = wrap(static_cast<int>(fy) + 1, level.height);
  auto at = [&](int xi, int yi) {
    const float* p = &level.rgb[3 * (static_cast<size_t>(yi) * level.width + xi)];
    return Color{p[0], p[1], p[2]};
  };
  return mix(mix(at(x0, y0), at(x1, y0), ax), mix(at(x0, y1), at(x1, y1), ax), ay);
}

Color TextureImage::sample(double u, double v, double texels) const {
  if (!std::isfinite(u) || !std::isfinite(v)) {
    return bilinear(levels_.back(), 0.0, 0.0);
  }
  const double lod = texels > 1.0 ? std::log2(texels) : 0.0;
  const double top = static_cast<double>(levels_.size() - 1);
  const double level = std::min(lod, top);
  const auto l0 = static_cast<size_t>(level);
  const size_t l1 = std::min(l0 + 1, levels_.size() - 1);
  const double t = level - static_cast<double>(l0);
  const Color a = bilinear(levels_[l0], u, v);
  return t > 0.0 ? mix(a, bilinear(levels_[l1], u, v), t) : a;
}

}  // namespace corsa::sensors
