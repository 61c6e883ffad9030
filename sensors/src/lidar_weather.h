#pragma once

// What fog, rain and snow do to a LiDAR beam besides dimming it (private to the library): early
// returns from the atmosphere in front of the target. Received powers are in the units of
// Kilic et al. (LISA, arXiv:2107.07004): a Lambertian target of reflectivity rho at range r in
// clear air returns rho / r^2 (1/m^2); the sensor detects what exceeds P_min = 0.9 / range^2 (a
// target of reflectivity 0.9 at the sensor's range, LISA's threshold).
//
// Fog (Hahner, Sakaridis, Dai, Van Gool, "Fog Simulation on Real LiDAR Point Clouds for 3D Object
// Detection in Adverse Weather", ICCV 2021, after Rasshofer et al. 2011): the fog is a soft
// target of backscattering coefficient beta = 0.046 / MOR (1/(m sr)), MOR = ln(20) / alpha the
// meteorological optical range. The pulse P0 sin^2(pi t / (2 tau_H)), 0 <= t <= 2 tau_H
// (tau_H = 20 ns), scattered back from every range r in front of the target gives
//   P_soft(R) = pi beta Int_{R - c tau_H}^{min(R, R0)} sin^2(pi (R - r) / (c tau_H)) xi(r)
//               e^(-2 alpha r) / r^2 dr
// at the range R that the echo time stands for; the reported range is R - c tau_H / 2 (the
// pulse's peak). xi is the overlap of transmitter and receiver fields of view, 0 up to
// r1 = 1.5 m (LISA's bistatic minimum range), rising linearly (Hahner et al.'s linear crossover)
// to 1 at r2 = 5 m (they note r2 < 10 m for most sensors). The peak of P_soft competes with the
// target's attenuated return.
//
// Rain and snow (Kilic et al.): single particles. Drop sizes follow Marshall and Palmer (1948),
// N(D) = 8000 e^(-4.1 R^-0.21 D) (1/(m^3 mm)), snowflakes Gunn and Marshall (1958),
// N(D) = 3800 R^-0.87 e^(-2.55 R^-0.48 D), R in mm/h (water equivalent), D in mm the melted
// diameter. A flake is an aggregate of density C3 / D_f (sensors::kDrySnowDensityDiameter), so
// the flake of melted diameter D is D_f = sqrt(rho_w D^3 / C3) across (never less than D). A
// particle of diameter D_f at range r intercepts the share min(1, (D_f / D_beam)^2) of the beam
// (D_beam = r times the 3 mrad divergence) and returns rho_p xi(r) min(1, (D_f / D_beam)^2)
// e^(-2 alpha r) / r^2 with rho_p the Fresnel reflectance of water (n = 1.328: 0.020) or, for the
// rough flakes, the diffuse reflectance of snow (0.8). Particles are detectable where that
// exceeds P_min (beyond r1), so each beam meets them as a Poisson process along its path whose
// rate is the number of detectable particles per metre of beam; the first one met is the
// candidate. Their extinction is sensors::rain_extinction / snow_extinction (environment.h).

#include <cstdint>
#include <vector>

#include "corsa/sensors/lidar.h"
#include "lidar_random.h"

namespace corsa::sensors::detail {

/// An early return: range (m, along the beam) and received power (LISA units, 1/m^2).
struct WeatherReturn {
  double range = 0.0;
  double power = 0.0;
};

class LidarWeatherModel {
 public:
  LidarWeatherModel(const LidarWeather& weather, double max_range);

  const LidarWeather& weather() const { return weather_; }
  /// Fog + rain + snow extinction, 1/m.
  double extinction() const { return alpha_; }
  /// Detection threshold P_min, 1/m^2.
  double threshold() const { return threshold_; }

  /// The fog's strongest echo in front of a target at range `r0` (infinity: no target); power
  /// 0 without fog.
  WeatherReturn fog_echo(double r0) const;
  /// Whether any beam can meet a detectable particle (rain or snow).
  bool has_particles() const { return !first_cdf_.empty(); }
  /// The first detectable particle along a beam before `limit` metres, drawn from `random`
  /// (power 0: none). One draw when there is none, two more when there is.
  WeatherReturn particle(BeamRandom& random, double limit) const;

 private:
  double particle_power(double range, double diameter_mm) const;
  /// Across the particle of melted diameter `melted_mm` (mm): the drop itself, or the flake.
  double seen_diameter(double melted_mm) const;
  /// The melted diameter of the particle `seen_mm` across (inverse of seen_diameter).
  double melted_diameter(double seen_mm) const;

  LidarWeather weather_;
  double alpha_ = 0.0;
  double threshold_ = 0.0;
  // Fog: the echo in front of targets nearer than fog_saturation_ (by 5 cm of target range),
  // then the free echo.
  std::vector<WeatherReturn> fog_table_;
  WeatherReturn fog_free_;
  double fog_saturation_ = 0.0;
  // Particles: probability that the first detectable one lies before each 5 cm bin edge
  // (first_cdf_[k] for range r1 + k * 5 cm), and the exponential size law of the precipitation.
  std::vector<double> first_cdf_;
  std::vector<double> min_diameter_;  ///< mm (melted), smallest detectable at each bin edge
  double size_rate_ = 0.0;            ///< Lambda, 1/mm (of melted diameter)
  double flake_swell_ = 0.0;          ///< rho_w / C3, 1/mm, for snow; 0 for rain
  double reflectance_ = 0.0;
};

}  // namespace corsa::sensors::detail
