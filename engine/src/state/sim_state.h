#pragma once

// Everything that changes during one run, in one place that actions and conditions are handed
// (no globals: two Simulations own two SimStates). The read-only models (xosc::Scenario,
// xodr::Map) are referenced, never modified.

#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <unordered_map>
#include <vector>

#include "corsa/core/diagnostic.h"
#include "corsa/engine/oriented_box.h"
#include "corsa/engine/simulation.h"
#include "corsa/engine/world_snapshot.h"
#include "state/control_state.h"
#include "state/element_table.h"
#include "state/entity.h"
#include "state/ghost_state.h"
#include "state/time_base.h"
#include "state/traffic_state.h"
#include "state/value_store.h"

namespace corsa::xosc {
struct Scenario;
}
namespace corsa::xodr {
class Map;
}

namespace corsa::engine::detail {

class EsminiRandom;

/// The entities, in document order (their index is their identity for the whole run).
struct World {
  std::vector<Entity> entities;
  std::unordered_map<std::string, uint32_t> by_name;

  std::optional<uint32_t> find(std::string_view name) const {
    const auto it = by_name.find(std::string(name));
    return it == by_name.end() ? std::nullopt : std::optional<uint32_t>(it->second);
  }
};

/// Whether `a` and `b` have the same bits (-0 and +0 differ, a NaN equals itself): a function
/// of either gives the same value.
inline bool same_bits(double a, double b) {
  return std::bit_cast<uint64_t>(a) == std::bit_cast<uint64_t>(b);
}
/// The bits in which `count` doubles from byte `offset` of `a` differ from those of `b` (0: the
/// same bits), ORed together: a test of many doubles without a branch per value, which the
/// compiler makes two at a time in vector registers. T's bytes there must be doubles alone.
template <size_t kOffset, size_t kCount, class T>
inline uint64_t double_bits_diff(const T& a, const T& b) {
  static_assert(std::is_trivially_copyable_v<T> && kOffset % 8 == 0 &&
                kOffset + 8 * kCount <= sizeof(T));
  const auto* pa = reinterpret_cast<const unsigned char*>(&a) + kOffset;
  const auto* pb = reinterpret_cast<const unsigned char*>(&b) + kOffset;
  uint64_t diff = 0;
  for (size_t i = 0; i < kCount; ++i) {
    uint64_t wa = 0, wb = 0;
    std::memcpy(&wa, pa + 8 * i, 8);
    std::memcpy(&wb, pb + 8 * i, 8);
    diff |= wa ^ wb;
  }
  return diff;
}
static_assert(sizeof(Pose) == 6 * sizeof(double) && sizeof(Box) == 6 * sizeof(double),
              "Pose and Box are compared as six doubles");
/// x, y, z and h of a pose (its first four doubles), as they differ.
inline uint64_t pose_xyzh_diff(const Pose& a, const Pose& b) {
  static_assert(offsetof(Pose, h) == 3 * sizeof(double));
  return double_bits_diff<0, 4>(a, b);
}
inline bool same_bits(const Pose& a, const Pose& b) { return double_bits_diff<0, 6>(a, b) == 0; }
inline bool same_bits(const std::optional<RoadCoordinates>& a,
                      const std::optional<RoadCoordinates>& b) {
  if (!a || !b) {
    return a.has_value() == b.has_value();
  }
  return a->road == b->road && a->section == b->section && a->lane == b->lane &&
         same_bits(a->s, b->s) && same_bits(a->t, b->t);
}
inline bool same_bits(const Box& a, const Box& b) { return double_bits_diff<0, 6>(a, b) == 0; }

inline bool same_bits(const EntityState& a, const EntityState& b) {
  static_assert(sizeof(EntityState) == 136, "add the new field to same_bits");
  // The pose and the five doubles after it, in one test.
  static_assert(offsetof(EntityState, pose) == 0 &&
                offsetof(EntityState, odometer) == sizeof(Pose) + 4 * sizeof(double));
  return double_bits_diff<0, 11>(a, b) == 0 && a.placed == b.placed && a.visible == b.visible &&
         same_bits(a.road, b.road);
}
inline bool same_bits(const LaneFollow& a, const LaneFollow& b) {
  static_assert(sizeof(LaneFollow) == 64, "add the new field to same_bits");
  return a.on_road == b.on_road && a.road == b.road && a.section == b.section && a.lane == b.lane &&
         a.node == b.node && same_bits(a.s, b.s) && a.dir == b.dir &&
         same_bits(a.lateral, b.lateral) && same_bits(a.heading_offset, b.heading_offset) &&
         same_bits(a.frame_shift, b.frame_shift);
}
/// The motion besides its state, field by field, so that padding bytes (never written, never the
/// same) take no part. The route is compared by address (see EntityMotion::chooser).
inline bool same_bits_beside_state(const EntityMotion& a, const EntityMotion& b) {
  static_assert(sizeof(EntityMotion) == 248, "add the new field to same_bits_beside_state");
  // The four doubles from speed_command to lateral_acceleration, in one test. (offsetof of a
  // type with private members, which GCC gives as for any other.)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Winvalid-offsetof"
  constexpr size_t kCommands = offsetof(EntityMotion, speed_command);
  static_assert(offsetof(EntityMotion, lateral_acceleration) == kCommands + 3 * sizeof(double));
#pragma GCC diagnostic pop
  return same_bits(a.lane, b.lane) && double_bits_diff<kCommands, 4>(a, b) == 0 &&
         a.end_of_road == b.end_of_road && a.chooser == b.chooser;
}
/// The whole motion. The count of the state's writes (state_changes) is no part of it: a write
/// that changes nothing leaves the same motion.
inline bool same_bits(const EntityMotion& a, const EntityMotion& b) {
  return same_bits(a.state(), b.state()) && same_bits_beside_state(a, b);
}

/// What the contacts of an entity were last computed from (state/world_contacts.h): its place
/// and pose. Its box is no part of it: an entity's box is fixed once the entity exists
/// (Entity::info), and entities keep their index for the run.
struct ContactInput {
  bool placed = false;
  Pose pose;
  /// The entity's count of its state's writes (EntityMotion::state_changes) when it was taken.
  uint32_t changes = 0;

  ContactInput() = default;
  explicit ContactInput(const Entity& entity)
      : placed(entity.state().placed), pose(entity.state().pose), changes(entity.state_changes()) {}

  /// Whether `entity`, the one this was taken from, is placed and posed as this records, to the
  /// bit (box_of gives the same box then; -0 and +0 differ, NaN equals itself). While its
  /// state's count of writes stands, its state is the one taken, and nothing is compared.
  bool same_as(const Entity& entity) const {
    if (changes == entity.state_changes()) {
      return true;
    }
    const EntityState& state = entity.state();
    // x alone first: a moving entity's differs, and its test ends there (the rest compares
    // every value without a branch).
    return same_bits(pose.x, state.pose.x) && placed == state.placed &&
           pose_xyzh_diff(pose, state.pose) == 0;
  }
};

/// An entity's contact box made by its mover right after its move, on the mover's thread
/// (premake_contact_box, state/world_contacts.h): the contacts' update takes it when the
/// entity still stands as it did then, instead of making the box again on its own thread.
struct PremadeContactBox {
  ContactInput input;  ///< what the box was made from
  bool boxed = false;  ///< whether the entity's box took part in the contacts then
  OrientedBox box;
  Interval x, y;  ///< the box's extents along x and y
};

/// Pairs of entities whose boxes overlap now: (first, second) with first < second, sorted.
struct ContactSet {
  std::vector<std::pair<uint32_t, uint32_t>> pairs;
  /// Every entity's box at the last update: when none has changed, neither have the pairs.
  std::vector<ContactInput> inputs;
  /// box_of(inputs[i].box, inputs[i].pose) for every entity that was placed with a length (not
  /// at or below 0) at the last update; the others' are left as they were.
  std::vector<OrientedBox> boxes;
  /// By entity: the boxes the moves since the last update made (fresh: made by them; the
  /// update then takes those still valid and ends their freshness).
  std::vector<PremadeContactBox> premade;
  bool premade_fresh = false;

  /// Entity `i`'s box as the last update made it, when `entity` (that entity now) is still
  /// placed and posed as then, to the bit: the same value box_of would give. Null
  /// otherwise. The followers' picture, taken before the next moves, reads it instead of making
  /// the box again.
  const OrientedBox* unmoved_box(uint32_t i, const Entity& entity) const {
    if (i >= inputs.size() || i >= boxes.size() || !entity.state().placed ||
        entity.info.box.length <= 0.0 || !inputs[i].same_as(entity)) {
      return nullptr;
    }
    return &boxes[i];
  }

  bool get(uint32_t a, uint32_t b) const {
    const auto key = a < b ? std::make_pair(a, b) : std::make_pair(b, a);
    return std::binary_search(pairs.begin(), pairs.end(), key);
  }
};

/// Where a vehicle with esmini's `refpoint_x_offset` property keeps the axle its body turns
/// about between steps (motion/refpoint_trail.h).
struct RefpointTrail {
  uint32_t entity = 0;  ///< index into world.entities
  double length = 0.0;  ///< m from the turning axle forward to the reference point (> 0)
  double axle_x = 0.0, axle_y = 0.0;  ///< the turning axle at the end of the last move (m)
  double heading = 0.0;               ///< rad, the heading the last move left
  /// Placed by a jump (TeleportAction, AddEntityAction): the heading given is the body's.
  bool jumped = false;
};

struct SimState {
  SimState(const xosc::Scenario& scenario_in, std::shared_ptr<const xodr::Map> map_in,
           const SimulationOptions& options_in, Diagnostics& diagnostics_in)
      : scenario(scenario_in),
        map_owner(std::move(map_in)),
        map(map_owner.get()),
        options(options_in),
        diagnostics(diagnostics_in),
        time(options_in.dt) {}

  const xosc::Scenario& scenario;
  std::shared_ptr<const xodr::Map> map_owner;
  const xodr::Map* map;  ///< null: no road network
  SimulationOptions options;
  Diagnostics& diagnostics;
  TimeBase time;
  int64_t tick = 0;

  World world;
  ValueStore parameters;
  ValueStore variables;
  EnvironmentState environment;
  /// Tick at which the time of day was last set; with animation it advances with the run.
  int64_t environment_tick = 0;
  bool time_of_day_animated = false;

  ElementTable elements;
  ContactSet contacts;
  std::vector<CollisionRecord> collisions;
  /// Lights set by LightStateActions, in the order they were set (the run summary's record).
  std::vector<LightChange> light_changes;
  std::map<std::string, CustomCommandHandler, std::less<>> custom_handlers;
  /// Values of UserDefinedValueConditions (Simulation::set_user_value_provider); may be empty.
  UserValueProvider user_values;
  /// Entities with a command from outside for the next step (ControlState::commanded).
  std::vector<uint32_t> commanded;
  /// MonitorDeclarations' values (SetMonitorAction), by name.
  std::map<std::string, bool, std::less<>> monitors;
  /// esmini's run generator (controllers/sloppy_driver.h), made when a controller that draws
  /// from it is assigned, seeded with options.seed.
  std::shared_ptr<EsminiRandom> esmini_random;
  /// Values of UserDefinedValueConditions given as text, by name (SimulationOptions::values,
  /// Simulation::set_user_value); they win over `user_values`.
  std::map<std::string, std::string, std::less<>> given_values;
  /// Each entity's controller (controllers/controllers.h), indexed like world.entities.
  std::vector<ControlState> controls;
  /// Traffic signals and generated traffic (state/traffic_state.h).
  TrafficState traffic;
  /// The Simulation that owns this state, for custom command handlers (refreshed every step,
  /// since a Simulation may be moved).
  const Simulation* simulation = nullptr;
  /// Whether a trigger of the storyboard has a TraveledDistanceCondition, found when the
  /// storyboard is built: the step then keeps Entity::straight_travel.
  bool straight_travel_wanted = false;
  /// Whether a trigger of the storyboard has a StandStill, Offroad or EndOfRoad condition,
  /// found when the storyboard is built: only these read the entities' timers
  /// (state/world_update.h), which are kept only then.
  bool timers_wanted = false;
  /// Whether an entity has been given a route (actions/route_assignment.h) in this run: until
  /// then no entity follows one, and the step's pass over the entities' routes is not made.
  bool routes_assigned = false;
  /// Whether a trailer has been connected in this run (motion/trailers.h): until then no entity
  /// is towed, and the step has no trailer to move.
  bool trailers_connected = false;
  /// The vehicles whose body trails their reference point (motion/refpoint_trail.h), in
  /// entity order; empty for most scenarios.
  std::vector<RefpointTrail> refpoint_trailing;
  /// The map's geographic -> map transform, made from options.geo_projection on the first
  /// GeoPosition (positions/geo_reference.h); a cache, hence mutable.
  mutable std::optional<GeographicToMap> geo_to_map;
  /// esmini's ghost of an entity under the followGhost controller (state/ghost_state.h); the run
  /// then starts at tick -headstart_ticks.
  std::optional<GhostLink> ghost;

  /// Whether entity `index` stands still this step: while the ghost has its head start (before
  /// time 0), or runs its head start again after a restart, only the ghost moves.
  bool frozen(uint32_t index) const {
    return ghost && tick < ghost->replay_end_tick && index != ghost->ghost;
  }

  double now() const { return time.time(tick); }
};

}  // namespace corsa::engine::detail
