#include "corsa/sensors/material.h"

#include <utility>

#include "material_defaults.h"

namespace corsa::sensors {
namespace materials {

Material plain(std::string name, Color base, double roughness) {
  Material m;
  m.name = std::move(name);
  m.base_color = base;
  m.roughness = roughness;
  return m;
}

Material glass(std::string name) {
  Material m;
  m.name = std::move(name);
  m.base_color = {0.03, 0.035, 0.04};  // the dark interior seen through it
  m.roughness = 0.03;
  m.transmission = 0.9;
  m.ior = 1.5;
  return m;
}

Material metal(std::string name, Color base, double roughness) {
  Material m;
  m.name = std::move(name);
  m.base_color = base;
  m.metallic = 1.0;
  m.roughness = roughness;
  return m;
}

Material lamp(std::string name, Color lens, Color emission, LightRole role) {
  Material m;
  m.name = std::move(name);
  m.base_color = lens;
  m.roughness = 0.15;
  m.emission = emission;
  m.light = role;
  return m;
}

}  // namespace materials

namespace detail {

Material default_material(SemanticClass c) {
  using materials::plain;
  Material m;
  switch (c) {
    case SemanticClass::kRoad:
      m = plain("asphalt", linear_rgb(92, 92, 94), 0.9);
      m.pattern = Pattern::kAsphalt;
      m.params[0] = 0.6;
      return m;
    case SemanticClass::kParking:
      m = plain("parking asphalt", linear_rgb(98, 97, 96), 0.9);
      m.pattern = Pattern::kAsphalt;
      m.params[0] = 1.0;
      m.seed = 7;
      return m;
    case SemanticClass::kBikeLane:
      m = plain("bike lane", linear_rgb(125, 70, 62), 0.85);
      m.pattern = Pattern::kAsphalt;
      m.seed = 11;
      return m;
    case SemanticClass::kLaneMarking:
      m = plain("road paint", linear_rgb(232, 232, 222), 0.6);
      m.pattern = Pattern::kPaint;
      m.secondary = linear_rgb(92, 92, 94);
      m.params[0] = 0.5;
      return m;
    case SemanticClass::kSidewalk:
      m = plain("sidewalk concrete", linear_rgb(168, 163, 154), 0.9);
      m.pattern = Pattern::kConcrete;
      m.pattern_scale = 1.2;
      m.secondary = linear_rgb(110, 106, 100);
      return m;
    case SemanticClass::kTerrain:
      m = plain("terrain", linear_rgb(92, 106, 60), 0.95);
      m.pattern = Pattern::kTerrain;
      m.secondary = linear_rgb(120, 100, 72);
      return m;
    case SemanticClass::kGround:
      m = plain("dirt", linear_rgb(122, 104, 80), 0.95);
      m.pattern = Pattern::kDirt;
      m.secondary = linear_rgb(96, 84, 66);
      return m;
    case SemanticClass::kVegetation:
      m = plain("foliage", linear_rgb(70, 100, 40), 0.75);
      m.pattern = Pattern::kFoliage;
      m.secondary = linear_rgb(32, 52, 22);
      return m;
    case SemanticClass::kBuilding:
      m = plain("facade", linear_rgb(185, 172, 152), 0.85);
      m.pattern = Pattern::kFacade;
      m.pattern_scale = 3.3;
      m.params = {3.2, 0.5, 0.45, 4.2};
      m.secondary = linear_rgb(70, 68, 64);
      return m;
    case SemanticClass::kRailTrack:
      return plain("ballast", linear_rgb(105, 95, 85), 0.95);
    case SemanticClass::kPole:
    case SemanticClass::kGuardRail:
      return materials::metal("galvanised steel", linear_rgb(150, 152, 150), 0.45);
    case SemanticClass::kWall:
      m = plain("concrete wall", linear_rgb(160, 156, 148), 0.9);
      m.pattern = Pattern::kConcrete;
      m.pattern_scale = 2.5;
      m.secondary = linear_rgb(120, 116, 110);
      return m;
    default:
      return plain("grey", linear_rgb(140, 140, 140), 0.8);
  }
}

}  // namespace detail
}  // namespace corsa::sensors
