// Image post-processing of the RGB camera: motion blur along per-pixel motion, metering (auto
// exposure), glare, and development: exposure, vignetting, sensor noise, the filmic tone curve
// and the display encoding.

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "corsa/core/random.h"
#include "fast_normal.h"
#include "scalar_math.h"
#include "shading.h"

namespace corsa::sensors::detail {

void motion_blur(std::vector<float>& linear, const std::vector<float>& motion, float scale,
                 int width, int height, std::vector<float>& scratch) {
  // The blurred image is written into `scratch` (pixels that do not move copied as they are)
  // and the two buffers swapped: no copy of the sharp image first.
  scratch.resize(linear.size());
  const std::vector<float>& sharp = linear;
  // Where sample s of n lies along the motion, as a share of it: the same doubles for every
  // pixel, computed once.
  constexpr int kMaxSamples = 16;
  double along[kMaxSamples + 1][kMaxSamples] = {};
  for (int n = 2; n <= kMaxSamples; ++n) {
    for (int s = 0; s < n; ++s) {
      along[n][s] = static_cast<double>(s) / (n - 1) - 0.5;
    }
  }
  tbb::parallel_for(tbb::blocked_range<int>(0, height), [&](const tbb::blocked_range<int>& r) {
    for (int row = r.begin(); row != r.end(); ++row) {
      for (int col = 0; col < width; ++col) {
        const size_t px = static_cast<size_t>(row) * width + col;
        const double mx = motion[2 * px] * scale;
        const double my = motion[2 * px + 1] * scale;
        const double length = std::sqrt(mx * mx + my * my);
        float* out = &scratch[3 * px];
        if (length < 0.5) {
          const float* v = &sharp[3 * px];
          out[0] = v[0];
          out[1] = v[1];
          out[2] = v[2];
          continue;
        }
        // One sample per pixel of motion, at most 16 (longer streaks are sampled more sparsely).
        const int samples = std::min(kMaxSamples, static_cast<int>(std::ceil(length)) + 1);
        double sum[3] = {0.0, 0.0, 0.0};
        for (int s = 0; s < samples; ++s) {
          const double f = along[samples][s];
          // Nearest pixel: clamp first, then round the non-negative coordinate by truncation.
          const int c = static_cast<int>(std::clamp(col + f * mx, 0.0, width - 1.0) + 0.5);
          const int q = static_cast<int>(std::clamp(row + f * my, 0.0, height - 1.0) + 0.5);
          const float* v = &sharp[3 * (static_cast<size_t>(q) * width + c)];
          sum[0] += v[0];
          sum[1] += v[1];
          sum[2] += v[2];
        }
        for (int k = 0; k < 3; ++k) {
          out[k] = static_cast<float>(sum[k] / samples);
        }
      }
    }
  });
  linear.swap(scratch);
}

namespace {

/// The auto-exposed camera gathers 64 times the light of the manual reference (ISO 100, 4 ms
/// and the aperture of the sunny-16 rule): a fixed f/2 lens, as automotive cameras have.
constexpr double kAutoAperture = 64.0;
constexpr double kMinShutter = 1.0 / 20000.0;
constexpr double kMaxShutter = 1.0 / 60.0;  // longer would smear the scene at driving speed
/// Automotive and machine-vision sensors (small pixels) stop at about 24 dB of gain over their
/// base sensitivity: 16 times ISO 100. Beyond it read noise buries the image, so at night the
/// camera runs out of exposure and the scene stays dark, as a dash camera's does.
constexpr double kMaxIso = 1600.0;

/// ACES filmic tone curve, Narkowicz's fit of the RRT + ODT ("ACES Filmic Tone Mapping Curve",
/// 2016): a toe, a linear middle and a soft shoulder into white.
double aces(double x) {
  x = std::max(x, 0.0);
  return std::clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
}

using ToneLanes = double __attribute__((vector_size(16)));

/// aces() of two values at once (the same operations on each: the same bits).
ToneLanes aces_lanes(ToneLanes x) {
  x = x < 0.0 ? 0.0 : x;  // std::max(x, 0.0)
  const ToneLanes y = (x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14);
  return y < 0.0 ? 0.0 : (1.0 < y ? 1.0 : y);  // std::clamp(y, 0.0, 1.0)
}

/// Highlights keep their hue: where a pixel's brightest channel passes white (the curve's 0.8),
/// its channels are compressed together by the curve of that brightest channel (their ratios
/// kept) instead of each by itself, which runs every channel of a warm shop window or a coloured
/// lamp's halo into the same white. Film and camera curves keep such colour a few stops above
/// white; far above it (5 to 10 stops: lamp filaments, the sun) the core burns out to white
/// again, as on a photograph, and so do highlights that are nearly white already.
constexpr double kHueKnee = 1.0;

/// The tone curve of one pixel: aces() of each channel below the knee; above it, blended
/// towards the same compression for all three channels. `v` is the exposed pixel, `a` its
/// channels through aces() (the curve of each channel alone), overwritten.
void keep_highlight_hue(const double v[3], double a[3]) {
  const double m = std::max({v[0], v[1], v[2]});
  if (m <= kHueKnee) {
    return;
  }
  // Near-white highlights (the warm sun glinting on white paint, a cool-white room) go to white
  // as before, as a camera balanced for the light shows them; coloured ones keep their hue.
  const double saturation = 1.0 - std::max(std::min({v[0], v[1], v[2]}), 0.0) / m;
  const double keep = smoothstep(kHueKnee, 4.0 * kHueKnee, m) *
                      (1.0 - smoothstep(5.0, 10.0, std::log2(m / kHueKnee))) *
                      smoothstep(0.15, 0.45, saturation);
  const double together = aces(m) / m;
  for (int k = 0; k < 3; ++k) {
    a[k] += (std::max(v[k], 0.0) * together - a[k]) * keep;
  }
}

/// One row of development without sensor noise: each value times its pixel's exposure and
/// vignetting `scale`, through the tone curve two at a time, encoded by `table` (as the loop of
/// develop() with noise, value for value); pixels past the knee again, a pixel at a time.
void develop_clean_row(const float* in, const double* scale, int width, const uint8_t* table,
                       uint8_t* out) {
  const int n = 3 * width;
  auto encode = [table](double a) { return table[static_cast<size_t>(a * 4096.0 + 0.5)]; };
  int i = 0;
  for (; i + 1 < n; i += 2) {
    const ToneLanes v{in[i] * scale[i / 3], in[i + 1] * scale[(i + 1) / 3]};
    const ToneLanes a = aces_lanes(v);
    out[i] = encode(a[0]);
    out[i + 1] = encode(a[1]);
  }
  for (; i < n; ++i) {
    out[i] = encode(aces(in[i] * scale[i / 3]));
  }
  for (int col = 0; col < width; ++col) {
    const float* p = in + 3 * col;
    const double s = scale[col];
    const double v[3] = {p[0] * s, p[1] * s, p[2] * s};
    if (v[0] <= kHueKnee && v[1] <= kHueKnee && v[2] <= kHueKnee) {
      continue;
    }
    double a[3] = {aces(v[0]), aces(v[1]), aces(v[2])};
    keep_highlight_hue(v, a);
    for (int k = 0; k < 3; ++k) {
      out[3 * col + k] = encode(a[k]);
    }
  }
}

/// Log-average luminance of the frame (Reinhard et al., "Photographic Tone Reproduction for
/// Digital Images", SIGGRAPH 2002) over a 4-pixel grid, centre-weighted, leaving out the
/// brightest and darkest 2% (lamps, the sun, black holes) by a histogram of log2 luminance.
double metered_luminance(const std::vector<float>& linear, int width, int height) {
  constexpr int kBins = 512;
  constexpr double kLo = -28.0, kHi = 8.0;  // log2 range
  std::vector<double> weight(kBins, 0.0);
  double total = 0.0;
  for (int row = 2; row < height; row += 4) {
    for (int col = 2; col < width; col += 4) {
      const float* v = &linear[3 * (static_cast<size_t>(row) * width + col)];
      const double y = 0.2126 * v[0] + 0.7152 * v[1] + 0.0722 * v[2];
      const double u = (2.0 * col - width) / width;
      const double q = (2.0 * row - height) / height;
      const double w = 1.0 + std::max(0.0, 1.0 - 0.5 * (u * u + q * q));
      const double l = std::clamp(std::log2(std::max(y, 1e-12)), kLo, kHi - 1e-9);
      weight[static_cast<size_t>((l - kLo) / (kHi - kLo) * kBins)] += w;
      total += w;
    }
  }
  if (total <= 0.0) {
    return 0.18;
  }
  double below = 0.0, sum = 0.0, used = 0.0;
  for (int b = 0; b < kBins; ++b) {
    const double lo = std::max(below, 0.02 * total);
    const double hi = std::min(below + weight[b], 0.98 * total);
    if (hi > lo) {
      sum += (hi - lo) * (kLo + (b + 0.5) * (kHi - kLo) / kBins);
      used += hi - lo;
    }
    below += weight[b];
  }
  return used > 0.0 ? std::exp2(sum / used) : 0.18;
}

}  // namespace

double exposure_key(double scene_cd_m2) {
  // Down to dusk (30 cd/m^2 of log-average scene luminance) the camera adapts fully and gives
  // the average the photographic 0.18. Below it adapts only partly: its exposure grows as the
  // square root of the light lost, so a scene 100 times darker shows 10 times darker. Night
  // photographs are exposed so (the exposure tables of ANSI PH2.7-1986 put street scenes at
  // night at EV100 5-8, two to four stops short of full adaptation); this puts the demo street
  // at 22:00, lit by street lamps (log average 0.4 cd/m^2), at EV100 5.3.
  constexpr double kFullAdaptation = 30.0;  // cd/m^2
  return std::clamp(0.18 * std::sqrt(std::max(scene_cd_m2, 0.0) / kFullAdaptation), 0.005, 0.18);
}

Exposure choose_exposure(const std::vector<float>& linear, int width, int height,
                         const RgbOptions& o) {
  Exposure e;
  const double ev = std::pow(2.0, o.exposure_compensation_ev);
  if (!o.auto_exposure) {
    // Manual: ISO 100 at 1/250 s puts a sunlit 18% grey at 0.18 before the tone curve.
    e.shutter_s = o.shutter_speed_s;
    e.iso = o.iso;
    e.scale = (o.iso / 100.0) * (o.shutter_speed_s / 0.004) * ev;
    return e;
  }
  const double average = metered_luminance(linear, width, height);
  const double key = exposure_key(average * kNitsPerUnit);
  const double wanted = key / std::max(average, 1e-12) * ev;
  // Exposure time first, then gain, within the camera's limits.
  const double per_second = kAutoAperture / 0.004;  // scale per second at ISO 100
  e.shutter_s = std::clamp(wanted / per_second, kMinShutter, kMaxShutter);
  e.iso = std::clamp(100.0 * wanted / (per_second * e.shutter_s), 100.0, kMaxIso);
  e.scale = per_second * e.shutter_s * (e.iso / 100.0);
  return e;
}

void bloom(std::vector<float>& linear, int width, int height, double threshold) {
  // The light above the threshold, averaged over 4x4 blocks, blurred (Gaussian, sigma 3
  // blocks) and added back with a weight of 1%: the glare of lamps and the sun in a lens. A
  // pixel gives at most kCap thresholds of light: the glare of a lamp far brighter than the
  // exposure is a faint halo, not a disc of white tens of pixels wide (real lenses spread most
  // of such light much wider and fainter than this kernel does).
  constexpr double kCap = 2.0;
  const int bw = (width + 3) / 4;
  const int bh = (height + 3) / 4;
  std::vector<float> bright(3 * static_cast<size_t>(bw) * bh, 0.0f);
  bool any = false;
  for (int row = 0; row < height; ++row) {
    for (int col = 0; col < width; ++col) {
      const float* v = &linear[3 * (static_cast<size_t>(row) * width + col)];
      const double y = 0.2126 * v[0] + 0.7152 * v[1] + 0.0722 * v[2];
      if (y <= threshold) {
        continue;
      }
      any = true;
      const double keep = (std::min(y, kCap * threshold) - threshold) / y / 16.0;
      float* b = &bright[3 * (static_cast<size_t>(row / 4) * bw + col / 4)];
      for (int k = 0; k < 3; ++k) {
        b[k] += static_cast<float>(v[k] * keep);
      }
    }
  }
  if (!any) {
    return;
  }
  constexpr int kRadius = 9;
  float kernel[2 * kRadius + 1];
  float ksum = 0.0f;
  for (int i = -kRadius; i <= kRadius; ++i) {
    kernel[i + kRadius] = static_cast<float>(std::exp(-i * i / (2.0 * 3.0 * 3.0)));
    ksum += kernel[i + kRadius];
  }
  for (float& k : kernel) {
    k /= ksum;
  }
  std::vector<float> tmp(bright.size(), 0.0f);
  for (int pass = 0; pass < 2; ++pass) {
    const std::vector<float>& src = pass == 0 ? bright : tmp;
    std::vector<float>& dst = pass == 0 ? tmp : bright;
    std::vector<float> next(src.size(), 0.0f);
    for (int r = 0; r < bh; ++r) {
      for (int c = 0; c < bw; ++c) {
        float acc[3] = {0, 0, 0};
        for (int i = -kRadius; i <= kRadius; ++i) {
          const int cc = pass == 0 ? std::clamp(c + i, 0, bw - 1) : c;
          const int rr = pass == 0 ? r : std::clamp(r + i, 0, bh - 1);
          const float* s = &src[3 * (static_cast<size_t>(rr) * bw + cc)];
          for (int k = 0; k < 3; ++k) {
            acc[k] += kernel[i + kRadius] * s[k];
          }
        }
        for (int k = 0; k < 3; ++k) {
          next[3 * (static_cast<size_t>(r) * bw + c) + k] = acc[k];
        }
      }
    }
    dst = std::move(next);
  }
  tbb::parallel_for(tbb::blocked_range<int>(0, height), [&](const tbb::blocked_range<int>& r) {
    for (int row = r.begin(); row != r.end(); ++row) {
      const double fy = std::clamp((row + 0.5) / 4.0 - 0.5, 0.0, bh - 1.0);
      const int y0 = static_cast<int>(fy);
      const int y1 = std::min(y0 + 1, bh - 1);
      const double ty = fy - y0;
      for (int col = 0; col < width; ++col) {
        const double fx = std::clamp((col + 0.5) / 4.0 - 0.5, 0.0, bw - 1.0);
        const int x0 = static_cast<int>(fx);
        const int x1 = std::min(x0 + 1, bw - 1);
        const double tx = fx - x0;
        float* v = &linear[3 * (static_cast<size_t>(row) * width + col)];
        for (int k = 0; k < 3; ++k) {
          auto at = [&](int x, int y) { return bright[3 * (static_cast<size_t>(y) * bw + x) + k]; };
          const double top = at(x0, y0) * (1.0 - tx) + at(x1, y0) * tx;
          const double bottom = at(x0, y1) * (1.0 - tx) + at(x1, y1) * tx;
          v[k] += static_cast<float>(0.01 * 16.0 * (top * (1.0 - ty) + bottom * ty));
        }
      }
    }
  });
}

std::vector<uint8_t> develop(const std::vector<float>& linear, int width, int height,
                             const RgbOptions& o, const Exposure& exposure, uint64_t frame_seed) {
  // Noise left in the camera's output after its own noise reduction, which works harder the
  // higher the gain: photon (shot) noise variance per unit signal and read noise standard
  // deviation both grow as the square root of the gain rather than with the gain itself, so that
  // a night frame at ISO 1600 is grainy but not buried in noise.
  const double gain = std::sqrt(exposure.iso / 100.0);
  const double shot = 0.0004 * gain;
  const double read = 0.0004 * gain;
  const double inv_gamma = 1.0 / o.gamma;
  // Encoding through a 4096-entry table keeps pow() out of the per-pixel loop.
  std::vector<uint8_t> table(4097);
  for (int i = 0; i <= 4096; ++i) {
    table[i] = static_cast<uint8_t>(std::lround(255.0 * std::pow(i / 4096.0, inv_gamma)));
  }
  // Vignetting: 1 - v at the corners, easing in from the centre as (1 - rho^2)^2 does.
  const double cx = 0.5 * (width - 1), cy = 0.5 * (height - 1);
  const double corner2 = cx * cx + cy * cy;
  std::vector<uint8_t> out(linear.size());
  tbb::parallel_for(tbb::blocked_range<int>(0, height), [&](const tbb::blocked_range<int>& r) {
    std::vector<double> scales(width);
    for (int row = r.begin(); row != r.end(); ++row) {
      const double dy = row - cy;
      for (int col = 0; col < width; ++col) {
        const double dx = col - cx;
        const double rho2 = corner2 > 0.0 ? (dx * dx + dy * dy) / corner2 : 0.0;
        const double fall = (1.0 - rho2) * (1.0 - rho2);
        scales[col] = exposure.scale * (1.0 - o.vignetting + o.vignetting * fall);
      }
      const size_t first = 3 * static_cast<size_t>(row) * width;
      if (!o.noise) {
        develop_clean_row(linear.data() + first, scales.data(), width, table.data(),
                          out.data() + first);
        continue;
      }
      RandomStream rng(block_seed(frame_seed ^ 0x6e6f697365ULL, static_cast<uint64_t>(row)));
      for (int col = 0; col < width; ++col) {
        const double scale = scales[col];
        const size_t i0 = first + 3 * static_cast<size_t>(col);
        double v[3], a[3];
        for (int k = 0; k < 3; ++k) {
          v[k] = linear[i0 + k] * scale;
          // Irwin-Hall: the sum of four 16-bit uniforms, rescaled, is close to a unit normal
          // and costs one 64-bit draw (image noise need not be exactly Gaussian).
          // (Summed as integers: below 2^18, every partial sum is exact in a double too.)
          const uint64_t bits = rng.next_u64();
          const double s = static_cast<double>((bits & 0xFFFF) + ((bits >> 16) & 0xFFFF) +
                                               ((bits >> 32) & 0xFFFF) + (bits >> 48));
          const double z = (s / 65536.0 - 2.0) * std::sqrt(3.0);
          v[k] += z * std::sqrt(std::max(0.0, v[k]) * shot + read * read);
          a[k] = aces(v[k]);
        }
        keep_highlight_hue(v, a);
        for (int k = 0; k < 3; ++k) {
          out[i0 + k] = table[static_cast<size_t>(a[k] * 4096.0 + 0.5)];
        }
      }
    }
  });
  return out;
}

}  // namespace corsa::sensors::detail
