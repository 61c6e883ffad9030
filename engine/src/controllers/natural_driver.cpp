// esmini's NaturalDriver (controllers/natural_driver.h), read from esmini's
// ControllerNaturalDriver: the speed by the Intelligent Driver Model, lane changes by a
// MOBIL-style rule, each step in the order esmini's Step takes.

#include "controllers/natural_driver.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <numbers>
#include <optional>
#include <string>

#include "controllers/controllers.h"
#include "corsa/xodr/map.h"
#include "corsa/xosc/scenario.h"
#include "lanes/lane_follow.h"
#include "motion/controller.h"
#include "motion/transition_shape.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {

/// The driver's parameters (esmini's property names in the comments) and esmini's defaults.
struct NaturalDriverParams {
  double desired_distance = 20.0;     ///< m, desiredDistance: IDM s0, bumper to bumper
  double desired_speed = 15.0;        ///< m/s, desiredSpeed: IDM v0
  double lane_change_duration = 3.0;  ///< s, laneChangeDuration
  double lookahead = 115.0;           ///< m, lookAheadDistance: others farther are not seen
  double max_dec = -3.0;              ///< m/s^2 (negative), maxDec: IDM b, the braking floor
  double max_acc = 3.0;               ///< m/s^2, maxAcc: IDM a
  double lane_change_delay = 1.0;     ///< s, laneChangeDelay: the wait after a lane change
  double thw = 2.0;                   ///< s, thw: IDM T
  double max_imposed_braking = 3.0;   ///< m/s^2, maxImposedBraking: MOBIL's safety limit
  double politeness = 0.5;            ///< politeness: MOBIL's p
  double lane_change_acc_gain = 0.2;  ///< m/s^2, laneChangeAccGain: MOBIL's threshold
  int route = -1;                     ///< route: the lane id it changes to on safety alone
};

/// The lane change the driver asked for, as esmini's LaneChangeAction performs it: the entity
/// follows the target lane at once, its lateral offset going from where it was to the lane's
/// centre along a sinusoid over the duration.
struct NaturalLaneChange {
  int target = 0;
  double from = 0.0;        ///< m, LaneFollow::lateral at the start
  double to = 0.0;          ///< m, LaneFollow::lateral at the end (the lane's centre)
  double seen_shift = 0.0;  ///< LaneFollow::frame_shift `from` and `to` are measured in
  int64_t start_tick = 0;
};

/// What the driver keeps between steps (esmini's members of the same meaning).
struct NaturalDriverState {
  NaturalDriverParams params;
  bool active = false;
  double speed = 0.0;      ///< m/s, the speed it integrates (current_speed_)
  bool changing = false;   ///< state CHANGE_LANE: the speed is held
  bool requested = false;  ///< a lane change was asked for and the wait has not run out
  double cooldown = 0.0;   ///< s left of laneChangeDuration + laneChangeDelay
  int target_lane = 0;
  /// The lane change asked for, and the tick at which it starts moving the entity.
  std::optional<int> pending_lane;
  int64_t pending_tick = 0;
  std::optional<NaturalLaneChange> lane_change;
};

namespace {

// esmini's SMALL_NUMBER: the least gap, and the margin a lane change's gain must beat.
constexpr double kNaturalSmall = 1e-10;
constexpr int kIdmExponent = 4;

// One entity as the driver sees it: road, nominal lane, s along the road, speed, box.
struct NaturalView {
  uint32_t index = 0;
  uint32_t road = 0;
  int lane = 0;
  double s = 0.0;
  int dir = 1;
  double speed = 0.0;
  double heading = 0.0;
  double front = 0.0;  ///< m from the reference point to the box's front
  double rear = 0.0;   ///< m from the reference point back to the box's rear
};

NaturalView natural_view_of(const Entity& entity, uint32_t index) {
  NaturalView view;
  view.index = index;
  view.road = entity.lane.road;
  view.lane = entity.lane.lane;
  view.s = entity.lane.s;
  view.dir = entity.lane.dir;
  view.speed = entity.state().speed;
  view.heading = entity.state().pose.h;
  view.front = 0.5 * entity.info.box.length + entity.info.box.center_x;
  view.rear = 0.5 * entity.info.box.length - entity.info.box.center_x;
  return view;
}

// Lanes from `from` to `to` counted toward the centre (toward the driver's left in the lane's
// direction of travel), the centre lane skipped.
int natural_lanes_left(int from, int to) {
  int steps = to - from;
  if ((from < 0) != (to < 0)) steps -= (to > from ? 1 : -1);
  return from < 0 ? steps : -steps;
}

// The kinds of neighbours esmini's driver keeps (its VoIType).
enum NaturalSlot {
  kSlotLead,
  kSlotFollowing,
  kSlotLeftLead,
  kSlotLeftFollow,
  kSlotRightLead,
  kSlotRightFollow,
  kSlotCount
};

struct NaturalNeighbour {
  const NaturalView* view = nullptr;
  double ds = 0.0;
};

class NaturalStep {
 public:
  NaturalStep(SimState& state, uint32_t self, NaturalDriverState& driver)
      : state_(state), self_(self), driver_(driver), p_(driver.params) {}

  // esmini's Step(dt): the acceleration, a lane change perhaps, the wait, the new speed.
  // `zero_step`: esmini's first Step, made with dt 0 in the frame that initialises the scenario.
  void run(double dt, bool zero_step) {
    zero_step_ = zero_step;
    see_around();
    double acceleration = 0.0;
    bool initiate = false;
    if (!driver_.changing) {
      acceleration = std::max(idm(&me_, slots_[kSlotLead].view), p_.max_dec);
      if (!driver_.requested) {
        const std::array<int, 2> lanes = adjacent_lanes();
        for (const int lane : lanes) {
          if (lane == 0) continue;
          initiate = lane_change_pays(lane, lanes);
          if (initiate && me_.speed > 0.0) {
            driver_.target_lane = lane;
            driver_.changing = true;
            break;
          }
        }
      }
    }
    // (esmini would also ask for a change at a standstill, to no lane: not done here.)
    if (initiate && driver_.target_lane != 0) {
      if (someone_else_changes_there()) {
        driver_.target_lane = 0;
        driver_.changing = false;
      } else {
        request_lane_change();
      }
    }
    if (driver_.requested) {
      driver_.cooldown -= dt;
      if (driver_.changing && driver_.cooldown <= p_.lane_change_delay) {
        // The speed is held while the lane change runs, then followed again.
        driver_.target_lane = 0;
        driver_.changing = false;
      }
      if (driver_.cooldown < 0.0) {
        driver_.cooldown = p_.lane_change_delay + p_.lane_change_duration;
        driver_.requested = false;
      }
    }
    double speed = driver_.speed + acceleration * dt;
    const double max_speed = state_.world.entities[self_].info.max_speed;
    if (speed >= p_.desired_speed) {
      speed = p_.desired_speed;
    } else if (max_speed > 0.0 && speed > max_speed) {
      speed = max_speed;
    } else if (speed < 0.0) {
      speed = 0.0;
    }
    driver_.speed = speed;
  }

 private:
  // The others within lookAheadDistance (straight line, reference points) on the same road,
  // sorted into the nearest ahead and behind in the own lane and in the lanes either side.
  void see_around() {
    const Entity& self = state_.world.entities[self_];
    me_ = natural_view_of(self, self_);
    others_.clear();
    for (uint32_t i = 0; i < state_.world.entities.size(); ++i) {
      const Entity& other = state_.world.entities[i];
      if (i == self_ || !seen(i)) continue;
      const double dx = other.state().pose.x - self.state().pose.x;
      const double dy = other.state().pose.y - self.state().pose.y;
      if (std::hypot(dx, dy) > p_.lookahead) continue;
      others_.push_back(natural_view_of(other, i));
    }
    slots_ = {};
    if (!self.lane.on_road) return;  // off the lanes it sees no one ahead or beside
    for (const NaturalView& other : others_) {
      if (other.road != me_.road) continue;
      const double ds = (other.s - me_.s) * me_.dir;
      const int left = natural_lanes_left(me_.lane, other.lane);
      const NaturalSlot ahead = left == 0 ? kSlotLead : left == 1 ? kSlotLeftLead : kSlotRightLead;
      if (left < -1 || left > 1) continue;
      const auto behind = static_cast<NaturalSlot>(ahead + 1);
      NaturalNeighbour& front = slots_[ahead];
      if (ds >= 0.0 && (front.view == nullptr || ds < front.ds)) front = {&other, ds};
      NaturalNeighbour& back = slots_[behind];
      if (ds < 0.0 && (back.view == nullptr || ds > back.ds)) back = {&other, ds};
    }
  }

  bool seen(uint32_t i) const {
    const Entity& other = state_.world.entities[i];
    return other.state().placed && !other.removed && !other.ghost && other.lane.on_road &&
           (i >= state_.controls.size() || state_.controls[i].traffic_visible);
  }

  // esmini's EstimateFreespace: the gap between the boxes along the road (ds between the
  // reference points less the follower's front and the target's rear); 0 when they overlap.
  static double freespace(const NaturalView& follow, const NaturalView& target, double ds) {
    const double dh =
        std::abs(std::remainder(follow.heading - target.heading, 2.0 * std::numbers::pi));
    if (dh >= 0.5 * std::numbers::pi) return ds;
    const double boxes = follow.front + target.rear;
    if (ds > 0.0) return std::max(0.0, ds - boxes);
    return std::min(0.0, ds + boxes);
  }

  double desired_gap(double follow_speed, double lead_speed) const {
    const double ab = -p_.max_acc * p_.max_dec;
    const double closing = follow_speed - lead_speed;
    return p_.desired_distance +
           std::max(0.0, follow_speed * p_.thw + follow_speed * closing / (2.0 * std::sqrt(ab)));
  }

  // esmini's GetAcceleration: the IDM acceleration of `follow` behind `lead` (none: free road;
  // no follower: 0).
  double idm(const NaturalView* follow, const NaturalView* lead) const {
    if (follow == nullptr) return 0.0;
    const double v = follow->speed;
    double a = p_.max_acc * (1.0 - std::pow(v / p_.desired_speed, kIdmExponent));
    if (lead != nullptr) {
      const double gap = desired_gap(v, lead->speed);
      double free = freespace(*follow, *lead, (lead->s - follow->s) * follow->dir);
      if (free == 0.0) free = kNaturalSmall;
      a -= p_.max_acc * std::pow(gap / free, 2);
    }
    return a;
  }

  // esmini's AdjacentLanesAvailable: the driving lanes beside the own one, {left, right}, 0
  // where there is none; none at all when the own side has a single driving lane.
  std::array<int, 2> adjacent_lanes() const {
    const Entity& self = state_.world.entities[self_];
    if (state_.map == nullptr || !self.lane.on_road) return {0, 0};
    const xodr::Road& road = state_.map->road(self.lane.road);
    const xodr::LaneSection& section = road.lane_sections[self.lane.section];
    const int lane = self.lane.lane;
    int driving_on_side = 0;
    const xodr::Lane* left = nullptr;
    const xodr::Lane* right = nullptr;
    const int sign = lane < 0 ? -1 : 1;
    for (const xodr::Lane& candidate : section.lanes) {
      if (candidate.id != 0 && (candidate.id < 0) == (lane < 0) &&
          xodr::is_drivable(candidate.type)) {
        ++driving_on_side;
      }
      if (candidate.id == lane - sign && candidate.id != 0) left = &candidate;
      if (candidate.id == lane + sign) right = &candidate;
    }
    if (driving_on_side <= 1) return {0, 0};
    return {left != nullptr && xodr::is_drivable(left->type) ? left->id : 0,
            right != nullptr && xodr::is_drivable(right->type) ? right->id : 0};
  }

  // esmini's CheckLaneChangePossible: no new follower braking harder than maxImposedBraking;
  // toward the route's lane the own braking under that limit is enough, elsewhere the gain in
  // acceleration (own, plus politeness times the followers') must beat laneChangeAccGain.
  bool lane_change_pays(int lane, const std::array<int, 2>& lanes) const {
    if (driver_.requested) return false;
    const bool to_left = lane == lanes[0];
    const NaturalView* new_lead = slots_[to_left ? kSlotLeftLead : kSlotRightLead].view;
    const NaturalView* new_follow = slots_[to_left ? kSlotLeftFollow : kSlotRightFollow].view;
    const double new_follow_now = idm(new_follow, new_lead);
    const double new_follow_then = idm(new_follow, &me_);
    if (new_follow_then < -p_.max_imposed_braking) return false;
    const double mine_then = idm(&me_, new_lead);
    if (lane == p_.route) return mine_then >= -p_.max_imposed_braking;
    const NaturalView* lead = slots_[kSlotLead].view;
    const NaturalView* follow = slots_[kSlotFollowing].view;
    const double mine_now = idm(&me_, lead);
    const double old_follow_now = idm(follow, &me_);
    const double old_follow_then = idm(follow, lead);
    const double gain =
        mine_then - mine_now +
        p_.politeness * (new_follow_then - new_follow_now + old_follow_then - old_follow_now);
    return gain > p_.lane_change_acc_gain + kNaturalSmall;
  }

  // esmini's AbortLaneChange: another NaturalDriver within reach, not in the own lane, has asked
  // for a change to the same lane and is nearer ahead than the gap the IDM wants.
  bool someone_else_changes_there() const {
    for (const NaturalView& other : others_) {
      const NaturalDriverState* driver = other.index < state_.controls.size()
                                             ? state_.controls[other.index].natural.get()
                                             : nullptr;
      if (driver == nullptr || !driver->active || other.road != me_.road ||
          other.lane == me_.lane) {
        continue;
      }
      const double ds = (other.s - me_.s) * me_.dir;
      const double free = freespace(me_, other, ds);
      if (free >= 0.0 && free < desired_gap(other.speed, driver_.speed) && driver->requested &&
          driver->target_lane == driver_.target_lane) {
        return true;
      }
    }
    return false;
  }

  // esmini injects a LaneChangeAction (absolute target lane, sinusoidal over the duration),
  // which its player starts the frame after and first steps the frame after that.
  void request_lane_change() {
    driver_.pending_lane = driver_.target_lane;
    driver_.pending_tick = state_.tick + (zero_step_ ? 1 : 2);
    driver_.requested = true;
  }

  SimState& state_;
  uint32_t self_;
  NaturalDriverState& driver_;
  const NaturalDriverParams& p_;
  bool zero_step_ = false;
  NaturalView me_;
  std::vector<NaturalView> others_;
  std::array<NaturalNeighbour, kSlotCount> slots_{};
};

// A property's value as a number; nothing (and a located warning) when it is none.
std::optional<double> natural_number(SimState& state, const std::string& name,
                                     const std::string& value, const xosc::Source& source) {
  char* end = nullptr;
  const double number = std::strtod(value.c_str(), &end);
  if (end != value.c_str() && *end == '\0' && std::isfinite(number)) return number;
  state.diagnostics.add(source.warning("NaturalDriver property '" + name + "' is not a number ('" +
                                       value + "'): esmini's default is used"));
  return std::nullopt;
}

// A Controller read in place of a catalog entry the catalog lacks (xosc: its source is the
// CatalogReference itself).
bool read_for_missing_entry(const xosc::Controller& controller) {
  return controller.catalog && controller.properties.properties.empty() &&
         controller.source.line == controller.catalog->reference.line &&
         controller.source.file_name() == controller.catalog->reference.file_name();
}

// The value of esmini property `name`: the Controller's Property, or for a controller read in
// place of a missing entry the reference's ParameterAssignment of the name with an upper-case
// first letter (highway_driver assigns `DesiredSpeed` to the entry's `desiredSpeed`).
std::optional<double> natural_setting(SimState& state, const xosc::Controller& controller,
                                      const std::string& name, bool& assigned,
                                      const xosc::Source*& source) {
  for (const xosc::Property& property : controller.properties.properties) {
    if (property.name == name) {
      source = &property.source;
      return natural_number(state, name, property.value, property.source);
    }
  }
  if (!read_for_missing_entry(controller)) return std::nullopt;
  std::string parameter = name;
  parameter[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(parameter[0])));
  for (const xosc::ParameterAssignment& assignment : controller.catalog->assignments) {
    if (assignment.parameter_ref == parameter) {
      assigned = true;
      source = &assignment.source;
      return natural_number(state, name, assignment.value, assignment.source);
    }
  }
  return std::nullopt;
}

// Starts the lane change to `target` where the entity is: it follows the target lane from now,
// offset so that it stays in place (as a LaneChangeAction starts, actions/lane_change_action.cpp).
// Nothing when the lane is not there.
std::optional<NaturalLaneChange> start_natural_lane_change(const SimState& state, Entity& entity,
                                                           int target) {
  LaneFollow& lane = entity.lane;
  if (state.map == nullptr || !lane.on_road) return std::nullopt;
  const xodr::Map& map = *state.map;
  const auto target_center = followed_lane_center_t(map, lane, target);
  const auto node = map.lane_graph().find(xodr::LaneRef{lane.road, lane.section, target});
  if (!target_center || !node) return std::nullopt;
  const double t_now =
      followed_lane_center_t(map, lane, lane.lane).value_or(0.0) + lane.dir * lane.lateral;
  lane.lane = target;
  lane.node = *node;
  lane.lateral = (t_now - *target_center) * lane.dir;
  entity.lateral_command = lane.lateral;
  return NaturalLaneChange{target, lane.lateral, 0.0, lane.frame_shift, state.tick};
}

// The lane change asked for starts at its tick; one under way sets the lateral offset for the
// end of the step. It ends at its duration, or when something else took the lateral motion: a
// lateral action of the storyboard holds the domain, or a teleport put the entity on another
// lane.
void step_natural_lane_change(SimState& state, uint32_t index, NaturalDriverState& driver) {
  Entity& entity = state.world.entities[index];
  if (driver.pending_lane && state.tick >= driver.pending_tick) {
    const int target = *driver.pending_lane;
    driver.pending_lane.reset();
    driver.lane_change.reset();
    if (entity.owners[1] == nullptr) {
      driver.lane_change = start_natural_lane_change(state, entity, target);
    }
  }
  if (!driver.lane_change) return;
  NaturalLaneChange& change = *driver.lane_change;
  if (entity.owners[1] != nullptr || entity.lane.lane != change.target) {
    driver.lane_change.reset();
    return;
  }
  // A route carried the entity on from a neighbouring lane's end: start and end move with the
  // followed lane's frame.
  const double shift = entity.lane.frame_shift - change.seen_shift;
  change.seen_shift += shift;
  change.from += shift;
  change.to += shift;
  const double elapsed = state.time.time(state.tick + 1 - change.start_tick);
  const double duration = driver.params.lane_change_duration;
  const double p = duration > 0.0 && elapsed < duration ? elapsed / duration : 1.0;
  const double shape = shape_value(xosc::DynamicsShape::kSinusoidal, p);
  entity.lateral_command = change.from + shape * (change.to - change.from);
  if (p >= 1.0) driver.lane_change.reset();
}

// The entity's move over the step at the driver's speed (the actions' speed command kept for
// when the driver is switched off).
void move_natural(SimState& state, uint32_t index, const MotionContext& motion, double speed) {
  Entity& entity = state.world.entities[index];
  move_at_controller_speed(entity, speed, [&] { DefaultController().step(entity, motion); });
}

}  // namespace

bool is_natural_driver(const xosc::ObjectController& oc) {
  return esmini_type(oc.controller) == "NaturalDriver";
}

std::shared_ptr<NaturalDriverState> make_natural_driver(SimState& state,
                                                        const xosc::ObjectController& oc) {
  auto driver = std::make_shared<NaturalDriverState>();
  NaturalDriverParams& p = driver->params;
  const xosc::Controller& controller = oc.controller;
  bool assigned = false;
  // Properties a controller read for a missing entry gets no value for: esmini's defaults.
  std::string defaulted;
  const bool missing_entry = read_for_missing_entry(controller);
  // A value the model cannot work with (a division by zero, the root of a negative, a lane id
  // beyond int, a duration beyond float) warns at its property and leaves esmini's default.
  const auto set = [&](const char* name, double& field, bool (*valid)(double) = nullptr,
                       const char* requirement = "") {
    const xosc::Source* source = nullptr;
    if (const auto value = natural_setting(state, controller, name, assigned, source)) {
      if (valid == nullptr || valid(*value)) {
        field = *value;
      } else {
        state.diagnostics.add(source->warning("NaturalDriver property '" + std::string(name) +
                                              "' must be " + requirement +
                                              ": esmini's default is used"));
      }
    } else if (missing_entry) {
      defaulted += (defaulted.empty() ? "" : ", ") + std::string(name);
    }
  };
  const auto positive = [](double v) { return v > 0.0; };
  const auto negative = [](double v) { return v < 0.0; };
  const auto nonnegative = [](double v) { return v >= 0.0; };
  set("desiredDistance", p.desired_distance);
  set("desiredSpeed", p.desired_speed, positive, "above 0");
  set(
      "laneChangeDuration", p.lane_change_duration,
      [](double v) { return v >= 0.0 && v <= std::numeric_limits<float>::max(); },
      "at least 0 and within a float's range");
  set("lookAheadDistance", p.lookahead);
  set("maxDec", p.max_dec, negative, "below 0");
  set("maxAcc", p.max_acc, positive, "above 0");
  set("laneChangeDelay", p.lane_change_delay, nonnegative, "at least 0");
  set("thw", p.thw, nonnegative, "at least 0");
  set("maxImposedBraking", p.max_imposed_braking);
  set("laneChangeAccGain", p.lane_change_acc_gain);
  set("politeness", p.politeness);
  double route = p.route;
  set(
      "route", route,
      [](double v) {
        return v >= std::numeric_limits<int>::min() && v <= std::numeric_limits<int>::max();
      },
      "within an int's range");
  p.route = static_cast<int>(route);
  // esmini reads laneChangeDuration as a float.
  p.lane_change_duration = static_cast<float>(p.lane_change_duration);
  driver->cooldown = p.lane_change_duration + p.lane_change_delay;
  if (assigned) {
    state.diagnostics.add_once(
        "natural-driver-assignments:" + controller.catalog->reference.file_name() + ":" +
            std::to_string(controller.catalog->reference.line),
        controller.catalog->reference.warning(
            "controller entry 'NaturalDriver' is not in the catalog: its ParameterAssignments are "
            "read as esmini's NaturalDriver properties of the same name with a lower-case first "
            "letter (read as esmini's catalog entry maps them)"));
  }
  if (!defaulted.empty()) {
    state.diagnostics.add_once(
        "natural-driver-defaults:" + controller.catalog->reference.file_name() + ":" +
            std::to_string(controller.catalog->reference.line),
        controller.catalog->reference.warning(
            "controller entry 'NaturalDriver' is not in the catalog and nothing gives its " +
            defaulted +
            ": esmini's defaults (read as esmini's NaturalDriver without those "
            "properties)"));
  }
  return driver;
}

void step_natural_drivers(SimState& state, const MotionContext& motion) {
  const auto count = static_cast<uint32_t>(state.world.entities.size());
  for (uint32_t i = 0; i < count && i < state.controls.size(); ++i) {
    ControlState& control = state.controls[i];
    if (!control.natural) continue;
    NaturalDriverState& driver = *control.natural;
    const Entity& entity = state.world.entities[i];
    if (control.effective() != ControllerKind::kNaturalDriver || !entity.state().placed ||
        entity.removed || entity.towed_by || state.frozen(i)) {
      driver.active = false;
      continue;
    }
    if (!control.longitudinal) {
      // Activated on the lateral domain alone: esmini's driver takes the longitudinal one only,
      // so it is not active and the default controller moves the entity.
      driver.active = false;
      DefaultController().step(state.world.entities[i], motion);
      continue;
    }
    bool zero_step = false;
    if (!driver.active) {
      // esmini's Activate: the integrated speed starts from the entity's. Activated in the
      // Init (the first step), esmini's first Step is made in its initialising frame, with dt 0.
      // Activated again, it starts afresh: no lane change asked for or under way, the wait
      // before one as when it was made.
      const NaturalDriverParams params = driver.params;
      driver = NaturalDriverState{};
      driver.params = params;
      driver.cooldown = params.lane_change_duration + params.lane_change_delay;
      driver.active = true;
      driver.speed = entity.state().speed;
      zero_step = state.tick == 0;
    }
    if (zero_step) NaturalStep(state, i, driver).run(0.0, true);
    step_natural_lane_change(state, i, driver);
    NaturalStep(state, i, driver).run(motion.dt, false);
    move_natural(state, i, motion, driver.speed);
  }
}

}  // namespace corsa::engine::detail
