// Early returns from fog, rain and snow (lidar_weather.h).

#include "lidar_weather.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

#include "corsa/core/det_math.h"
#include "corsa/sensors/environment.h"
#include "scalar_math.h"

namespace corsa::sensors::detail {
namespace {

constexpr double kPulseLength = 299792458.0 * 20e-9;  // c tau_H, m (tau_H = 20 ns)
constexpr double kOverlapStart = 1.5;                 // r1, m
constexpr double kOverlapFull = 5.0;                  // r2, m
constexpr double kBeamDivergence = 3e-3;              // rad: the beam is 3 mm wide per metre
constexpr double kThresholdReflectance = 0.9;         // P_min = 0.9 / range^2
constexpr double kWaterReflectance = 0.0201;          // ((1.328 - 1) / (1.328 + 1))^2
constexpr double kSnowReflectance = 0.8;
constexpr double kStep = 0.02;      // m, integration and search grid of the fog echo
constexpr double kFogTable = 0.05;  // m, target ranges of the fog table
constexpr double kBin = 0.05;       // m, particle table

// x^p from IEEE basic operations (corsa::det), so that the tables are the same bits everywhere.
double power(double x, double p) { return det::exp(p * det::log(x)); }

double overlap(double r) {
  return std::clamp((r - kOverlapStart) / (kOverlapFull - kOverlapStart), 0.0, 1.0);
}

// pi beta Int sin^2(pi (R - r) / (c tau_H)) xi(r) e^(-2 alpha r) / r^2 dr over the pulse, for
// scatterers nearer than `target` (trapezoid rule on the kStep grid of `f`, f[i] = xi e / r^2 at
// i kStep).
double soft_power(const std::vector<double>& f, double beta, double echo, double target) {
  const double from = std::max(echo - kPulseLength, 0.0);
  const double to = std::min(echo, target);
  if (to <= from) {
    return 0.0;
  }
  const auto first = static_cast<size_t>(std::ceil(from / kStep));
  const auto last = std::min(static_cast<size_t>(std::floor(to / kStep)), f.size() - 1);
  double sum = 0.0;
  for (size_t i = first; i <= last; ++i) {
    const double r = static_cast<double>(i) * kStep;
    const double w = det::sin(kPi * (echo - r) / kPulseLength);
    const double weight = (i == first || i == last) ? 0.5 : 1.0;
    sum += weight * w * w * f[i];
  }
  return kPi * beta * sum * kStep;
}

// The strongest echo over the echo ranges, reported at the pulse's peak (R - c tau_H / 2).
WeatherReturn strongest_echo(const std::vector<double>& f, double beta, double target,
                             double last_echo) {
  WeatherReturn best;
  for (double echo = kOverlapStart; echo <= last_echo; echo += kStep) {
    const double p = soft_power(f, beta, echo, target);
    if (p > best.power) {
      best.power = p;
      best.range = std::max(echo - 0.5 * kPulseLength, kOverlapStart);
    }
  }
  return best;
}

}  // namespace

LidarWeatherModel::LidarWeatherModel(const LidarWeather& weather, double max_range)
    : weather_(weather) {
  alpha_ = weather.fog_extinction + rain_extinction(weather.rain_rate) +
           snow_extinction(weather.snow_rate);
  threshold_ = kThresholdReflectance / (max_range * max_range);
  if (weather.fog_extinction > 0.0) {
    // beta = 0.046 / MOR with MOR = ln(20) / alpha_fog.
    const double beta = 0.046 * weather.fog_extinction / det::log(20.0);
    const double reach = std::min(max_range, 40.0);
    std::vector<double> f(static_cast<size_t>(reach / kStep) + 1);
    for (size_t i = 1; i < f.size(); ++i) {
      const double r = static_cast<double>(i) * kStep;
      f[i] = overlap(r) * det::exp(-2.0 * alpha_ * r) / (r * r);
    }
    const double last_echo = reach;
    fog_free_ = strongest_echo(f, beta, 1e30, last_echo);
    // A target nearer than the free echo's range R* cuts the echo short; beyond R* (+ half a
    // pulse, where the reported range stands) it changes nothing.
    fog_saturation_ = fog_free_.range + kPulseLength;
    for (double target = 0.0; target < fog_saturation_; target += kFogTable) {
      fog_table_.push_back(
          strongest_echo(f, beta, target, std::min(last_echo, target + kPulseLength)));
    }
  }
  const bool rain = weather.rain_rate > 0.0;
  if (rain || weather.snow_rate > 0.0) {
    const double rate = rain ? weather.rain_rate : weather.snow_rate;
    const double n0 = rain ? 8000.0 : 3800.0 * power(rate, -0.87);             // 1/(m^3 mm)
    size_rate_ = rain ? 4.1 * power(rate, -0.21) : 2.55 * power(rate, -0.48);  // 1/mm
    reflectance_ = rain ? kWaterReflectance : kSnowReflectance;
    // rho_w / C3 in 1/mm: (1000 kg/m^3 / C3) / (1000 mm/m).
    flake_swell_ = rain ? 0.0 : 1.0 / kDrySnowDensityDiameter;
    // Detectable particles per metre of beam at range r: the beam's cross-section times the
    // number density of particles of at least the diameter that reaches the threshold there.
    auto rate_at = [&](double r) {
      const double beam_mm = 1e3 * kBeamDivergence * r;
      const double seen = reflectance_ * overlap(r);
      if (seen <= 0.0) {
        return std::pair{0.0, melted_diameter(beam_mm)};
      }
      const double need = threshold_ * r * r * det::exp(2.0 * alpha_ * r) / seen;
      const double seen_min = beam_mm * std::sqrt(need);  // mm; >= beam: nothing is enough
      if (!(seen_min < beam_mm)) {
        return std::pair{0.0, melted_diameter(beam_mm)};
      }
      const double d_min = melted_diameter(seen_min);
      const double beam_area = kPi * 0.25 * (beam_mm * 1e-3) * (beam_mm * 1e-3);  // m^2
      return std::pair{beam_area * (n0 / size_rate_) * det::exp(-size_rate_ * d_min), d_min};
    };
    // first_cdf_[k]: probability that the first detectable particle lies before r1 + k kBin.
    double expected = 0.0;  // particles met so far
    double previous = rate_at(kOverlapStart).first;
    first_cdf_.push_back(0.0);
    min_diameter_.push_back(rate_at(kOverlapStart).second);
    for (int k = 1; kOverlapStart + k * kBin <= max_range; ++k) {
      const double r = kOverlapStart + k * kBin;
      const auto [rate_here, d_min] = rate_at(r);
      expected += 0.5 * (previous + rate_here) * kBin;
      previous = rate_here;
      first_cdf_.push_back(1.0 - det::exp(-expected));
      min_diameter_.push_back(d_min);
      if (rate_here < 1e-12 && r > kOverlapFull + 1.0) {
        break;  // beyond here no particle is bright enough
      }
    }
    if (first_cdf_.empty() || first_cdf_.back() <= 0.0) {
      first_cdf_.clear();
    }
  }
}

WeatherReturn LidarWeatherModel::fog_echo(double r0) const {
  if (fog_table_.empty() && fog_free_.power == 0.0) {
    return {};
  }
  if (!(r0 < fog_saturation_)) {
    return fog_free_;
  }
  const auto index = static_cast<size_t>(std::max(r0, 0.0) / kFogTable);
  return fog_table_[std::min(index, fog_table_.size() - 1)];
}

double LidarWeatherModel::seen_diameter(double melted_mm) const {
  // D_f^2 = (rho_w / C3) D^3; below D = C3 / rho_w (0.17 mm) the law would make the flake
  // denser than water, and it is taken as the drop.
  return std::max(melted_mm, std::sqrt(flake_swell_ * melted_mm * melted_mm * melted_mm));
}

double LidarWeatherModel::melted_diameter(double seen_mm) const {
  if (!(flake_swell_ * seen_mm > 1.0)) {
    return seen_mm;
  }
  return power(seen_mm * seen_mm / flake_swell_, 1.0 / 3.0);
}

double LidarWeatherModel::particle_power(double range, double diameter_mm) const {
  const double beam_mm = 1e3 * kBeamDivergence * range;
  const double share = std::min(1.0, (diameter_mm / beam_mm) * (diameter_mm / beam_mm));
  return reflectance_ * overlap(range) * share * det::exp(-2.0 * alpha_ * range) / (range * range);
}

WeatherReturn LidarWeatherModel::particle(BeamRandom& random, double limit) const {
  const double u = random.uniform01();
  if (first_cdf_.empty() || !(u < first_cdf_.back())) {
    return {};
  }
  // Inverse of the first particle's distribution, linear within a bin.
  const auto it = std::upper_bound(first_cdf_.begin(), first_cdf_.end(), u);
  const auto k = static_cast<size_t>(it - first_cdf_.begin());
  const double below = k == 0 ? 0.0 : first_cdf_[k - 1];
  const double share = (u - below) / std::max(first_cdf_[k] - below, 1e-300);
  const double range = kOverlapStart + (static_cast<double>(k) - 1.0 + share) * kBin;  // k >= 1
  const double d_min = min_diameter_[k];
  // Sizes are exponential: above the smallest detectable one the excess is exponential too.
  const double diameter = d_min - det::log(1.0 - random.uniform01()) / size_rate_;
  if (!(range < limit) || range < kOverlapStart) {
    return {};
  }
  return {range, particle_power(range, seen_diameter(diameter))};
}

}  // namespace corsa::sensors::detail
