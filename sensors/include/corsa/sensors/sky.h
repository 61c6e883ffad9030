#pragma once

// The sky as a light source and a background: the analytic clear daylight sky of Preetham,
// Shirley and Smits ("A Practical Analytic Model for Daylight", SIGGRAPH 1999), blended with the
// CIE overcast sky (Moon and Spencer 1942) by the cloud cover, faded through twilight and ended
// at night by the glow of city light on the sky. Radiance is linear RGB (sRGB primaries) in the
// renderer's relative unit: 1 is the radiance of a white diffuse surface lit by 100,000 lux,
// i.e. 100,000 / pi cd/m^2.

#include <algorithm>
#include <array>
#include <numbers>
#include <vector>

#include "corsa/sensors/color.h"
#include "corsa/sensors/geometry.h"

namespace corsa::sensors {

/// cd/m^2 per relative radiance unit (a white diffuse surface under 100,000 lux).
inline constexpr double kNitsPerUnit = 100000.0 / 3.14159265358979323846;

/// Preetham's xyY sky distribution for one sun position and turbidity.
struct PreethamSky {
  double turbidity = 3.0;
  double sun_theta = 0.0;  ///< zenith angle of the sun used by the fit (radians, <= pi/2)
  std::array<double, 5> perez_Y{}, perez_x{};
  double zenith_Y = 0.0;  ///< kcd/m^2 (the paper's unit)
  double zenith_x = 0.0;

  /// Luminance (kcd/m^2) and chromaticity at view zenith angle theta and angle gamma from the
  /// sun (radians); theta is clamped just above the horizon. x is the paper's, y the daylight
  /// locus's at that x (see daylight_locus_y).
  void xyY(double theta, double gamma, double& x, double& y, double& Y) const;
};

/// Preetham's model: zenith luminance and chromaticity and the Perez coefficients (paper,
/// appendix A.2) for turbidity T (about 2 very clear .. 10 hazy) and the sun's zenith angle.
PreethamSky make_preetham(double turbidity, double sun_theta);

/// CIE daylight locus: the chromaticity y of daylight of chromaticity x (CIE 15, from Judd,
/// MacAdam and Wyszecki 1964).
double daylight_locus_y(double x);

/// Linear sRGB of CIE xyY (D65 white).
Color rgb_from_xyY(double x, double y, double Y);

/// The whole sky of a moment. Directions are unit vectors in the map frame (z up).
struct SkyModel {
  Vec3 sun_direction{0.0, 0.0, 1.0};
  double sun_elevation = 1.0;  ///< radians
  PreethamSky clear;
  /// Scale of the clear sky (twilight fade below 2 degrees of sun and the share of clear sky
  /// left by the clouds), relative units per kcd/m^2.
  double clear_scale = 0.0;
  double overcast_zenith = 0.0;  ///< CIE overcast zenith radiance, relative units
  Color overcast_tint{1.0, 1.0, 1.0};
  Color twilight_tint{1.0, 1.0, 1.0};  ///< colour of the sky after sunset (blue hour)
  Color glow_zenith;                   ///< city glow at night, relative units
  Color glow_horizon;
  Color ground;  ///< radiance of the ground seen below the horizon (diffuse, relative units)

  /// Sky radiance towards `direction` (the ground below the horizon), without the sun's disc:
  /// read from the table when tabulate() has made one, else evaluated.
  Color radiance(Vec3 direction) const;
  /// The evaluated sky above the horizon at cos(view zenith angle) and cos(angle to the sun).
  Color radiance_above(double cos_theta, double cos_gamma) const;
  /// Tabulates radiance_above over sqrt(cos theta) and sin(gamma / 2) (kTableRows x kTableCols
  /// samples, read bilinearly: within a fraction of a per cent of the evaluated sky, at a
  /// tenth of its cost per ray). Call it after the last change to the fields above.
  void tabulate();

  static constexpr int kTableRows = 65;
  static constexpr int kTableCols = 129;

 private:
  std::vector<Color> table_;  ///< kTableRows x kTableCols, empty until tabulate()
};

/// Irradiance of a distant environment on a surface of any orientation, from its projection on
/// the first nine spherical harmonics (Ramamoorthi and Hanrahan, "An Efficient Representation
/// for Irradiance Environment Maps", SIGGRAPH 2001, eq. 13): exact to a few per cent for skies.
struct IrradianceSH {
  std::array<Color, 9> coefficients{};

  /// Irradiance / pi (the radiance of a white diffuse surface) for unit normal n. Inline: the
  /// camera evaluates it two to three times a pixel.
  Color operator()(Vec3 n) const {
    // Ramamoorthi and Hanrahan 2001, eq. 13, divided by pi.
    constexpr double c1 = 0.429043, c2 = 0.511664, c3 = 0.743125, c4 = 0.886227, c5 = 0.247708;
    const auto& L = coefficients;
    const double x = n.x, y = n.y, z = n.z;
    const Color e = L[8] * (c1 * (x * x - y * y)) + L[6] * (c3 * z * z) + L[0] * c4 + L[6] * -c5 +
                    (L[4] * (x * y) + L[7] * (x * z) + L[5] * (y * z)) * (2.0 * c1) +
                    (L[3] * x + L[1] * y + L[2] * z) * (2.0 * c2);
    const double inv_pi = 1.0 / std::numbers::pi;
    return {std::max(0.0, e.r * inv_pi), std::max(0.0, e.g * inv_pi), std::max(0.0, e.b * inv_pi)};
  }
};

/// Projects the sky model (including the ground below the horizon) by numerical quadrature.
IrradianceSH project_sky(const SkyModel& sky);

}  // namespace corsa::sensors
