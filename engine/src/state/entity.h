#pragma once

// One entity's run state inside the engine: the public EntityInfo / EntityState plus what the
// default controller and the conditions need between steps.

#include <array>
#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <type_traits>
#include <utility>

#include "corsa/engine/entity_state.h"
#include "corsa/engine/world_snapshot.h"
#include "corsa/xodr/lane_graph.h"
#include "corsa/xodr/map.h"
#include "corsa/xodr/map_parts.h"
#include "corsa/xosc/enums.h"
#include "state/out_of_line.h"

namespace corsa::xosc {
struct ScenarioObject;
}

namespace corsa::engine::detail {

class ActionInstance;
class LaneChooser;

/// How the default controller holds an entity on the road: the lane it follows (nominal lane;
/// during a lane change already the target lane), where along it, and the lateral offset.
struct LaneFollow {
  bool on_road = false;  ///< false: the entity moves freely along its heading
  uint32_t road = 0;
  uint32_t section = 0;
  int lane = 0;
  xodr::LaneNode node = xodr::kNoLane;
  double s = 0.0;
  int dir = 1;  ///< +1 drives toward +s, -1 toward -s
  /// Offset (m) of the reference point from the nominal lane's centre, positive to the left of
  /// the direction of travel (so that it keeps its meaning across roads of opposite s).
  double lateral = 0.0;
  /// Heading (rad) relative to the lane's direction of travel, from lateral motion.
  double heading_offset = 0.0;
  /// Sum (m, left of travel) of the shifts of `lateral` made when a route carried the entity on
  /// from the end of a neighbouring lane (LaneChooser::redirect): an offset commanded before
  /// such a shift is moved by it, so that the entity keeps its place across the lane end.
  double frame_shift = 0.0;
};

/// The lane position an entity's pose and road coordinates were last computed from, and what
/// they were (motion/controller.h, update_pose_from_lane): while neither has changed since (a
/// standing entity), the same pose follows without asking the map again.
struct LanePoseMemo {
  bool valid = false;
  LaneFollow from;
  Pose pose;
  std::optional<RoadCoordinates> road;
};

/// What the default controller's step reads and writes of an entity (motion/controller.h,
/// DefaultController): besides the map, the step and the entity's memos of the map's answers
/// (LanePoseMemo, PointLocateMemo, which give what the map would), the step is a function of
/// these fields alone, and it is handed nothing else of the entity. Entity holds them as its
/// first part. A field the step reads or writes belongs here: the still step memo
/// (Entity::still_step) copies this whole part and compares it field by field (same_bits in
/// state/sim_state.h, whose size checks refuse a field it does not compare).
struct EntityMotion {
 public:
  /// The entity's state (what the run shows of it, and the trajectories record).
  const EntityState& state() const { return state_; }
  /// The state to write: every write of it goes through here, which counts it (state_changes),
  /// so that while the count stays the state is the same, bit for bit. Take it where the state is
  /// written, not ahead: a reference kept past the write is a later write not counted.
  EntityState& write_state() {
    ++changes_;
    return state_;
  }
  /// How many times the state was taken for writing (write_state; 32 bits, wrapping): a reader
  /// that saw the state at some count sees the same state while the count is that. (The binary
  /// recorder skips an entity that has not changed since its last row with one comparison, and
  /// the memos of what was computed from a state compare its count first.) A reference, where
  /// the count lies: Simulation::state_changes reads every entity's from the first one's.
  const uint32_t& state_changes() const { return changes_; }

 private:
  EntityState state_;

 public:
  LaneFollow lane;

  /// What the running actions ask for at the end of the current step: speed (m/s) and lateral
  /// offset (m, see LaneFollow::lateral). Controllers turn them into motion.
  double speed_command = 0.0;
  double lateral_command = 0.0;

  /// Metres driven along the lanes (the odometer without the lateral motion): the distance a
  /// lane change over a distance is measured in.
  double longitudinal_distance = 0.0;
  /// m/s^2 across the heading over the last step (AccelerationCondition, lateral).
  double lateral_acceleration = 0.0;

  bool end_of_road = false;  ///< stuck at a lane end without successor (EndOfRoadCondition)

 private:
  /// See state_changes (in the padding after end_of_road: the motion stays 248 bytes).
  uint32_t changes_ = 0;

 public:
  /// Chooses among lane successors at lane ends (a route); null: the straightest. Compared by
  /// address: whoever assigns it also drops the entity's still step memo, since a replaced route
  /// may be freed and its address reused by the next.
  const LaneChooser* chooser = nullptr;
};
// The still step memo copies EntityMotion by assignment; a trivial copy keeps that cheap.
static_assert(std::is_trivially_copyable_v<EntityMotion>);
static_assert(sizeof(EntityMotion) == 248);

/// The map's last answer, for one entity, to which lane holds the point (x, y) within half a
/// metre (motion/controller.h, locate_near): a controller that puts its entity at a vehicle
/// model's pose asks it three times a step for the same point, and a model at rest asks it
/// every step. The map does not change during a run, so the same point has the same answer.
struct PointLocateMemo {
  bool valid = false;
  double x = 0.0;  ///< m, the point asked for, compared bit for bit
  double y = 0.0;
  std::optional<xodr::LanePosition> located;
  /// m, when nothing was located: every point within this of (x, y) along each axis has no
  /// answer either (xodr::Map::clear_of_lanes), so an entity off the road that moves a little
  /// needs no search.
  double clear = 0.0;
  /// The road surface at `located` (motion/controller.h, surface_near), once asked for: like the
  /// answer, it holds while the point does.
  bool surface_valid = false;
  xodr::SurfacePose surface;
};

/// Where an entity is along its route and the lane change its route needs, under way
/// (motion/route_lanes.h). Reset when a route is assigned.
struct RouteProgress {
  size_t step = 0;      ///< first route step of the lane section the entity drives in
  bool joined = false;  ///< it has been on the route
  bool lost = false;    ///< it left the route (warned once)
  bool changing = false;
  double from = 0.0;            ///< m, LaneFollow::lateral where the lane change began
  double to = 0.0;              ///< m, LaneFollow::lateral it ends at
  double start_distance = 0.0;  ///< m, longitudinal_distance when it began
  double length = 0.0;          ///< m driven over which it is made
  double last_command = 0.0;    ///< m, the lateral command it gave last
};

/// Action domains that override each other on one entity (OpenSCENARIO 1.3 §7.4: a new
/// longitudinal or lateral action replaces the running one of the same domain).
enum ActionDomain : uint8_t {
  kDomainNone = 0,
  kDomainLongitudinal = 1,
  kDomainLateral = 2,
};
inline constexpr int kDomainSlots = 2;

/// A vehicle light a LightStateAction set (OpenSCENARIO 1.2 §7.4.3.5 LightStateAction).
struct LightSetting {
  using Mode = LightMode;
  Mode mode = Mode::kOn;
  double on_s = 0.5;              ///< flashing: s lit per cycle
  double off_s = 0.5;             ///< flashing: s dark per cycle
  double since = 0.0;             ///< simulation time it was set (flashing starts lit)
  std::optional<double> candela;  ///< LightState luminousIntensity; none: the lamp's own
  /// LightState Color as linear RGB (0..1 each); none: the lamp's own colour.
  std::optional<std::array<double, 3>> rgb;
  /// transitionTime (s): the light fades linearly from `previous` to this state from `since`.
  double transition_s = 0.0;
  /// The setting this one replaced (none: the light was unset, read as off); kept while the
  /// fade runs.
  std::shared_ptr<const LightSetting> previous;

  /// As the world snapshot and the run summary show it (light `light`).
  LightSettingView view(VehicleLight light) const {
    return {light, mode, candela, rgb, since, transition_s, on_s, off_s};
  }
};
inline constexpr size_t kVehicleLightCount = kVehicleLightTypes;

/// The lights an entity has had set (LightStateAction), by VehicleLight.
using LightSettings = std::array<std::optional<LightSetting>, kVehicleLightCount>;

/// The fields are in the order a step reads them: first what every step's passes over all
/// entities touch (the motion: state, lane, commands; then the flags, the still step memo's
/// count, trailer links, the route, the pose command, the lane pose memo, the box and
/// performance in `info`), then what only some entities or events need (the info's name and
/// model, the still step's copy of the motion, the condition timers, the actions owning the
/// domains, a removed entity's last place among them). With hundreds of vehicles the entities
/// no longer fit in a core's cache, and a step then costs the cache lines it reads of each
/// entity: the part up to `info.max_deceleration_rate` (576 of the entity's 1,248 bytes, nine
/// lines) is what the moves ask for ahead (controllers/controllers.cpp) and what the other
/// passes read; a field read or written every step does not belong below it.
struct Entity : EntityMotion {
  Entity() = default;
  /// An entity of the description `described` (state/entity_builder.h, describe_object).
  explicit Entity(EntityInfo described) : info(std::move(described)) {}

  /// Flags of the duration-based conditions (StandStill, Offroad, EndOfRoad; their timers are
  /// below, with what few steps read).
  bool standing_still = false;  ///< slower than 1e-3 m/s (state/world_update.cpp)
  bool was_offroad = false;
  bool was_at_end = false;  ///< EntityMotion::end_of_road at the last timers' update
  /// Set by a DeleteEntityAction (or a sink) until the entity is placed again; state.pose and
  /// removed_road keep where it was, which a position relative to it is read from (esmini's
  /// reading of a reference to a deleted entity, with a lenient-reading warning).
  bool removed = false;
  /// esmini's ghost of another entity (state/ghost_state.h): recorded, but no other entity,
  /// sensor or collision sees it.
  bool ghost = false;
  /// `still_step` holds the motion of a default-controller step that changed nothing (read every
  /// step; the motion itself only for an entity standing on its lane).
  bool still_step_valid = false;
  /// The state's count of writes (state_changes) when `still_step` was last found held: while
  /// the count is this, the state is the memo's. (Written every default-controller step.)
  uint32_t still_step_changes = 0;

  /// Trailers (§7.4.8): the entity towing this one, and the one this one tows.
  std::optional<uint32_t> towed_by;
  std::optional<uint32_t> towing;
  /// A trailer just disconnected from this entity: while their boxes still overlap at the hitch,
  /// that is no collision.
  std::optional<uint32_t> unhitched_from;

  /// Owns the route chooser (AssignRouteAction, AcquirePositionAction) `chooser` points at; every
  /// step tests it (motion/route_lanes.cpp).
  std::shared_ptr<const LaneChooser> route;
  /// A pose an action sets for the end of the step (FollowTrajectoryAction): the controller
  /// puts the entity there instead of moving it along its lane (motion/pose_command.h).
  /// Out of line: few entities have one, and every step tests it.
  OutOfLine<Pose> pose_command;
  LanePoseMemo lane_pose_memo;
  /// Its kind, box and performance are read every step, its name and model (last) by none.
  /// Fixed once the entity exists (given to its constructor; const, so that no later write
  /// compiles, and an entity is never assigned over another): what was computed from an
  /// entity's box holds for as long as the entity (the contacts' inputs, ContactInput, and the
  /// distance memos, EntityDistanceInputs, compare no box).
  const EntityInfo info{};

  // Below (with the info's name and model): what only some entities, or some events, read.
  /// The entity's motion around a default-controller step that changed nothing of it (one
  /// standing on its lane: asked for no speed, or for a speed it cannot take at a lane end with
  /// nothing beyond; motion/default_controller.cpp), while `still_step_valid`. That step is a
  /// function of EntityMotion (and of the map and the step, fixed for the run): while the entity
  /// holds exactly this again, field for field and bit for bit (same_bits: -0 and +0 differ, a
  /// NaN equals itself), the next step would change nothing either, and is skipped.
  EntityMotion still_step;
  /// Timers (s) for the duration-based conditions (StandStill, Offroad, EndOfRoad; the flags
  /// above): kept only while the storyboard has such a condition (SimState::timers_wanted).
  double standstill_time = 0.0;
  double offroad_time = 0.0;
  double end_of_road_time = 0.0;
  /// The running action that owns each domain (index 0 longitudinal, 1 lateral), or null.
  std::array<ActionInstance*, kDomainSlots> owners{};
  std::optional<RoadCoordinates> removed_road;  ///< see `removed`
  double removed_speed = 0.0;  ///< m/s when it was removed (esmini re-adds it at that speed)
  /// Metres summed as straight lines between the entity's places at the ends of successive
  /// steps, jumps to a new place (a TeleportAction, being added) left out: the distance a
  /// TraveledDistanceCondition reads, as esmini's odometer measures it. Kept only while a
  /// scenario has such a condition (SimState::straight_travel_wanted).
  double straight_travel = 0.0;
  double straight_from_x = 0.0, straight_from_y = 0.0;  ///< the place it is summed from
  /// The last lane found at a point (entities placed at a pose, or off their lanes).
  PointLocateMemo point_memo;

  const xosc::ScenarioObject* object = nullptr;
  RouteProgress route_progress;
  /// Lights set by LightStateAction; null until the first is set (unset ones follow the
  /// motion). Out of line: most entities never use them.
  std::unique_ptr<LightSettings> lights;
  /// AnimationAction: each animation by type name, going from `from` to `to` over `duration`.
  struct Animation {
    double from = 0.0, to = 1.0, start = 0.0, duration = 0.0;
    bool loop = false;
  };
  std::map<std::string, Animation> animations;
  /// The entity of a trailer defined inline in this vehicle, connected at Init.
  std::optional<uint32_t> initial_trailer;
};

/// An animation's state (0..1) at run time `now` (s).
double animation_state(const Entity::Animation& animation, double now);

}  // namespace corsa::engine::detail
