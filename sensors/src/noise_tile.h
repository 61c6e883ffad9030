#pragma once

// Prefiltered noise for the procedural textures: a tileable 256 x 256 texel field of four
// independent fractal (fBm) channels with a box-filtered mip chain. Reading it trilinearly at the
// pixel's footprint is the "mip-mapped" prefilter: a pixel covering many texels gets their
// average, never an aliased sample. Built once from fixed seeds (the same bytes everywhere).

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace corsa::sensors::detail {

/// 32-bit integer hash (a murmur3-style finaliser) of a 2D cell and a seed: the random value of
/// cell-based patterns (bricks, windows, plants), identical on every platform.
inline uint32_t cell_hash(int64_t x, int64_t y, uint32_t seed) {
  uint64_t h = static_cast<uint64_t>(x) * 0x9E3779B97F4A7C15ULL ^
               (static_cast<uint64_t>(y) + 0x632BE59BD9B4E019ULL) * 0xC2B2AE3D27D4EB4FULL ^
               (static_cast<uint64_t>(seed) << 17);
  h ^= h >> 33;
  h *= 0xFF51AFD7ED558CCDULL;
  h ^= h >> 33;
  h *= 0xC4CEB9FE1A85EC53ULL;
  h ^= h >> 33;
  return static_cast<uint32_t>(h);
}

/// The hash as a number in [0, 1).
inline double cell_random(int64_t x, int64_t y, uint32_t seed) {
  return cell_hash(x, y, seed) * (1.0 / 4294967296.0);
}

class NoiseTile {
 public:
  static constexpr int kSize = 256;
  /// The shared tile (built at first use; immutable afterwards). Inline: every texture read
  /// asks for it, and out of line the call cost more than the check.
  static const NoiseTile& instance() {
    static const NoiseTile tile;
    return tile;
  }

  /// The four channels (each about 0..1, mean 0.5) at texel coordinates (x, y) of the full-size
  /// level (the tile repeats every kSize texels), averaged over `texels` texels (the footprint
  /// of the pixel; <= 1 reads the full-size level).
  std::array<float, 4> sample(double x, double y, double texels) const;
  /// Channel `channel` (0..3) of sample(x, y, texels), the same value read without the others.
  float sample(int channel, double x, double y, double texels) const;
  /// Channel `channel` read bilinearly on the one level nearest the footprint (log2(texels)
  /// rounded), not blended between two: half the texel reads and no log2, with a visible step
  /// in the texture's sharpness where the level changes (the `fast` camera preset).
  float sample_one_level(int channel, double x, double y, double texels) const;

 private:
  NoiseTile();
  struct Level {
    int size = 0;
    std::vector<float> texels;  ///< 4 planes (channels) of size x size texels, row-major
  };
  /// The four texels around (x, y) (full-size texel units) on a level and the weights between
  /// them.
  struct Footprint {
    const float* texel[4];  ///< channel 0 of (x0, y0), (x1, y0), (x0, y1), (x1, y1)
    size_t plane = 0;       ///< from one channel to the next
    float ax = 0.0f, ay = 0.0f;
    float lerp(int k) const {
      const size_t o = static_cast<size_t>(k) * plane;
      const float top = texel[0][o] + (texel[1][o] - texel[0][o]) * ax;
      const float bottom = texel[2][o] + (texel[3][o] - texel[2][o]) * ax;
      return top + (bottom - top) * ay;
    }
  };
  Footprint footprint(const Level& level, double x, double y) const;
  std::array<float, 4> bilinear(const Level& level, double x, double y) const;
  float bilinear(const Level& level, double x, double y, int channel) const;
  std::vector<Level> levels_;
};

/// Average of one noise channel of `tile_m`-metre tiles around a surface point (u, v metres)
/// over a pixel footprint of `footprint_m` metres: the workhorse of the patterns. `one_level`:
/// read the nearest mip level only (NoiseTile::sample_one_level) instead of blending two.
inline float noise(int channel, double u, double v, double tile_m, double footprint_m,
                   bool one_level) {
  const double scale = NoiseTile::kSize / tile_m;
  const NoiseTile& tile = NoiseTile::instance();
  return one_level ? tile.sample_one_level(channel, u * scale, v * scale, footprint_m * scale)
                   : tile.sample(channel, u * scale, v * scale, footprint_m * scale);
}

/// Share of [x - w/2, x + w/2] covered by the pulses [k p, k p + d) (k integer): the box
/// filtered value of a periodic line pattern (joints, window rows), exact for any footprint w.
double filtered_pulse(double x, double period, double duty, double w);

}  // namespace corsa::sensors::detail
