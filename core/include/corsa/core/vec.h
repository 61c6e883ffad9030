#pragma once

// Small vectors in double precision: points and directions in the plane (Vec2) and in space
// (Vec3). One type each for every module, so that coordinates pass between them without copying
// field by field. They carry no frame: the user names it (map frame: x east, y north, z up,
// metres; entity and sensor frames: x forward, y left, z up).
//
// Plain aggregates with inline operators, so they cost what loose doubles cost. norm() is the
// square root of the dot product, not hypot: it sits on hot paths (polyline projection, ray
// setup), and hypot's care against overflow costs more than map coordinates ever need.

#include <cmath>

namespace corsa {

struct Vec2 {
  double x = 0.0;
  double y = 0.0;
};

inline Vec2 operator+(Vec2 a, Vec2 b) { return {a.x + b.x, a.y + b.y}; }
inline Vec2 operator-(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
inline Vec2 operator-(Vec2 a) { return {-a.x, -a.y}; }
inline Vec2 operator*(Vec2 a, double s) { return {a.x * s, a.y * s}; }
inline Vec2 operator*(double s, Vec2 a) { return {s * a.x, s * a.y}; }
inline double dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }
/// The z component of the cross product: > 0 when b lies counter-clockwise of a.
inline double cross(Vec2 a, Vec2 b) { return a.x * b.y - a.y * b.x; }
inline double norm(Vec2 a) { return std::sqrt(a.x * a.x + a.y * a.y); }

struct Vec3 {
  double x = 0.0;
  double y = 0.0;
  double z = 0.0;
};

inline Vec3 operator+(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline Vec3 operator-(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline Vec3 operator-(Vec3 a) { return {-a.x, -a.y, -a.z}; }
inline Vec3 operator*(Vec3 a, double s) { return {a.x * s, a.y * s, a.z * s}; }
inline Vec3 operator*(double s, Vec3 a) { return a * s; }
inline double dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Vec3 cross(Vec3 a, Vec3 b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double norm(Vec3 a) { return std::sqrt(dot(a, a)); }
/// a scaled to length 1; a itself when it is zero.
inline Vec3 normalized(Vec3 a) {
  const double n = norm(a);
  return n > 0.0 ? a * (1.0 / n) : a;
}

/// The horizontal part of a point or direction.
inline Vec2 xy(Vec3 a) { return {a.x, a.y}; }

}  // namespace corsa
