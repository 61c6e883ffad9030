#pragma once

// Building blocks of the generated assets (vehicles, people, trees, poles, signs): a triangle
// mesh with a material palette, a semantic class and a bone per triangle/vertex, grown from
// boxes, tubes, ellipsoids and lofts (private to the library).

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "corsa/sensors/geometry.h"
#include "corsa/sensors/material.h"
#include "corsa/sensors/semantic.h"
#include "corsa/sensors/static_mesh.h"

namespace corsa::sensors::detail {

/// A mesh whose vertices each follow one rigid bone (0: the body, which never moves); units
/// metres, in the frame the builder was given (an entity's frame for entity assets).
struct ArticulatedMesh {
  std::vector<Vec3> vertices;
  std::vector<uint8_t> bone;  ///< per vertex
  std::vector<std::array<uint32_t, 3>> triangles;
  std::vector<uint16_t> material;         ///< per triangle, into `materials`
  std::vector<SemanticClass> classes;     ///< per triangle
  std::vector<Material> materials;        ///< palette
  std::vector<std::array<float, 2>> uvs;  ///< per vertex
  /// Shading normals per vertex (unit, the mesh's frame), or empty: every triangle flat. A zero
  /// normal marks a vertex of a flat part (a triangle of three such shades with its own normal).
  std::vector<Vec3> normals;
};

class MeshBuilder {
 public:
  /// Selects the material of the next triangles (added to the palette once, by name).
  MeshBuilder& material(const Material& m);
  MeshBuilder& semantic(SemanticClass c) {
    class_ = c;
    return *this;
  }
  MeshBuilder& bone(uint8_t b) {
    bone_ = b;
    return *this;
  }
  /// A transform applied to every vertex added after it (identity by default).
  MeshBuilder& transform(const Rigid& t) {
    xf_ = t;
    return *this;
  }
  const Rigid& transform() const { return xf_; }

  uint32_t vertex(Vec3 p, float u = 0.0f, float v = 0.0f);
  void triangle(uint32_t a, uint32_t b, uint32_t c);
  /// Two triangles a b c, a c d.
  void quad(uint32_t a, uint32_t b, uint32_t c, uint32_t d);

  /// Axis-aligned box (in the current transform) between two corners.
  void box(Vec3 lo, Vec3 hi);
  /// A tube from a to b, radius r0 at a and r1 at b, `segments` around, optionally closed.
  void tube(Vec3 a, Vec3 b, double r0, double r1, int segments, bool caps = true);
  /// An ellipsoid with semi-axes `radii` along the columns of `axes` (a rotation).
  void ellipsoid(Vec3 centre, Vec3 radii, const Mat3& axes, int slices, int stacks);
  /// Closed rings of equal size joined into a tube-like surface; end rings capped by fans.
  void loft(const std::vector<std::vector<Vec3>>& rings, bool cap_ends);
  /// A flat convex polygon (counter-clockwise), with uvs given per point.
  void polygon(const std::vector<Vec3>& points, const std::vector<std::array<float, 2>>& uvs);
  /// A simple polygon, convex or not and of either winding, filled by ear clipping in its x-y
  /// plane and wound counter-clockwise seen from +z (paint outlines such as arrows). Returns
  /// false and adds nothing when the ring is not a simple polygon of at least 3 points.
  bool filled_ring(const std::vector<Vec3>& ring);

  /// Makes the part added since `first_vertex` / `first_triangle` shade smooth: each of its
  /// vertices gets the area-weighted mean of the normals of the part's triangles that use it
  /// (outwards for closed parts wound counter-clockwise seen from outside, as all of these are).
  void smooth_normals(size_t first_vertex, size_t first_triangle);

  /// Gives an already added triangle another material (e.g. glass cut out of a body loft).
  void set_material(size_t triangle, const Material& m);

  size_t triangle_count() const { return mesh_.triangles.size(); }
  const ArticulatedMesh& mesh() const { return mesh_; }
  /// The mesh so far, for shaping what was added (e.g. displacing vertices).
  ArticulatedMesh& edit() { return mesh_; }
  ArticulatedMesh take() { return std::move(mesh_); }

 private:
  ArticulatedMesh mesh_;
  uint16_t material_ = 0;
  SemanticClass class_ = SemanticClass::kStatic;
  uint8_t bone_ = 0;
  Rigid xf_;
  bool has_material_ = false;
};

/// The mesh as a static mesh placed by `placement` (bones ignored), one class per triangle,
/// its palette and uvs carried over.
StaticMesh to_static_mesh(const ArticulatedMesh& mesh, const Rigid& placement, std::string name);

/// Ear clipping of a counter-clockwise simple polygon: index triples into `ring`; empty when
/// the ring has fewer than 3 points or is not simple (no ear to clip).
std::vector<std::array<uint32_t, 3>> ear_clip(const std::vector<Vec2>& ring);

/// Unit vectors e1, e2 perpendicular to a unit axis and to each other (a stable choice).
void perpendicular_basis(Vec3 axis, Vec3& e1, Vec3& e2);

}  // namespace corsa::sensors::detail
