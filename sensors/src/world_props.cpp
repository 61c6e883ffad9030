#include "world_props.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "scalar_math.h"

namespace corsa::sensors::detail {
namespace {

Material steel() { return materials::metal("galvanised steel", linear_rgb(150, 152, 150), 0.45); }
Material dark_paint() { return materials::plain("signal housing", linear_rgb(28, 30, 30), 0.6); }

}  // namespace

ArticulatedMesh make_street_light(double height, double reach) {
  MeshBuilder b;
  b.semantic(SemanticClass::kPole).material(steel());
  b.tube({0, 0, 0}, {0, 0, height}, 0.09, 0.06, 10, true);
  b.tube({0, 0, height - 0.15}, {reach, 0, height + 0.1}, 0.045, 0.04, 8, true);
  b.material(dark_paint());
  b.box({reach - 0.3, -0.16, height}, {reach + 0.35, 0.16, height + 0.14});
  // The lamp's diffuser faces down; it glows when it is dark, as bright as its 3,000 cd
  // (light_list.cpp) spread over its 0.13 m^2 make it: about 23,000 cd/m^2, 0.72 in the
  // renderer's radiance unit (kNitsPerUnit), in a warm LED white.
  b.material(materials::lamp("street lamp", linear_rgb(230, 225, 210), Color{0.8, 0.72, 0.55},
                             LightRole::kStreetLamp));
  b.box({reach - 0.25, -0.12, height - 0.02}, {reach + 0.3, 0.12, height});
  return b.take();
}

Vec3 street_lamp_head(double height, double reach) { return {reach + 0.025, 0.0, height + 0.07}; }

ArticulatedMesh make_traffic_light(SignalLayout layout, double bottom, double head_height) {
  MeshBuilder b;
  const bool horizontal = layout != SignalLayout::kVertical3;
  const int bulbs = layout == SignalLayout::kHorizontal4 ? 4 : 3;
  const double cell = horizontal ? head_height : head_height / 3.0;  // bulb pitch
  const double w = horizontal ? cell * bulbs : cell * 1.1;
  const double h = horizontal ? cell * 1.1 : head_height;
  // Post: beside the head for vertical lights, a mast arm for horizontal ones. The mast stands
  // 2 m beyond the head's +y end: on the right of the traffic the head faces (+y is the facing
  // drivers' right; the kerb side under right-hand traffic), so that a head hung over the lanes
  // keeps its post off them.
  b.semantic(SemanticClass::kPole).material(steel());
  if (horizontal) {
    b.tube({-0.2, 0.5 * w + 2.0, 0}, {-0.2, 0.5 * w + 2.0, bottom + 0.5 * h + 0.3}, 0.12, 0.1, 10,
           true);
    b.tube({-0.2, 0.5 * w + 2.0, bottom + 0.5 * h + 0.25},
           {-0.2, -0.5 * w, bottom + 0.5 * h + 0.25}, 0.06, 0.05, 8, true);
  } else {
    b.tube({-0.2, 0, 0}, {-0.2, 0, bottom + h}, 0.07, 0.06, 10, true);
  }
  b.semantic(SemanticClass::kTrafficLight).material(dark_paint());
  b.box({-0.15, -0.5 * w, bottom}, {0.12, 0.5 * w, bottom + h});
  const LightRole roles4[4] = {LightRole::kSignalRed, LightRole::kSignalYellow,
                               LightRole::kSignalGreen, LightRole::kSignalGreen};
  const Color lens[3] = {linear_rgb(70, 8, 8), linear_rgb(80, 55, 5), linear_rgb(5, 60, 30)};
  // Saturated glows: no channel should clip towards white before the red one does.
  const Color glow[3] = {Color{6.0, 0.08, 0.03}, Color{6.0, 2.6, 0.05}, Color{0.08, 5.0, 2.2}};
  for (int i = 0; i < bulbs; ++i) {
    const int k = std::min(i, 2);
    const LightRole role = roles4[i];
    const char* names[3] = {"signal red", "signal yellow", "signal green"};
    b.material(materials::lamp(names[k], lens[k], glow[k], role));
    Vec3 c;
    if (horizontal) {
      c = {0.125, 0.5 * w - cell * (i + 0.5), bottom + 0.5 * h};
    } else {
      c = {0.125, 0.0, bottom + h - cell * (i + 0.5)};
    }
    b.tube(c, c + Vec3{0.02, 0, 0}, 0.36 * cell, 0.36 * cell, 14, true);
    // Visor over each bulb.
    b.material(dark_paint());
    b.box(c + Vec3{0.0, -0.4 * cell, 0.36 * cell}, c + Vec3{0.18, 0.4 * cell, 0.42 * cell});
  }
  return b.take();
}

ArticulatedMesh make_sign(const SignFace& face, double width, double height, double bottom,
                          const std::string& name) {
  MeshBuilder b;
  b.semantic(SemanticClass::kPole).material(steel());
  b.tube({-0.05, 0, 0}, {-0.05, 0, bottom + 0.8 * height}, 0.035, 0.035, 8, true);
  b.semantic(SemanticClass::kTrafficSign);
  Material m = sign_face_material(face, name);
  // The face polygon follows the shape (circles as 24-gons), uv over its square.
  std::vector<Vec3> points;
  std::vector<std::array<float, 2>> uvs;
  auto add = [&](double u, double v) {
    points.push_back({0.0, (0.5 - u) * width, bottom + v * height});
    uvs.push_back({static_cast<float>(u), static_cast<float>(v)});
  };
  switch (face.shape) {
    case SignShape::kCircle:
      for (int i = 0; i < 24; ++i) {
        const double a = 2.0 * kPi * i / 24.0;
        add(0.5 + 0.5 * std::cos(a), 0.5 + 0.5 * std::sin(a));
      }
      break;
    case SignShape::kTriangleUp:
      add(0.0, 0.11), add(1.0, 0.11), add(0.5, 0.975);
      break;
    case SignShape::kTriangleDown:
      add(0.5, 0.025), add(1.0, 0.89), add(0.0, 0.89);
      break;
    case SignShape::kOctagon:
      for (int i = 0; i < 8; ++i) {
        const double a = 2.0 * kPi * (i + 0.5) / 8.0;
        const double r = 0.5 / std::cos(kPi / 8.0);
        add(0.5 + r * std::cos(a), 0.5 + r * std::sin(a));
      }
      break;
    case SignShape::kDiamond:
      add(0.5, 0.0), add(1.0, 0.5), add(0.5, 1.0), add(0.0, 0.5);
      break;
    default:
      add(0.0, 0.0), add(1.0, 0.0), add(1.0, 1.0), add(0.0, 1.0);
      break;
  }
  b.material(m);
  b.polygon(points, uvs);
  // The back: grey metal a little behind.
  std::vector<Vec3> back;
  for (auto it = points.rbegin(); it != points.rend(); ++it) {
    back.push_back(*it - Vec3{0.015, 0.0, 0.0});
  }
  b.material(steel());
  b.polygon(back, {});
  return b.take();
}

Material sign_face_material(const SignFace& face, const std::string& name) {
  Material m;
  m.name = name;
  m.pattern = Pattern::kSignFace;
  m.sign = face;
  m.roughness = 0.5;
  m.base_color = face.fill;
  return m;
}

Material road_paint() {
  Material m = materials::plain("road paint", linear_rgb(232, 232, 222), 0.6);
  m.pattern = Pattern::kPaint;
  m.secondary = linear_rgb(92, 92, 94);
  m.params[0] = 0.5;
  return m;
}

ArticulatedMesh make_rail(double length, bool fence) {
  MeshBuilder b;
  b.semantic(fence ? SemanticClass::kFence : SemanticClass::kGuardRail).material(steel());
  const int posts = std::max(2, static_cast<int>(std::ceil(length / 2.0)) + 1);
  for (int i = 0; i < posts; ++i) {
    const double x = length * i / (posts - 1);
    if (fence) {
      b.tube({x, 0, 0}, {x, 0, 1.8}, 0.03, 0.03, 6, true);
    } else {
      b.box({x - 0.05, -0.08, 0.0}, {x + 0.05, 0.0, 0.75});
    }
  }
  if (fence) {
    // Galvanised wire mesh: seen from the road mostly the light wires against what is behind.
    Material mesh_panel = materials::plain("fence panel", linear_rgb(168, 172, 166), 0.6);
    mesh_panel.pattern = Pattern::kMetalGrid;
    mesh_panel.secondary = linear_rgb(92, 98, 90);
    b.material(mesh_panel);
    b.box({0, -0.01, 0.05}, {length, 0.01, 1.75});
  } else {
    b.box({0, 0.0, 0.48}, {length, 0.12, 0.78});  // the W beam, towards the road (+y)
  }
  return b.take();
}

}  // namespace corsa::sensors::detail
