#pragma once

// Street lights, vehicle lamps and traffic-light bulbs as light sources of one frame (private).
// Every lamp's light reaches only a limited range (its inverse-square falloff is windowed to
// zero there, as in Karis, "Real Shading in Unreal Engine 4", 2013), and a uniform grid over the
// map lists for each cell the lights that reach it, at most kMaxLightsPerCell (the strongest at
// the cell), so the cost of a shading point does not grow with the number of lamps on the map.

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "corsa/engine/world_snapshot.h"
#include "corsa/sensors/color.h"
#include "corsa/sensors/environment.h"
#include "corsa/sensors/geometry.h"
#include "corsa/sensors/material.h"

namespace corsa::sensors::detail {

struct SceneData;

/// How a light's intensity varies with direction.
enum class LightPattern : uint8_t {
  kStreetLamp,  ///< full cut-off down-light, out to 78 degrees, cut short behind its pole
  kLowBeam,     ///< headlight: a horizontal fan below a sharp cut-off just under the horizon
  kLambert,     ///< small lamp lens: I0 cos about its axis (tail, brake, signal bulbs)
};

struct Light {
  Vec3 position;  ///< tracer-local
  Vec3 axis;      ///< unit, the main direction of the light
  /// Unit, horizontal, perpendicular to the axis: a low beam's left, a street lamp's street
  /// side (from its pole out along its arm; zero for a lamp on top of its pole: all round).
  Vec3 side;
  Color intensity;      ///< peak luminous intensity / 100,000 (cd per relative unit)
  double radius = 0.1;  ///< emitter size (m): soft shadow rays aim within it
  double range = 30.0;  ///< m: no light beyond
  LightPattern pattern = LightPattern::kLambert;
};

/// A light's irradiance (renderer units) at a point and the unit direction towards it.
struct LightSample {
  Color irradiance;  ///< on a surface facing the light
  Vec3 direction;    ///< from the point to the light
  double distance = 0.0;
};

/// Irradiance from light `k` at point p (tracer-local), facing it; zero beyond its range.
LightSample illuminate(const Light& light, Vec3 p);

/// Emitting patches of a lit lamp: where light sources sit (computed from the meshes' emissive
/// triangles; see SceneData::static_lamps and EntityShape::lamps).
struct LampPatch {
  LightRole role = LightRole::kNone;
  Vec3 centre;  ///< frame of the mesh
  Vec3 normal;  ///< unit, area-weighted; zero when the lens is closed (a box, a capped disc)
  double area = 0.0;
  Color emission;
  int signal = -1;  ///< static traffic-light bulbs: the signal index
  uint32_t bone = 0;
  Vec3 reach;  ///< street lamps: unit, horizontal, from the pole out to the lamp (or zero)
};

/// Clusters the emissive triangles of a mesh (vertices, triangles, one role and emission per
/// triangle) into lamps: triangles of the same role, bone and side within 0.6 m.
std::vector<LampPatch> find_lamps(std::span<const Vec3> vertices,
                                  std::span<const std::array<uint32_t, 3>> triangles,
                                  std::span<const LightRole> roles,
                                  std::span<const Color> emissions,
                                  std::span<const uint32_t> bones);

/// The LightStateAction looks of an entity's lamps by LightRole (up to kReversing); null: the
/// lamp as it is.
using LampLooks = std::array<const engine::LightLook*, 8>;

/// Which of an entity's looks drive its lamps: the headlights the low beam's, else the high
/// beam's or the daytime running lights' (whichever is lit), brake and reversing lamps their
/// own, an indicator its own or else the warning lights'. Tail lamps keep their own look.
LampLooks lamp_looks(const engine::EntitySnapshot& entity);

/// What a lamp of `role` whose own emission is `own` emits under `look` (same units as `own`;
/// the role's peak intensity stands for the lamp's own intensity).
Color looked_emission(const engine::LightLook& look, LightRole role, Color own);

class LightList {
 public:
  static constexpr int kMaxLightsPerCell = 16;

  /// The lit lamps of the frame: entity lamps by their lit roles (`entity_lamps`, by instance
  /// pool index), static lamps by `static_lamps` bits and the signals' bulbs. Lights too faint
  /// to matter against the daylight `floor` (renderer units of irradiance at 2 m) are left out.
  /// `looks` (by instance pool index, or empty) tints and scales the entity lamps.
  LightList(const SceneData& scene, std::span<const uint32_t> entity_lamps,
            std::span<const LampLooks> looks, uint32_t static_lamps, double floor);
  LightList() = default;

  std::span<const Light> lights() const { return lights_; }
  /// The lights that can reach tracer-local point p.
  std::span<const uint32_t> near(Vec3 p) const;
  bool empty() const { return lights_.empty(); }

 private:
  void add(const Light& light);
  void build_grid();

  std::vector<Light> lights_;
  double x0_ = 0.0, y0_ = 0.0, cell_ = 10.0;
  int nx_ = 0, ny_ = 0;
  std::vector<uint32_t> offsets_;  ///< nx * ny + 1
  std::vector<uint32_t> indices_;
};

}  // namespace corsa::sensors::detail
