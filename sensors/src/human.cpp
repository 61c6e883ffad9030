// People: a skeleton in human proportions (segment lengths as shares of the stature, after
// Drillis and Contini's anthropometric table), a body of lofted and tubular parts each rigidly on
// its bone, clothing and build drawn from the seed, and postures: a walk cycle driven by the
// distance walked, standing, pedalling (two-bone leg reach to the pedals) and riding.

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "scalar_math.h"
#include "vehicle_generators.h"

namespace corsa::sensors::detail {
namespace {

/// Joint heights and offsets as shares of the stature (standing, arms hanging).
struct Joints {
  Vec3 pelvis, lumbar, neck, shoulder_l, elbow_l, wrist_l, hip_l, knee_l, ankle_l;
};

Joints joints_of(const PersonLook& p) {
  const double s = p.stature;
  Joints j;
  j.pelvis = {0.0, 0.0, 0.56 * s};
  j.lumbar = {0.0, 0.0, 0.62 * s};
  j.neck = {0.0, 0.0, 0.835 * s};
  j.shoulder_l = {0.0, 0.112 * s * p.shoulders, 0.805 * s};
  j.elbow_l = {0.0, 0.124 * s * p.shoulders, 0.625 * s};
  j.wrist_l = {0.0, 0.128 * s * p.shoulders, 0.485 * s};
  // Hip joint centres about a tenth of the stature apart; knees and ankles a little closer.
  j.hip_l = {0.0, 0.052 * s * std::sqrt(p.build), 0.53 * s};
  j.knee_l = {0.0, 0.047 * s, 0.285 * s};
  j.ankle_l = {0.0, 0.045 * s, 0.045 * s};
  return j;
}

Vec3 mirror(Vec3 v) { return {v.x, -v.y, v.z}; }

/// A limb segment: a tapered tube between two joints with rounded ends.
void limb(MeshBuilder& b, Vec3 a, Vec3 c, double r0, double r1) {
  b.tube(a, c, r0, r1, 10, false);
  b.ellipsoid(a, {r0, r0, r0}, Mat3{}, 10, 6);
  b.ellipsoid(c, {r1, r1, r1}, Mat3{}, 10, 6);
}

/// An elliptic cross-section ring at height z with half width w and half depth d, squared off a
/// little (exponent 2.4) as torsos are.
std::vector<Vec3> section(double z, double w, double d, double x_shift) {
  std::vector<Vec3> ring;
  const int n = 16;
  for (int i = 0; i < n; ++i) {
    const double t = 2.0 * kPi * i / n;
    const double c = std::cos(t);
    const double s = std::sin(t);
    const double e = 2.0 / 2.4;
    const double x = d * std::copysign(std::pow(std::fabs(c), e), c);
    const double y = w * std::copysign(std::pow(std::fabs(s), e), s);
    ring.push_back({x + x_shift, y, z});
  }
  return ring;
}

Material cloth(const char* name, Rgb8 c) {
  Material m = materials::plain(name, linear_rgb(c.r, c.g, c.b), 0.85);
  return m;
}

/// Rotation taking unit vector a onto unit vector b (Rodrigues).
Mat3 rotation_between(Vec3 a, Vec3 b) {
  const Vec3 v = cross(a, b);
  const double c = dot(a, b);
  const double s = norm(v);
  Mat3 r;
  if (s < 1e-12) {
    if (c > 0.0) {
      return r;
    }
    // Opposite: half a turn about any perpendicular axis.
    Vec3 e1, e2;
    perpendicular_basis(a, e1, e2);
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) {
        const double ei[3] = {e1.x, e1.y, e1.z};
        r.m[i][j] = 2.0 * ei[i] * ei[j] - (i == j ? 1.0 : 0.0);
      }
    }
    return r;
  }
  const Vec3 k = v * (1.0 / s);
  const double K[3][3] = {{0, -k.z, k.y}, {k.z, 0, -k.x}, {-k.y, k.x, 0}};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      double kk = 0.0;
      for (int m = 0; m < 3; ++m) {
        kk += K[i][m] * K[m][j];
      }
      r.m[i][j] = (i == j ? 1.0 : 0.0) + s * K[i][j] + (1.0 - c) * kk;
    }
  }
  return r;
}

Mat3 rot_y(double a) { return rigid_from_pose(0, 0, 0, 0, a, 0).rotation; }
Mat3 rot_x(double a) { return rigid_from_pose(0, 0, 0, 0, 0, a).rotation; }
Mat3 rot_z(double a) { return rigid_from_pose(0, 0, 0, a, 0, 0).rotation; }

/// A posed joint frame: where the joint is and how the segment below it is turned.
struct Frame {
  Mat3 r;
  Vec3 p;
};

/// The bone transform of a segment whose rest joint is at `rest` and posed frame is `f`.
Rigid bone_of(const Frame& f, Vec3 rest) {
  Rigid t;
  t.rotation = f.r;
  t.translation = f.p - f.r * rest;
  return t;
}

/// A child joint's frame: `offset` from the parent joint in the parent's rest frame, turned by
/// `local` relative to the parent.
Frame child(const Frame& parent, Vec3 offset, const Mat3& local) {
  return {parent.r * local, parent.p + parent.r * offset};
}

/// Two-bone reach in a plane: the middle joint for segments l1, l2 from `root` to `target`,
/// bent towards `bend` (a direction).
Vec3 middle_joint(Vec3 root, Vec3 target, double l1, double l2, Vec3 bend) {
  Vec3 d = target - root;
  double dist = norm(d);
  dist = std::clamp(dist, std::fabs(l1 - l2) + 1e-4, l1 + l2 - 1e-4);
  const Vec3 dir = normalized(d);
  const double a = (l1 * l1 - l2 * l2 + dist * dist) / (2.0 * dist);
  const double h = std::sqrt(std::max(0.0, l1 * l1 - a * a));
  Vec3 side = bend - dir * dot(bend, dir);
  side = normalized(side);
  return root + dir * a + side * h;
}

}  // namespace

PersonLook draw_person_look(double stature, RandomStream& rng) {
  PersonLook p;
  p.stature = std::clamp(stature, 0.8, 2.3);
  p.build = rng.uniform(0.88, 1.22);
  p.shoulders = rng.uniform(0.9, 1.08);
  static constexpr std::array<Rgb8, 11> kTops = {{{25, 25, 28},
                                                  {30, 38, 70},
                                                  {105, 106, 112},
                                                  {222, 222, 216},
                                                  {188, 168, 138},
                                                  {52, 70, 50},
                                                  {150, 32, 36},
                                                  {52, 90, 160},
                                                  {96, 70, 50},
                                                  {150, 180, 210},
                                                  {206, 176, 60}}};
  static constexpr std::array<double, 11> kTopShares = {20, 12, 12, 12, 8, 6, 6, 8, 6, 6, 4};
  static constexpr std::array<Rgb8, 5> kBottoms = {
      {{44, 58, 92}, {24, 24, 27}, {88, 88, 94}, {168, 148, 112}, {32, 36, 60}}};
  static constexpr std::array<double, 5> kBottomShares = {35, 30, 15, 12, 8};
  static constexpr std::array<Rgb8, 5> kSkins = {
      {{226, 192, 166}, {214, 172, 140}, {196, 150, 116}, {160, 112, 80}, {112, 78, 56}}};
  static constexpr std::array<double, 5> kSkinShares = {30, 30, 20, 12, 8};
  static constexpr std::array<Rgb8, 5> kHairs = {
      {{18, 16, 16}, {48, 34, 24}, {92, 62, 40}, {150, 148, 145}, {196, 166, 108}}};
  static constexpr std::array<double, 5> kHairShares = {55, 20, 12, 8, 5};
  static constexpr std::array<Rgb8, 4> kShoes = {
      {{20, 20, 22}, {230, 230, 228}, {90, 64, 44}, {70, 72, 78}}};
  static constexpr std::array<double, 4> kShoeShares = {45, 25, 15, 15};
  p.top = cloth("top", kTops[rng.weighted_index(kTopShares)]);
  p.bottom = cloth("bottom", kBottoms[rng.weighted_index(kBottomShares)]);
  p.skin = cloth("skin", kSkins[rng.weighted_index(kSkinShares)]);
  p.skin.roughness = 0.6;
  p.hair = cloth("hair", kHairs[rng.weighted_index(kHairShares)]);
  p.shoes = cloth("shoes", kShoes[rng.weighted_index(kShoeShares)]);
  p.long_sleeves = rng.uniform01() < 0.6;
  p.skirt = rng.uniform01() < 0.12;
  p.long_hair = rng.uniform01() < 0.3;
  // Names carry the colours so that two people's materials never merge in the scene's table.
  auto tag = [](Material& m) {
    m.name += " " + std::to_string(static_cast<int>(m.base_color.r * 1000)) + "/" +
              std::to_string(static_cast<int>(m.base_color.g * 1000)) + "/" +
              std::to_string(static_cast<int>(m.base_color.b * 1000));
  };
  tag(p.top);
  tag(p.bottom);
  tag(p.skin);
  tag(p.hair);
  tag(p.shoes);
  return p;
}

void add_person(MeshBuilder& b, const PersonLook& p, const PersonPlacement& where) {
  const double s = p.stature;
  const double g = p.build;
  const Joints j = joints_of(p);
  const Rigid keep = b.transform();
  // Rest pose around the placement's ground point (riders are placed by their hip); the
  // entity frame, whatever transform the builder had.
  const Vec3 base = where.by_hip ? where.ground - Vec3{0.0, 0.0, j.hip_l.z} : where.ground;
  Rigid at;
  at.translation = base;
  b.transform(at);
  b.semantic(where.semantic);
  auto bone = [&](Bone bn) {
    b.bone(static_cast<uint8_t>(where.first_bone + bn - 1));
    return &b;
  };
  // Pelvis and lower torso (trousers), then chest and shoulders (top).
  bone(kBonePelvis)->material(p.bottom);
  std::vector<std::vector<Vec3>> lower = {
      section(0.47 * s, 0.07 * s * g, 0.058 * s * g, 0.0),
      section(0.52 * s, 0.093 * s * g, 0.066 * s * g, -0.005 * s),
      section(0.58 * s, 0.09 * s * g, 0.062 * s * g, -0.004 * s),
      section(0.62 * s, 0.083 * s * g, 0.06 * s * g, 0.0)};
  b.loft(lower, true);
  bone(kBoneTorso)->material(p.top);
  std::vector<std::vector<Vec3>> upper = {
      section(0.60 * s, 0.088 * s * g, 0.062 * s * g, 0.0),
      section(0.67 * s, 0.086 * s * g, 0.062 * s * g, 0.002 * s),
      section(0.74 * s, 0.097 * s * g, 0.07 * s * g, 0.006 * s),
      section(0.785 * s, 0.104 * s * p.shoulders * std::sqrt(g), 0.066 * s * g, 0.004 * s),
      section(0.815 * s, 0.096 * s * p.shoulders, 0.05 * s, 0.0),
      section(0.84 * s, 0.045 * s, 0.04 * s, 0.0)};
  b.loft(upper, true);
  // Neck and head (head on its own bone).
  bone(kBoneHead)->material(p.skin);
  b.tube({0.0, 0.0, 0.82 * s}, {0.005 * s, 0.0, 0.885 * s}, 0.03 * s, 0.028 * s, 10, false);
  const Vec3 head{0.008 * s, 0.0, 0.933 * s};
  b.ellipsoid(head, {0.056 * s, 0.046 * s, 0.066 * s}, Mat3{}, 14, 10);
  b.material(p.hair);
  b.ellipsoid(head + Vec3{-0.008 * s, 0.0, 0.012 * s}, {0.058 * s, 0.049 * s, 0.06 * s}, Mat3{}, 14,
              10);
  if (p.long_hair) {
    b.ellipsoid(head + Vec3{-0.03 * s, 0.0, -0.06 * s}, {0.035 * s, 0.05 * s, 0.08 * s}, Mat3{}, 10,
                8);
  }
  // Arms.
  for (int side : {1, -1}) {
    const bool left = side > 0;
    const Vec3 sh = left ? j.shoulder_l : mirror(j.shoulder_l);
    const Vec3 el = left ? j.elbow_l : mirror(j.elbow_l);
    const Vec3 wr = left ? j.wrist_l : mirror(j.wrist_l);
    bone(left ? kBoneUpperArmL : kBoneUpperArmR)->material(p.top);
    limb(b, sh, el, 0.027 * s * g, 0.022 * s * g);
    bone(left ? kBoneForearmL : kBoneForearmR)->material(p.long_sleeves ? p.top : p.skin);
    limb(b, el, wr, 0.022 * s * g, 0.017 * s);
    b.material(p.skin);
    b.ellipsoid(wr + Vec3{0.0, 0.0, -0.045 * s}, {0.02 * s, 0.013 * s, 0.048 * s}, Mat3{}, 8, 6);
  }
  // Legs.
  for (int side : {1, -1}) {
    const bool left = side > 0;
    const Vec3 hip = left ? j.hip_l : mirror(j.hip_l);
    const Vec3 knee = left ? j.knee_l : mirror(j.knee_l);
    const Vec3 ankle = left ? j.ankle_l : mirror(j.ankle_l);
    bone(left ? kBoneThighL : kBoneThighR)->material(p.bottom);
    limb(b, hip, knee, 0.047 * s * g, 0.033 * s * std::sqrt(g));
    bone(left ? kBoneShinL : kBoneShinR)->material(p.skirt ? p.skin : p.bottom);
    limb(b, knee, ankle, 0.034 * s * std::sqrt(g), 0.022 * s);
    bone(left ? kBoneFootL : kBoneFootR)->material(p.shoes);
    b.ellipsoid(ankle + Vec3{0.045 * s, 0.0, -0.018 * s}, {0.078 * s, 0.031 * s, 0.028 * s}, Mat3{},
                10, 6);
  }
  if (p.skirt) {
    bone(kBonePelvis)->material(p.bottom);
    b.tube({0.0, 0.0, 0.56 * s}, {0.0, 0.0, 0.36 * s}, 0.1 * s * g, 0.14 * s * g, 14, true);
  }
  b.bone(0);
  b.transform(keep);
}

void pose_person(const PersonLook& p, const PersonPlacement& where, Posture posture, double phase,
                 double amplitude, std::vector<Rigid>& bones) {
  const double s = p.stature;
  const Joints j = joints_of(p);
  const bool rider =
      posture == Posture::kCycle || posture == Posture::kRideMotorbike || posture == Posture::kSit;
  const Vec3 base = where.by_hip ? where.ground - Vec3{0.0, 0.0, j.hip_l.z} : where.ground;
  const uint8_t b0 = where.first_bone;
  auto set = [&](Bone bn, const Frame& f, Vec3 rest) {
    const size_t i = b0 + bn - 1;
    if (i < bones.size()) {
      bones[i] = bone_of(f, rest + base);
    }
  };
  double lowest_ankle = 1e9;
  const double a = std::clamp(amplitude, 0.0, 1.3);
  const double w = 2.0 * kPi * phase;
  // Pelvis and torso.
  double lean = 3.0 * kDeg;
  double sway = 0.0;
  if (posture == Posture::kWalk) {
    sway = 0.01 * s * a * std::sin(w);
  } else if (posture == Posture::kCycle) {
    lean = 28.0 * kDeg;
  } else if (posture == Posture::kRideMotorbike) {
    lean = 22.0 * kDeg;
  } else if (posture == Posture::kSit) {
    lean = 0.0;
  }
  const Frame pelvis{posture == Posture::kWalk ? rot_z(4.0 * kDeg * a * std::sin(w)) : Mat3{},
                     base + j.pelvis + Vec3{0.0, sway, 0.0}};
  set(kBonePelvis, pelvis, j.pelvis);
  const Frame torso = child(
      pelvis, j.lumbar - j.pelvis,
      rot_y(lean) * (posture == Posture::kWalk ? rot_z(-7.0 * kDeg * a * std::sin(w)) : Mat3{}));
  set(kBoneTorso, torso, j.lumbar);
  // The head stays level with the horizon (riders look ahead).
  const Frame head = child(torso, j.neck - j.lumbar, rot_y(-0.8 * lean));
  set(kBoneHead, head, j.neck);
  // Legs.
  for (int side : {1, -1}) {
    const bool left = side > 0;
    const Vec3 hip = left ? j.hip_l : mirror(j.hip_l);
    const Vec3 knee = left ? j.knee_l : mirror(j.knee_l);
    const Vec3 ankle = left ? j.ankle_l : mirror(j.ankle_l);
    const double l1 = norm(knee - hip);
    const double l2 = norm(ankle - knee);
    const Frame hip_frame = child(pelvis, hip - j.pelvis, Mat3{});
    Mat3 thigh_r;
    Mat3 shin_r;
    if (posture == Posture::kWalk || posture == Posture::kStand) {
      const double ph = w + (left ? 0.0 : kPi);
      const double thigh = posture == Posture::kWalk ? (4.0 + 21.0 * std::sin(ph)) * kDeg * a : 0.0;
      const double swing = std::max(0.0, std::cos(ph + 0.1 * 2.0 * kPi));
      const double flex =
          posture == Posture::kWalk ? (5.0 + 58.0 * swing * swing) * kDeg * a : 2.0 * kDeg;
      thigh_r = rot_y(-thigh) * rot_x(side * (posture == Posture::kStand ? 2.0 : 1.0) * kDeg);
      shin_r = rot_y(flex);
    } else {
      // Reach for the pedal (cycling) or the foot peg (motorbike) with the knee bent forward.
      Vec3 target;
      if (posture == Posture::kCycle) {
        const double crank = phase + (left ? 0.0 : kPi);
        target = where.pedal_axis +
                 Vec3{where.crank * std::cos(crank), side * 0.11 * s / 1.75,
                      where.crank * std::sin(crank)} +
                 Vec3{0.0, 0.0, 0.05 * s / 1.75};
      } else {
        target = where.feet + Vec3{0.0, side * 0.16 * s / 1.75, 0.05 * s / 1.75};
      }
      const Vec3 h = hip_frame.p;
      const Vec3 k = middle_joint(h, target, l1, l2, {1.0, 0.0, 0.6});
      const Mat3 world_thigh = rotation_between({0.0, 0.0, -1.0}, normalized(k - h));
      const Mat3 world_shin = rotation_between({0.0, 0.0, -1.0}, normalized(target - k));
      thigh_r = hip_frame.r.transposed() * world_thigh;
      shin_r = world_thigh.transposed() * world_shin;
    }
    const Frame thigh = child(pelvis, hip - j.pelvis, thigh_r);
    set(left ? kBoneThighL : kBoneThighR, thigh, hip);
    const Frame shin = child(thigh, knee - hip, shin_r);
    set(left ? kBoneShinL : kBoneShinR, shin, knee);
    // Feet stay level with the ground.
    const Frame foot{Mat3{}, shin.p + shin.r * (ankle - knee)};
    set(left ? kBoneFootL : kBoneFootR, foot, ankle);
    lowest_ankle = std::min(lowest_ankle, foot.p.z);
  }
  // Arms.
  for (int side : {1, -1}) {
    const bool left = side > 0;
    const Vec3 sh = left ? j.shoulder_l : mirror(j.shoulder_l);
    const Vec3 el = left ? j.elbow_l : mirror(j.elbow_l);
    const Vec3 wr = left ? j.wrist_l : mirror(j.wrist_l);
    const Frame shoulder = child(torso, sh - j.lumbar, Mat3{});
    Mat3 upper_r;
    Mat3 fore_r;
    if (rider) {
      const Vec3 grip = where.hands + Vec3{0.0, side * 0.5 * where.hand_spread, 0.0};
      const double l1 = norm(el - sh);
      const double l2 = norm(wr - el) + 0.06 * s;
      const Vec3 e = middle_joint(shoulder.p, grip, l1, l2, {-0.3, side * 0.6, -1.0});
      const Mat3 world_upper = rotation_between({0.0, 0.0, -1.0}, normalized(e - shoulder.p));
      const Mat3 world_fore = rotation_between({0.0, 0.0, -1.0}, normalized(grip - e));
      upper_r = shoulder.r.transposed() * world_upper;
      fore_r = world_upper.transposed() * world_fore;
    } else {
      const double ph = w + (left ? kPi : 0.0);  // arms swing against the same-side leg
      const double swing = posture == Posture::kWalk ? 16.0 * kDeg * a * std::sin(ph) : 0.0;
      const double elbow =
          posture == Posture::kWalk ? (14.0 + 10.0 * (1.0 + std::sin(ph))) * kDeg * a : 8.0 * kDeg;
      upper_r = rot_y(-swing - lean) * rot_x(side * 6.0 * kDeg);
      fore_r = rot_y(-elbow);
    }
    const Frame upper = child(torso, sh - j.lumbar, upper_r);
    set(left ? kBoneUpperArmL : kBoneUpperArmR, upper, sh);
    const Frame fore = child(upper, el - sh, fore_r);
    set(left ? kBoneForearmL : kBoneForearmR, fore, el);
  }
  if (!rider) {
    // Whole body up or down so that the lower foot stands on the ground (the walk's bob).
    const double lift = base.z + j.ankle_l.z - lowest_ankle;
    for (int bn = kBonePelvis; bn < kBoneCount; ++bn) {
      const size_t i = b0 + bn - 1;
      if (i < bones.size()) {
        bones[i].translation.z += lift;
      }
    }
  }
}

}  // namespace corsa::sensors::detail
