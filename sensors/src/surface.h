#pragma once

// How a material looks at one surface point: its textures evaluated at the point, prefiltered
// to the pixel footprint (private to the renderers).

#include "corsa/sensors/geometry.h"
#include "corsa/sensors/material.h"

namespace corsa::sensors::detail {

/// Where a material is read.
struct TexturePoint {
  Vec3 position;   ///< metres; a frame fixed to the surface (tracer frame for static
                   ///< geometry, the entity frame for entities)
  Vec3 normal;     ///< unit, same frame, facing the viewer
  double u = 0.0;  ///< the mesh's texture coordinates (0 when it has none)
  double v = 0.0;
  double footprint = 0.0;  ///< metres covered by the pixel on the surface
  /// The footprint's long axis over `footprint` (1 / sqrt(cos incidence)): at grazing views
  /// the pixel covers this much more along the view than `footprint`, and a pattern whose
  /// features line up on a lattice (the noise tile's texels) would alias into stripes there
  /// unless read at the long axis.
  double stretch = 1.0;
  double uv_per_m = 1.0;   ///< texture-coordinate units per metre on this triangle
  double base_z = 0.0;     ///< height of the mesh's lowest point (facades count floors from it)
  double darkness = 0.0;   ///< 0 day .. 1 night: how many windows are lit
  bool one_level = false;  ///< noise read on the nearest mip level only (the `fast` preset)
};

/// A material's look at a point.
struct SurfaceSample {
  Color albedo;
  double roughness = 0.8;
  double metallic = 0.0;
  double clearcoat = 0.0;
  double transmission = 0.0;
  Color emission;  ///< emitted radiance that does not depend on a light role (lit windows)
};

/// Evaluates the material's pattern or image at the point.
SurfaceSample sample_surface(const Material& material, const TexturePoint& point);

/// Coverage (0..1) of a sign face's shape, border and symbol at uv, antialiased over `fw` uv
/// units; the colour is returned.
Color sign_face_color(const SignFace& face, double u, double v, double fw);

}  // namespace corsa::sensors::detail
