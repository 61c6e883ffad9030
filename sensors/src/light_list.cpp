#include "light_list.h"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <numbers>

#include "brdf.h"
#include "scalar_math.h"
#include "scene_data.h"

namespace corsa::sensors::detail {
namespace {

constexpr uint32_t bit(LightRole r) { return 1u << static_cast<unsigned>(r); }

/// Photometry of a lamp by role: peak intensity (cd), pattern, range (m), emitter radius (m).
/// Orders of magnitude of real lamps: an LED street light of ~13 klm peaks at a few kcd, a low
/// beam at 10-20 kcd below its cut-off (UN ECE R112), a brake lamp at 60-185 cd (R7), a tail
/// lamp at 4-17 cd, a 200 mm signal bulb at a few hundred cd (EN 12368).
struct Photometry {
  double candela = 0.0;
  LightPattern pattern = LightPattern::kLambert;
  double range = 10.0;
  double radius = 0.05;
};

Photometry photometry(LightRole role) {
  switch (role) {
    case LightRole::kStreetLamp:
      return {4500.0, LightPattern::kStreetLamp, 60.0, 0.2};
    case LightRole::kHeadlight:
      return {12000.0, LightPattern::kLowBeam, 80.0, 0.06};
    case LightRole::kTail:
      return {10.0, LightPattern::kLambert, 6.0, 0.05};
    case LightRole::kBrake:
      return {80.0, LightPattern::kLambert, 12.0, 0.05};
    case LightRole::kIndicatorLeft:
    case LightRole::kIndicatorRight:
      return {150.0, LightPattern::kLambert, 12.0, 0.04};
    case LightRole::kReversing:
      return {250.0, LightPattern::kLambert, 15.0, 0.04};
    case LightRole::kSignalRed:
    case LightRole::kSignalYellow:
    case LightRole::kSignalGreen:
      // The on-axis 400 cd spread as a cosine would send out three times the flux of a real
      // signal head, whose beam is a narrow cone: the average intensity stands in for it.
      return {150.0, LightPattern::kLambert, 15.0, 0.08};
    default:
      return {};
  }
}

/// Unit colour of an emission (luminance 1).
Color hue(Color emission) {
  const double y = luminance(emission);
  return y > 0.0 ? emission * (1.0 / y) : Color{1.0, 1.0, 1.0};
}

Color rgb_color(const std::array<double, 3>& c) { return Color{c[0], c[1], c[2]}; }

/// Relative intensity of a pattern towards unit direction d (from the light).
double pattern_gain(const Light& l, Vec3 d) {
  const double c = dot(d, l.axis);
  switch (l.pattern) {
    case LightPattern::kStreetLamp: {
      // A full cut-off lantern of a street with lamps some four mounting heights apart: 0.8 of
      // the peak straight down, the peak from 45 to 60 degrees from the vertical, nothing from
      // 78 degrees up (half the peak at 70). The light falls on the road beneath and around the
      // lamp, a pool several times the light half-way to the next, instead of being thrown
      // tens of metres along the road, where it was seen mostly as the asphalt's sheen.
      if (c <= 0.2) {
        return 0.0;
      }
      const double s2 = 1.0 - c * c;
      double gain = (0.8 + 0.2 * std::min(1.0, s2 / 0.5)) * smoothstep(0.2, 0.5, c);
      if (norm(l.side) > 0.0) {
        // Towards the street across it (to two mounting heights out); behind the pole the
        // sidewalk (0.4 mounting heights back) and beyond it a spill of 30% on the houses.
        const double across = dot(d, l.side) / c;
        gain *= across >= 0.0 ? 1.0 - smoothstep(1.0, 2.0, across)
                              : 1.0 - 0.7 * smoothstep(0.4, 1.2, -across);
      }
      return gain;
    }
    case LightPattern::kLowBeam: {
      if (c <= 0.0) {
        return 0.0;
      }
      // Horizontal angle from the axis and elevation above the cut-off plane (radians).
      const Vec3 up = cross(l.axis, l.side);  // side is to the left: axis x left is up
      const double h = std::atan2(dot(d, l.side), c);
      const double v = std::asin(std::clamp(dot(d, up), -1.0, 1.0));
      const double fan = std::exp(-h * h / (2.0 * 0.30 * 0.30));
      const double below = 1.0 - smoothstep(-0.005, 0.02, v);  // the cut-off
      // Below the hot spot the intensity falls steeply (about a tenth at 8 degrees down and a
      // hundredth at 18, as measured beams do), so the road just ahead of the bumper is not the
      // brightest part.
      const double drop = std::max(0.0, -v - 0.03);
      const double deep = 0.96 * std::exp(-drop / 0.05) + 0.04 * std::exp(-drop / 0.15);
      return fan * (0.03 + 0.97 * below) * deep;
    }
    case LightPattern::kLambert:
      return norm(l.axis) > 0.0 ? std::max(0.0, c) : 1.0;  // no axis: all round
  }
  return 0.0;
}

}  // namespace

LightSample illuminate(const Light& l, Vec3 p) {
  LightSample s;
  const Vec3 to = l.position - p;
  const double d2 = dot(to, to);
  const double r2 = l.range * l.range;
  if (d2 >= r2 || d2 < 1e-8) {
    return s;
  }
  const double d = std::sqrt(d2);
  s.distance = d;
  s.direction = to * (1.0 / d);
  const double gain = pattern_gain(l, -s.direction);
  if (gain <= 0.0) {
    return s;
  }
  // Inverse square law windowed to zero at the range (Karis 2013), and never closer than the
  // emitter's size.
  const double q = d2 / r2;
  const double window = (1.0 - q * q) * (1.0 - q * q);
  s.irradiance = l.intensity * (gain * window / std::max(d2, l.radius * l.radius));
  return s;
}

std::vector<LampPatch> find_lamps(std::span<const Vec3> vertices,
                                  std::span<const std::array<uint32_t, 3>> triangles,
                                  std::span<const LightRole> roles,
                                  std::span<const Color> emissions,
                                  std::span<const uint32_t> bones) {
  std::vector<LampPatch> out;
  std::vector<Vec3> sums;  // area-weighted centre sums
  for (size_t i = 0; i < triangles.size(); ++i) {
    if (roles[i] == LightRole::kNone || roles[i] == LightRole::kAlways) {
      continue;
    }
    const Vec3 a = vertices[triangles[i][0]];
    const Vec3 b = vertices[triangles[i][1]];
    const Vec3 c = vertices[triangles[i][2]];
    const Vec3 n2 = cross(b - a, c - a);
    const double area = 0.5 * norm(n2);
    if (!(area > 0.0)) {
      continue;
    }
    const Vec3 centre = (a + b + c) * (1.0 / 3.0);
    const uint32_t bone = bones.empty() ? 0 : bones[i];
    LampPatch* into = nullptr;
    for (size_t k = 0; k < out.size() && into == nullptr; ++k) {
      LampPatch& p = out[k];
      const Vec3 at = sums[k] * (1.0 / p.area);
      const bool same_side = (at.y >= 0.0) == (centre.y >= 0.0) || std::fabs(centre.y) < 0.2;
      if (p.role == roles[i] && p.bone == bone && same_side && norm(at - centre) < 0.6) {
        into = &p;
        sums[k] = sums[k] + centre * area;
      }
    }
    if (into == nullptr) {
      out.push_back({roles[i], {}, {}, 0.0, emissions[i], -1, bone, {}});
      sums.push_back(centre * area);
      into = &out.back();
    }
    into->area += area;
    into->normal = into->normal + n2 * 0.5;
  }
  for (size_t k = 0; k < out.size(); ++k) {
    out[k].centre = sums[k] * (1.0 / out[k].area);
    // Closed lenses (boxes, capped discs) have normals that cancel: no direction of their own.
    const double consistency = norm(out[k].normal) / out[k].area;
    out[k].normal = consistency > 0.5 ? normalized(out[k].normal) : Vec3{};
  }
  return out;
}

LampLooks lamp_looks(const engine::EntitySnapshot& entity) {
  LampLooks out{};
  using engine::VehicleLight;
  auto look_of = [&](VehicleLight v) -> const engine::LightLook* {
    for (const engine::LightLook& look : entity.light_looks) {
      if (look.light == v && (entity.lights_on & engine::light_bit(v)) != 0) {
        return &look;
      }
    }
    return nullptr;
  };
  auto first = [&](std::initializer_list<VehicleLight> lights) -> const engine::LightLook* {
    for (VehicleLight v : lights) {
      if (const engine::LightLook* look = look_of(v)) {
        return look;
      }
    }
    return nullptr;
  };
  if (entity.light_looks.empty()) {
    return out;
  }
  out[static_cast<size_t>(LightRole::kHeadlight)] =
      first({VehicleLight::kLowBeam, VehicleLight::kHighBeam, VehicleLight::kDaytimeRunning});
  out[static_cast<size_t>(LightRole::kBrake)] = first({VehicleLight::kBrake});
  out[static_cast<size_t>(LightRole::kIndicatorLeft)] =
      first({VehicleLight::kIndicatorLeft, VehicleLight::kWarning});
  out[static_cast<size_t>(LightRole::kIndicatorRight)] =
      first({VehicleLight::kIndicatorRight, VehicleLight::kWarning});
  out[static_cast<size_t>(LightRole::kReversing)] = first({VehicleLight::kReversing});
  return out;
}

Color looked_emission(const engine::LightLook& look, LightRole role, Color own) {
  // EntitySnapshot::LightLook: fixed_cd + lamp_colour_cd * h + I0 * (colour_share +
  // lamp_share * h) with h = hue(own), scaled from cd to the units of `own` (I0 emits `own`).
  const double own_cd = photometry(role).candela;
  const double y = luminance(own);
  if (own_cd <= 0.0 || y <= 0.0) {
    return own * look.lamp_share;
  }
  const Color h = hue(own);
  const Color cd = rgb_color(look.fixed_cd) + h * look.lamp_colour_cd;
  return cd * (y / own_cd) + rgb_color(look.colour_share) * y + own * look.lamp_share;
}

LightList::LightList(const SceneData& d, std::span<const uint32_t> entity_lamps,
                     std::span<const LampLooks> looks, uint32_t static_lamps, double floor) {
  auto keep = [&](const Light& l) {
    if (luminance(l.intensity) / 4.0 >= floor) {
      add(l);
    }
  };
  for (const LampPatch& p : d.static_lamps) {
    bool lit = false;
    if (p.signal >= 0) {
      const int k = p.role == LightRole::kSignalRed      ? 0
                    : p.role == LightRole::kSignalYellow ? 1
                                                         : 2;
      lit = (d.signal_bulbs[p.signal] >> k) & 1u;
    } else {
      lit = (static_lamps & bit(p.role)) != 0;
    }
    const Photometry ph = photometry(p.role);
    if (!lit || ph.candela <= 0.0) {
      continue;
    }
    Light l;
    // Emitters face the way their lens does: the street lamp's diffuser down, bulbs outwards.
    l.axis = p.role == LightRole::kStreetLamp ? Vec3{0.0, 0.0, -1.0} : p.normal;
    l.side = p.role == LightRole::kStreetLamp ? p.reach : Vec3{};
    l.position = p.centre + l.axis * 0.02;
    l.intensity = hue(p.emission) * (ph.candela / 100000.0);
    l.range = ph.range;
    l.radius = ph.radius;
    l.pattern = ph.pattern;
    keep(l);
  }
  for (size_t i = 0; i < d.instances.size(); ++i) {
    const EntityInstance& inst = d.instances[i];
    const uint32_t lit = i < entity_lamps.size() ? entity_lamps[i] : 0u;
    for (const LampPatch& p : inst.shape->lamps) {
      const Photometry ph = photometry(p.role);
      if (!(lit & bit(p.role)) || ph.candela <= 0.0) {
        continue;
      }
      const Rigid& w = inst.world_from_entity;
      Light l;
      const Vec3 forward = w.apply_direction({1.0, 0.0, 0.0});
      if (ph.pattern == LightPattern::kLowBeam) {
        // Aimed 1 degree down along the vehicle (ECE R48 aiming), whatever the lens shape.
        const Vec3 left = w.apply_direction({0.0, 1.0, 0.0});
        const double dip = 0.0175;
        l.axis = normalized(forward * std::cos(dip) - cross(forward, left) * std::sin(dip));
        l.side = left;
      } else {
        // A lens without a direction of its own shines to the front or the back it sits at.
        const Vec3 n = norm(p.normal) > 0.0 ? p.normal : Vec3{p.centre.x >= 0.0 ? 1.0 : -1.0, 0, 0};
        l.axis = w.apply_direction(n);
      }
      l.position = d.to_local(w.apply(p.centre)) + l.axis * 0.05;
      l.intensity = hue(p.emission) * (ph.candela / 100000.0);
      const auto role = static_cast<size_t>(p.role);
      if (i < looks.size() && role < looks[i].size() && looks[i][role] != nullptr) {
        l.intensity = looked_emission(*looks[i][role], p.role, l.intensity);
      }
      l.range = ph.range;
      l.radius = ph.radius;
      l.pattern = ph.pattern;
      keep(l);
    }
  }
  build_grid();
}

void LightList::add(const Light& light) { lights_.push_back(light); }

void LightList::build_grid() {
  if (lights_.empty()) {
    return;
  }
  double x_min = 1e300, x_max = -1e300, y_min = 1e300, y_max = -1e300;
  for (const Light& l : lights_) {
    x_min = std::min(x_min, l.position.x - l.range);
    x_max = std::max(x_max, l.position.x + l.range);
    y_min = std::min(y_min, l.position.y - l.range);
    y_max = std::max(y_max, l.position.y + l.range);
  }
  // 10 m cells, coarser on huge maps (at most 512 x 512 cells).
  cell_ = std::max({10.0, (x_max - x_min) / 512.0, (y_max - y_min) / 512.0});
  x0_ = x_min;
  y0_ = y_min;
  nx_ = static_cast<int>(std::ceil((x_max - x_min) / cell_)) + 1;
  ny_ = static_cast<int>(std::ceil((y_max - y_min) / cell_)) + 1;
  std::vector<std::vector<std::pair<double, uint32_t>>> cells(static_cast<size_t>(nx_) * ny_);
  for (uint32_t i = 0; i < lights_.size(); ++i) {
    const Light& l = lights_[i];
    const int cx0 = static_cast<int>((l.position.x - l.range - x0_) / cell_);
    const int cx1 = static_cast<int>((l.position.x + l.range - x0_) / cell_);
    const int cy0 = static_cast<int>((l.position.y - l.range - y0_) / cell_);
    const int cy1 = static_cast<int>((l.position.y + l.range - y0_) / cell_);
    for (int cy = std::max(cy0, 0); cy <= std::min(cy1, ny_ - 1); ++cy) {
      for (int cx = std::max(cx0, 0); cx <= std::min(cx1, nx_ - 1); ++cx) {
        // Distance from the light to the cell (0 inside it), against the range.
        const double px = std::clamp(l.position.x, x0_ + cx * cell_, x0_ + (cx + 1) * cell_);
        const double py = std::clamp(l.position.y, y0_ + cy * cell_, y0_ + (cy + 1) * cell_);
        const double dx = px - l.position.x, dy = py - l.position.y;
        const double d2 = dx * dx + dy * dy;
        if (d2 >= l.range * l.range) {
          continue;
        }
        // Strength at the cell's centre ranks the lights when a cell has too many.
        const double cxm = x0_ + (cx + 0.5) * cell_ - l.position.x;
        const double cym = y0_ + (cy + 0.5) * cell_ - l.position.y;
        const double strength = luminance(l.intensity) / (cxm * cxm + cym * cym + 25.0);
        cells[static_cast<size_t>(cy) * nx_ + cx].push_back({strength, i});
      }
    }
  }
  offsets_.assign(cells.size() + 1, 0);
  for (size_t c = 0; c < cells.size(); ++c) {
    auto& list = cells[c];
    if (list.size() > kMaxLightsPerCell) {
      // Strongest first; equal strengths by index, so the choice never depends on anything else.
      std::partial_sort(list.begin(), list.begin() + kMaxLightsPerCell, list.end(),
                        [](const auto& a, const auto& b) {
                          return a.first != b.first ? a.first > b.first : a.second < b.second;
                        });
      list.resize(kMaxLightsPerCell);
      std::sort(list.begin(), list.end(),
                [](const auto& a, const auto& b) { return a.second < b.second; });
    }
    for (const auto& e : list) {
      indices_.push_back(e.second);
    }
    offsets_[c + 1] = static_cast<uint32_t>(indices_.size());
  }
}

std::span<const uint32_t> LightList::near(Vec3 p) const {
  if (nx_ == 0) {
    return {};
  }
  const double fx = (p.x - x0_) / cell_;
  const double fy = (p.y - y0_) / cell_;
  if (!(fx >= 0.0) || !(fy >= 0.0) || fx >= nx_ || fy >= ny_) {
    return {};
  }
  const size_t c = static_cast<size_t>(static_cast<int>(fy)) * nx_ + static_cast<int>(fx);
  return {indices_.data() + offsets_[c], offsets_[c + 1] - offsets_[c]};
}

}  // namespace corsa::sensors::detail
