#include "corsa/sensors/sky.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "scalar_math.h"

namespace corsa::sensors {

using detail::kPi;
using detail::smoothstep;
namespace {

/// Perez et al.'s all-weather distribution F(theta, gamma) = (1 + A e^(B / cos theta))
/// (1 + C e^(D gamma) + E cos^2 gamma).
double perez(const std::array<double, 5>& c, double cos_theta, double gamma, double cos_gamma) {
  return (1.0 + c[0] * std::exp(c[1] / cos_theta)) *
         (1.0 + c[2] * std::exp(c[3] * gamma) + c[4] * cos_gamma * cos_gamma);
}

}  // namespace

PreethamSky make_preetham(double turbidity, double sun_theta) {
  PreethamSky s;
  const double T = turbidity;
  s.turbidity = T;
  s.sun_theta = sun_theta;
  // Preetham et al. 1999, appendix A.2: the Perez coefficients are linear in T.
  s.perez_Y = {0.17872 * T - 1.46303, -0.35540 * T + 0.42749, -0.02266 * T + 5.32505,
               0.12064 * T - 2.57705, -0.06696 * T + 0.37027};
  s.perez_x = {-0.01925 * T - 0.25922, -0.06651 * T + 0.00081, -0.00041 * T + 0.21247,
               -0.06409 * T - 0.89887, -0.00325 * T + 0.04517};
  // Zenith luminance (kcd/m^2) and chromaticity x, cubic in the sun's zenith angle. The
  // paper's fit of y is left out: xyY() puts the colour on the daylight locus.
  const double chi = (4.0 / 9.0 - T / 120.0) * (kPi - 2.0 * sun_theta);
  s.zenith_Y = std::max(0.0, (4.0453 * T - 4.9710) * std::tan(chi) - 0.2155 * T + 2.4192);
  const double t1 = sun_theta, t2 = t1 * t1, t3 = t2 * t1;
  const double T2 = T * T;
  s.zenith_x = (0.00166 * t3 - 0.00375 * t2 + 0.00209 * t1) * T2 +
               (-0.02903 * t3 + 0.06377 * t2 - 0.03202 * t1 + 0.00394) * T +
               (0.11693 * t3 - 0.21196 * t2 + 0.06052 * t1 + 0.25886);
  return s;
}

void PreethamSky::xyY(double theta, double gamma, double& x, double& y, double& Y) const {
  // Directions at the horizon make 1 / cos(theta) blow up: the fit is read just above it.
  const double cos_theta = std::max(std::cos(theta), 0.01);
  const double cos_gamma = std::cos(gamma);
  const double cos_sun = std::cos(sun_theta);
  auto ratio = [&](const std::array<double, 5>& c) {
    return perez(c, cos_theta, gamma, cos_gamma) / perez(c, 1.0, sun_theta, cos_sun);
  };
  x = zenith_x * ratio(perez_x);
  // Measured skylight lies along the CIE daylight locus (Judd, MacAdam and Wyszecki 1964, from
  // spectra of sun and sky alike, 4,000-25,000 K). Preetham's fit of y strays from it: 0.01-0.02
  // below it near the horizon under a high sun (a pink-mauve band where the sky is a pale
  // blue-white, x about 0.31) and 0.04 above it towards a low sun (yellow-green instead of
  // orange). So the colour keeps the fit's x, its correlated colour temperature, on the locus.
  y = daylight_locus_y(x);
  Y = zenith_Y * ratio(perez_Y);
}

double daylight_locus_y(double x) { return -3.0 * x * x + 2.87 * x - 0.275; }

Color rgb_from_xyY(double x, double y, double Y) {
  if (y <= 1e-9 || Y <= 0.0) {
    return {};
  }
  const double X = x / y * Y;
  const double Z = std::max(0.0, 1.0 - x - y) / y * Y;
  // IEC 61966-2-1 (sRGB) XYZ to linear RGB.
  return {std::max(0.0, 3.2406 * X - 1.5372 * Y - 0.4986 * Z),
          std::max(0.0, -0.9689 * X + 1.8758 * Y + 0.0415 * Z),
          std::max(0.0, 0.0557 * X - 0.2040 * Y + 1.0570 * Z)};
}

Color SkyModel::radiance(Vec3 d) const {
  if (d.z < 0.0) {
    // Beyond the modelled ground: the diffuse ground, hazed towards the horizon's sky colour.
    const double flat = std::sqrt(d.x * d.x + d.y * d.y);
    const Vec3 level = flat > 0.0 ? Vec3{d.x / flat, d.y / flat, 0.0} : Vec3{1.0, 0.0, 0.0};
    const Color horizon = radiance(level);
    return mix(ground, horizon, std::exp(40.0 * d.z));
  }
  const double cos_theta = std::min(d.z, 1.0);
  const double cos_gamma = std::clamp(dot(d, sun_direction), -1.0, 1.0);
  if (table_.empty()) {
    return radiance_above(cos_theta, cos_gamma);
  }
  const double fr = std::sqrt(cos_theta) * (kTableRows - 1);
  const double fc = std::sqrt(std::max(0.0, 0.5 * (1.0 - cos_gamma))) * (kTableCols - 1);
  const int r0 = std::min(static_cast<int>(fr), kTableRows - 2);
  const int c0 = std::min(static_cast<int>(fc), kTableCols - 2);
  const double tr = fr - r0, tc = fc - c0;
  const Color* row0 = &table_[static_cast<size_t>(r0) * kTableCols + c0];
  const Color* row1 = row0 + kTableCols;
  return mix(mix(row0[0], row0[1], tc), mix(row1[0], row1[1], tc), tr);
}

void SkyModel::tabulate() {
  table_.clear();
  std::vector<Color> table(static_cast<size_t>(kTableRows) * kTableCols);
  for (int r = 0; r < kTableRows; ++r) {
    const double a = static_cast<double>(r) / (kTableRows - 1);
    for (int c = 0; c < kTableCols; ++c) {
      const double b = static_cast<double>(c) / (kTableCols - 1);
      table[static_cast<size_t>(r) * kTableCols + c] = radiance_above(a * a, 1.0 - 2.0 * b * b);
    }
  }
  table_ = std::move(table);
}

Color SkyModel::radiance_above(double cos_theta, double cos_gamma) const {
  // The city's glow: a dome of light low over the horizon (the light scattered towards the
  // camera through the most air), fading to the zenith's within some 30 degrees.
  Color c = mix(glow_zenith, glow_horizon, std::exp(-cos_theta / 0.25));
  if (clear_scale > 0.0) {
    double x = 0.0, y = 0.0, Y = 0.0;
    clear.xyY(std::acos(cos_theta), std::acos(cos_gamma), x, y, Y);
    Color sky = rgb_from_xyY(x, y, Y) * clear_scale;
    // After sunset the fit (held at the horizon) is recoloured: blue overhead and away from
    // the sun, orange low towards it.
    const double towards_sun = std::max(0.0, cos_gamma) * (1.0 - cos_theta);
    const Color tint = mix(twilight_tint, Color{1.35, 0.8, 0.5}, towards_sun * towards_sun);
    const double dusk = 1.0 - smoothstep(-0.07, 0.07, sun_elevation);
    sky = sky * mix(Color{1.0, 1.0, 1.0}, tint, dusk);
    c = c + sky;
  }
  if (overcast_zenith > 0.0) {
    c = c + overcast_tint * (overcast_zenith * (1.0 + 2.0 * cos_theta) / 3.0);
  }
  return c;
}

IrradianceSH project_sky(const SkyModel& sky) {
  // Midpoint quadrature over the sphere; the sky varies slowly except near the sun, whose disc
  // is direct light and not part of this.
  constexpr int kTheta = 32;
  constexpr int kPhi = 64;
  IrradianceSH sh;
  for (int i = 0; i < kTheta; ++i) {
    const double theta = (i + 0.5) * kPi / kTheta;
    const double st = std::sin(theta);
    const double weight = st * (kPi / kTheta) * (2.0 * kPi / kPhi);
    for (int j = 0; j < kPhi; ++j) {
      const double phi = (j + 0.5) * 2.0 * kPi / kPhi;
      const double x = st * std::cos(phi), y = st * std::sin(phi), z = std::cos(theta);
      const Color L = sky.radiance({x, y, z}) * weight;
      const double basis[9] = {0.282095,
                               0.488603 * y,
                               0.488603 * z,
                               0.488603 * x,
                               1.092548 * x * y,
                               1.092548 * y * z,
                               0.315392 * (3.0 * z * z - 1.0),
                               1.092548 * x * z,
                               0.546274 * (x * x - y * y)};
      for (int k = 0; k < 9; ++k) {
        sh.coefficients[k] = sh.coefficients[k] + L * basis[k];
      }
    }
  }
  return sh;
}

}  // namespace corsa::sensors
