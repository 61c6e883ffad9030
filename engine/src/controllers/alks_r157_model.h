#pragma once

// The run state of esmini's ALKS_R157SM_Controller (controllers/alks_r157.h) and its models'
// decisions: what the ego sees of an object, which object it focuses on, and, step by step, how
// the Regulation and ReferenceDriver models judge and react (esmini's Model::Step). Units: m,
// m/s, m/s^2, s; road frame: s along the reference line, t to its left.

#include <cstdint>
#include <optional>
#include <vector>

#include "corsa/engine/entity_state.h"

namespace corsa::engine::detail {

struct SimState;

inline constexpr double kAlksLarge = 1e10;   // esmini's LARGE_NUMBER: "none"
inline constexpr double kAlksSmall = 1e-10;  // esmini's SMALL_NUMBER

enum class AlksModel : uint8_t { kRegulation, kReferenceDriver };
enum class AlksScenario : uint8_t { kNone, kCutIn, kCutOut, kDeceleration };
enum class AlksMode : uint8_t { kCritical, kTargetInSight, kNoTarget };
enum class AlksPhase : uint8_t { kInactive, kPerceive, kReact, kBrakeRef };

/// The Properties of the controller (esmini's names in brackets).
struct AlksSettings {
  AlksModel model = AlksModel::kReferenceDriver;  ///< [model]
  bool cruise = true;                             ///< [cruise]: car following when not critical
  bool full_stop = false;             ///< [fullStop]: once critical, brake until standstill
  bool always_trig = false;           ///< [alwaysTrigOnScenario]: react also when not critical
  bool perceive_by_time = false;      ///< [cutInPerceptionDelayMode] Time (else Dist, 0.72 m)
  double pedestrian_risk_time = 0.4;  ///< s [pedestrianRiskEvaluationTime]
  double aeb_ttc = 1.5;               ///< s [aebTTC]
  /// m [lateralTrigDistance]: given, it replaces the lane wandering threshold as the cut-in
  /// trigger (esmini makes the trigger whenever the property exists, also at 0).
  std::optional<double> lateral_trigger;
  double overlap_tolerance = 0.1;  ///< m [overlapTolerance]
};

/// What the ego sees of one entity this step.
struct AlksSeen {
  bool usable = false;  ///< placed, visible to traffic and on a lane
  bool vehicle = false;
  bool pedestrian = false;
  bool motorbike = false;
  RoadCoordinates road;
  double speed = 0.0;   ///< m/s
  double offset = 0.0;  ///< m, t from the centre of the lane it is in
  double h = 0.0;       ///< rad, world heading
  double h_rel = 0.0;   ///< rad, heading relative to the road's direction (+s)
  double v_s = 0.0;     ///< m/s along the road (+s)
  double v_t = 0.0;     ///< m/s across the road (+t)
  double acc_s = 0.0;   ///< m/s^2 along the road
  double lane_width = 0.0;
  double front_x = 0.0;  ///< m: front axle (vehicles) or half the box length ahead of the reference
  Box box;
  Pose pose;
};

/// esmini's ObjectInfo: an object and how it relates to the ego.
struct AlksObject {
  std::optional<uint32_t> entity;
  std::optional<uint32_t> cut_out_vehicle;
  double dist_long = kAlksLarge;  ///< m, free space along the road
  double dist_lat = kAlksLarge;   ///< m, free space across it
  double dv_s = 0.0;              ///< m/s, the ego's speed toward it along the road
  double dv_t = 0.0;              ///< m/s, the speed at which the two close in across the road
  double ttc = kAlksLarge;
  double thw = kAlksLarge;
  int d_lane = 0;  ///< -1, 0 or 1: its lane from the ego's (ids, as OpenDRIVE numbers them)
  AlksScenario action = AlksScenario::kNone;
};

/// A lateral trigger of the ReferenceDriver: armed on an object moving toward the ego at its t
/// then; fires once it has moved `threshold` metres across from there.
struct AlksLateralTrigger {
  bool wandering = true;  ///< the lane wandering trigger (else lateralTrigDistance's)
  double threshold = 0.0;
  bool active = false;
  std::optional<uint32_t> entity;
  double t0 = 0.0;
};

/// The ego's view for one step: every entity as seen (by index), and the ego's index.
struct AlksView {
  const SimState* state = nullptr;
  std::vector<AlksSeen> seen;
  uint32_t ego = 0;
  double dt = 0.01;
  /// Measures `info.entity` against the ego (esmini's Process): false, leaving `info` as it
  /// was, when the object is not ahead within `range` in the ego's or a neighbouring lane.
  bool measure(AlksObject& info, double range) const;
  /// Whether entity `other`'s box covers the ego's front line (esmini's OverlappingFront,
  /// better than a partial overlap), within `tolerance` metres.
  bool covers_front(uint32_t other, double tolerance) const;
};

struct AlksR157 {
  AlksSettings settings;
  bool pending_activation = true;  ///< the set speed is taken at the next step
  double set_speed = 0.0;
  double acc = 0.0;  ///< m/s^2, the model's last acceleration
  AlksMode mode = AlksMode::kNoTarget;
  AlksScenario scenario = AlksScenario::kNone;
  AlksPhase phase = AlksPhase::kInactive;
  double timer = 0.0;         ///< s, perception or reaction time left
  double perception_t = 0.0;  ///< m, the object's t when its cut-in was perceived
  bool aeb = false;
  AlksObject focus;
  AlksLateralTrigger trigger;
};

/// One step of the model (esmini's Model::Step): the ego's speed at the end of the step.
double alks_step(AlksR157& alks, const AlksView& view);

}  // namespace corsa::engine::detail
