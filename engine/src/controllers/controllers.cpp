// Controller choice per entity and the per-step dispatch (OpenSCENARIO 1.3 §7.5).

#include "controllers/controllers.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <numbers>
#include <thread>
#include <utility>
#include <vector>

#include "controllers/alks_r157.h"
#include "controllers/esmini_vehicle.h"
#include "controllers/external.h"
#include "controllers/follow_ghost.h"
#include "controllers/follow_view.h"
#include "controllers/give_way.h"
#include "controllers/natural_driver.h"
#include "controllers/npc_caution.h"
#include "controllers/sloppy_driver.h"
#include "controllers/thread_choice.h"
#include "controllers/worker_pool.h"
#include "corsa/xodr/map.h"
#include "corsa/xosc/scenario.h"
#include "state/sim_state.h"
#include "state/world_contacts.h"

namespace corsa::engine::detail {

std::optional<double> nonnegative_property(const SimState& state,
                                           const xosc::Controller& controller, const char* name,
                                           const char* controller_label) {
  for (const xosc::Property& property : controller.properties.properties) {
    if (property.name != name) continue;
    char* end = nullptr;
    const double value = std::strtod(property.value.c_str(), &end);
    if (end != property.value.c_str() && *end == '\0' && std::isfinite(value) && value >= 0.0) {
      return value;
    }
    // Once per property: a catalog controller or a traffic template serves many entities.
    state.diagnostics.add_once(
        "controller-property:" + property.source.file_name() + ":" +
            std::to_string(property.source.line) + ":" + property.name,
        property.source.warning(std::string(controller_label) + " property '" + property.name +
                                "' is not a non-negative number ('" + property.value +
                                "'): its default is used"));
    return std::nullopt;
  }
  return std::nullopt;
}

bool controller_kind_of(const xosc::Controller& controller, Diagnostics& diagnostics,
                        ControllerKind& out) {
  for (const xosc::Property& property : controller.properties.properties) {
    // esmini's DefaultController performs the actions as given, as ours does: no substitute.
    if (property.name == "esminiController" && property.value == "DefaultController") {
      out = ControllerKind::kDefault;
      return true;
    }
    if (property.name != "corsa:controller") {
      continue;
    }
    if (parse_controller_kind(property.value, out)) {
      return true;
    }
    diagnostics.add_once("unknown-corsa-controller:" + property.value,
                         property.source.warning("unknown corsa:controller '" + property.value +
                                                 "' (default, acc, dynamics or external): the "
                                                 "default "
                                                 "controller moves the entity"));
    out = ControllerKind::kDefault;
    return true;
  }
  return false;
}

bool names_external(const SimulationOptions& options, const xosc::ObjectController& oc) {
  for (const std::string& name : options.external_controllers) {
    if (name == oc.controller.name || (oc.name && *oc.name == name)) {
      return true;
    }
    // esmini spells its controller types as a property of any Controller.
    for (const xosc::Property& property : oc.controller.properties.properties) {
      if (property.name == "esminiController" && property.value == name) {
        return true;
      }
    }
  }
  return false;
}

std::string esmini_type(const xosc::Controller& controller) {
  return controller.properties.get("esminiController").value_or(controller.name);
}

void substitute_controller(SimState& state, uint32_t index, const xosc::ObjectController& oc) {
  ControlState& control = control_of(state, index);
  const std::string& entity = state.world.entities[index].info.name;
  if (is_alks_r157(oc.controller)) {
    // esmini's ALKS_R157SM_Controller (controllers/alks_r157.h), for the models emulated.
    if (auto alks = make_alks_r157(state, oc)) {
      control.kind = ControllerKind::kAlksR157;
      control.substitute_for.clear();
      control.alks = std::move(alks);
      return;
    }
  }
  const std::string type = esmini_type(oc.controller);
  if (type == "ACCController" || type == "ALKSController") {
    // esmini's ACC: the acc controller with esmini's law (controllers/acc_controller.cpp).
    // esmini's ALKSController is its ACCController under another name.
    EsminiAcc acc;
    acc.time_gap = nonnegative_property(state, oc.controller, "timeGap", "ACCController")
                       .value_or(acc.time_gap);
    if (oc.controller.properties.get("mode") == "override") {
      acc.set_speed = nonnegative_property(state, oc.controller, "setSpeed", "ACCController");
    }
    control.kind = ControllerKind::kAcc;
    control.substitute_for.clear();
    control.esmini_acc = acc;
    return;
  }
  if (assign_esmini_driver(state, index, oc)) {
    return;  // esmini's interactiveDriver or offroadFollower (controllers/esmini_vehicle.h)
  }
  if (is_sloppy_driver(oc)) {
    // esmini's sloppyDriver, emulated (controllers/sloppy_driver.h).
    control.kind = ControllerKind::kSloppyDriver;
    control.substitute_for.clear();
    control.sloppy = make_sloppy_driver(state, oc);
    return;
  }
  if (is_natural_driver(oc)) {
    // esmini's NaturalDriver, emulated (controllers/natural_driver.h).
    control.kind = ControllerKind::kNaturalDriver;
    control.substitute_for.clear();
    control.natural = make_natural_driver(state, oc);
    return;
  }
  control.kind = ControllerKind::kAcc;
  control.substitute_for = oc.controller.name;
  state.diagnostics.add_once(
      "foreign-controller:" + entity + ":" + oc.controller.name,
      oc.source.warning("controller '" + oc.controller.name +
                        "' is not one of this engine's (default, acc, dynamics via the "
                        "corsa:controller property): the acc controller stands in for it on '" +
                        entity + "' once activated"));
}

namespace {

bool is_interactive_driver(const ControlState& control, ControllerKind kind) {
  return kind == ControllerKind::kEsminiVehicle && control.esmini_driver &&
         control.esmini_driver->kind == EsminiDriverKind::kInteractive;
}

}  // namespace

bool may_share_domains(const ControlState& control, ControllerKind a, ControllerKind b) {
  return (a == ControllerKind::kSloppyDriver && is_interactive_driver(control, b)) ||
         (b == ControllerKind::kSloppyDriver && is_interactive_driver(control, a));
}

void swap_with_partner(ControlState& control) {
  DomainPartner& partner = *control.partner;
  std::swap(control.kind, partner.kind);
  std::swap(control.assigned, partner.assigned);
  std::swap(control.longitudinal, partner.longitudinal);
  std::swap(control.lateral, partner.lateral);
  partner.assigned_last = !partner.assigned_last;
}

bool settle_domains(ControlState& control) {
  if (!control.partner) {
    return true;
  }
  const DomainPartner& partner = *control.partner;
  const bool own = control.longitudinal || control.lateral;
  const bool other = partner.longitudinal || partner.lateral;
  if (own && other) {
    // Two active, in different domains (an activation takes a domain from the other).
    const ControllerKind lateral = control.lateral ? control.kind : partner.kind;
    const ControllerKind longitudinal = control.longitudinal ? control.kind : partner.kind;
    if (lateral != ControllerKind::kSloppyDriver || !is_interactive_driver(control, longitudinal)) {
      control.partner.reset();  // `kind`, assigned or activated last, moves the entity
      return false;
    }
    if (!control.longitudinal) {
      swap_with_partner(control);  // the dispatch steps the longitudinal one
    }
  } else if (other) {
    swap_with_partner(control);
  }
  return true;
}

void settle_domains_at(SimState& state, uint32_t index, const xosc::Source& source) {
  ControlState& control = control_of(state, index);
  const std::string own = control.assigned;
  const std::string partner = control.partner ? control.partner->assigned : std::string();
  if (!settle_domains(control)) {
    state.diagnostics.add(
        source.warning("'" + state.world.entities[index].info.name + "': controllers '" + own +
                       "' and '" + partner +
                       "' on different motion domains at once are defined for an interactiveDriver "
                       "(longitudinal) with a sloppyDriver (lateral) only: '" +
                       control.assigned + "' alone moves it"));
  }
}

void assign_initial_controllers(SimState& state) {
  std::optional<ControllerKind> for_vehicles;
  if (!state.options.controller.empty()) {
    ControllerKind kind;
    if (!parse_controller_kind(state.options.controller, kind)) {
      throw InputError(Diagnostic{Severity::kError, "", 0, -1, "",
                                  "unknown controller '" + state.options.controller +
                                      "' (default, acc, dynamics or external)"});
    }
    for_vehicles = kind;
  }
  state.controls.assign(state.world.entities.size(), ControlState{});
  for (size_t i = 0; i < state.world.entities.size(); ++i) {
    const Entity& entity = state.world.entities[i];
    ControlState& control = state.controls[i];
    bool chosen = false;
    if (entity.ghost) {
      // The ghost performs its entity's actions as written, seen by no one (state/ghost_state.h).
      control.traffic_visible = false;
      control.graphics_visible = false;
      continue;
    }
    if (state.ghost && state.ghost->entity == i) {
      // esmini's followGhost (controllers/follow_ghost.h): as any assigned controller, it moves
      // the entity once an ActivateControllerAction activates it.
      for (const xosc::ObjectController& oc : entity.object->controllers) {
        if (is_follow_ghost(oc)) {
          control.assigned = oc.name.value_or(oc.controller.name);
        }
      }
      control.kind = ControllerKind::kFollowGhost;
      control.longitudinal = false;
      control.lateral = false;
      continue;
    }
    if (entity.object != nullptr && !state.options.disable_controllers) {
      for (const xosc::ObjectController& oc : entity.object->controllers) {
        control.assigned = oc.name.value_or(oc.controller.name);
        if (names_external(state.options, oc)) {
          control.kind = ControllerKind::kExternal;
          chosen = true;
          break;
        }
        if (controller_kind_of(oc.controller, state.diagnostics, control.kind)) {
          chosen = true;
          break;
        }
      }
      if (!chosen && !entity.object->controllers.empty() && !for_vehicles) {
        // A controller this engine does not know (an external driver model, e.g. the ASAM
        // EndOfTrafficJam's ego): the acc controller stands in for a driver that does not run
        // into the vehicle ahead. As the standard has it (§7.5), it moves the entity only once
        // an ActivateControllerAction activates it; until then the default controller does.
        substitute_controller(state, static_cast<uint32_t>(i), entity.object->controllers.front());
        control.longitudinal = false;
        control.lateral = false;
        chosen = true;
      }
    }
    if (!chosen && for_vehicles && entity.info.kind == ObjectKind::kVehicle) {
      control.kind = *for_vehicles;
    }
  }
}

[[gnu::hot]] ControlState& control_of(SimState& state, uint32_t index) {
  if (state.controls.size() < state.world.entities.size()) {
    state.controls.resize(state.world.entities.size());
  }
  return state.controls[index];
}

namespace {

// Entities from which a step is shared out among threads: below that the hand-over costs more
// than the moves.
constexpr uint32_t kParallelEntities = 128;
// Entities from which light per-entity work (EntityMover::share: the contacts' boxes, a few
// nanoseconds each) is shared out in a run of its own: handing it to another core costs more
// below that.
constexpr size_t kParallelLightEntities = 8192;
// Entities a thread takes at a time (consecutive in the moving order, so mostly of one lane):
// small enough that the threads end together, large enough that taking one costs nothing.
constexpr size_t kChunkEntities = 32;
constexpr uint32_t kArrangeSteps = 50;
// Entities from which the moves go in lane order and ask for the next mover's records ahead:
// fewer (tens of kilobytes of entities) stay in the core's cache from one step to the next,
// where the sorting and the prefetches only cost their instructions.
constexpr uint32_t kArrangedEntities = 32;

std::optional<xodr::LaneType> lane_type_at(const xodr::Map& map, const RoadCoordinates& road) {
  const auto node = map.lane_graph().find(xodr::LaneRef{road.road, road.section, road.lane});
  return node ? std::optional<xodr::LaneType>(map.lane_graph().info(*node).type) : std::nullopt;
}

// Whether the point (x, y) lies on a lane vehicles drive on, as Map::locate with max_distance 0
// and drivable_only answers it, remembered in `look` for the walker's next steps. A walker on
// its sidewalk asks every step for a point that moves a centimetre, mostly metres from any
// road: the look-up goes as far as kAround, and its distance d to the nearest such lane (or
// kAround when none is that near) clears every point within d / 2 of (x, y) without another
// look-up. A point within d of (x, y) on a drivable lane would be within d of it by the
// look-up's own measure as well (the chunk that holds the point is among those it examines,
// the rectangle's distance and the lateral offset change by no more than the point moves);
// half of d leaves room for lanes whose width changes along the road. A walker standing still
// asks again for the same point, which gets the same answer. The height is left out: it only
// ranks lanes at the same distance.
bool on_drivable_lane(const xodr::Map& map, double x, double y, KerbLook& look) {
  constexpr double kAround = 4.0;  // m looked around the point
  const double dx = x - look.x, dy = y - look.y;
  if (dx == 0.0 && dy == 0.0) {
    return look.on_road;
  }
  if (dx * dx + dy * dy < look.clear * look.clear) {
    return false;
  }
  xodr::LocateOptions options;
  options.max_distance = kAround;
  options.drivable_only = true;
  const auto found = map.locate(x, y, options);
  // Of the answers within kAround, one at distance 0 is there when (and only when) a look-up
  // with max_distance 0 finds the point on a lane: both rank the same candidates by distance.
  look.x = x;
  look.y = y;
  look.on_road = found && found->distance == 0.0;
  look.clear = look.on_road ? 0.0 : 0.5 * (found ? found->distance : kAround);
  return look.on_road;
}

// A generated walker about to step onto a road along its heading (the point a metre ahead is on
// a lane vehicles drive on, its own lane is not) waits while a vehicle is close to its way
// across (controllers/npc_caution.h).
bool waits_at_kerb(const SimState& state, uint32_t index, const FollowView& view, KerbLook& look,
                   std::vector<uint32_t>& near) {
  constexpr double kKerb = 1.0;    // m ahead
  constexpr double kAcross = 8.0;  // m of its way looked along: about two lanes
  const Entity& me = state.world.entities[index];
  if (state.map == nullptr || !view.has_shapes()) {
    return false;
  }
  const double x = me.state().pose.x + kKerb * std::cos(me.state().pose.h);
  const double y = me.state().pose.y + kKerb * std::sin(me.state().pose.h);
  if (!on_drivable_lane(*state.map, x, y, look)) {
    return false;
  }
  const auto here = me.state().road ? lane_type_at(*state.map, *me.state().road) : std::nullopt;
  if (here && xodr::is_drivable(*here)) {
    return false;  // on the road already: across it rather than stand in it
  }
  return walker_waits(me, index, view, kAcross, near);
}

// Pedestrians: on a sidewalk (or any lane) facing along it they walk along it like
// any entity of the default controller. One facing across its lane (more than 45 degrees off
// the lane's direction, e.g. placed with a relative orientation of pi/2) crosses the road: it
// walks straight along its heading over the lanes and stops on the first sidewalk (or off the
// road) once it has crossed a lane vehicles drive on.
void step_pedestrian(SimState& state, uint32_t index, const DefaultController& ideal,
                     const MotionContext& motion, const FollowView& view) {
  Entity& entity = state.world.entities[index];
  ControlState& control = control_of(state, index);
  if (entity.lane.on_road && std::abs(entity.lane.heading_offset) > 0.25 * std::numbers::pi) {
    entity.lane.on_road = false;  // free motion along the heading
    control.crossing = true;
    control.crossed_roadway = false;
  }
  double pace_command = -1.0;
  if (!control.crossing && entity.lane.on_road && is_generated(state, index)) {
    // Generated walkers keep right of oncoming ones, pass slower ones on the left and never
    // walk into anyone (controllers/npc_caution.h).
    constexpr double kSideStepSpeed = 0.6;  // m/s across the sidewalk at most
    if (control.pace < 0.0) {
      control.pace = entity.speed_command;
    }
    const WalkerMove move = walker_move(entity, index, view, control.pace, *motion.nearby);
    pace_command = std::min(move.speed, entity.speed_command);
    if (pace_command > 0.0 && waits_at_kerb(state, index, view, control.kerb, *motion.nearby)) {
      pace_command = 0.0;
    }
    // Sideways at most half as fast as forwards in this step (30 degrees off the sidewalk): far
    // from the 45 degrees that mean crossing the road, and no sidestep on the spot. (Bounded by
    // the speed of the step before, a walker that has to slow down sharply stepped aside nearly
    // on the spot, turned past 45 degrees and crossed into the walker beside it.)
    const double step = std::min(kSideStepSpeed, 0.5 * std::max(pace_command, 0.0)) * motion.dt;
    entity.lateral_command += std::clamp(move.lateral - entity.lateral_command, -step, step);
    entity.speed_command = pace_command;
  }
  ideal.step(entity, motion);
  if (pace_command >= 0.0 && entity.speed_command == pace_command) {
    entity.speed_command = control.pace;  // back to its own pace unless it reached an end
  }
  if (!control.crossing || state.map == nullptr) {
    return;
  }
  const auto type =
      entity.state().road ? lane_type_at(*state.map, *entity.state().road) : std::nullopt;
  if (type && xodr::is_drivable(*type)) {
    control.crossed_roadway = true;
  } else if (control.crossed_roadway &&
             (!type || *type == xodr::LaneType::kSidewalk || *type == xodr::LaneType::kBorder)) {
    // Across: wait on the far side.
    control.crossing = false;
    entity.speed_command = 0.0;
  }
}

// One entity's move with its controller. It reads and writes only that entity (and its
// control state), the map and, for car following and generated traffic, the picture `view`
// taken before the moves.
void move_one(SimState& state, uint32_t i, const MotionContext& motion, const FollowView& view,
              LanesAhead& ahead) {
  const DefaultController ideal;
  Entity& entity = state.world.entities[i];
  const ControllerKind kind = state.controls[i].effective();
  if (!entity.state().placed || entity.towed_by || state.frozen(i)) {
    // A connected trailer follows its tower (motion/trailers.h); during a ghost's head start
    // only the ghost moves.
    return;
  }
  if (entity.info.kind == ObjectKind::kPedestrian && kind == ControllerKind::kDefault) {
    step_pedestrian(state, i, ideal, motion, view);
    return;
  }
  switch (kind) {
    case ControllerKind::kDefault:
      ideal.step(entity, motion);
      break;
    case ControllerKind::kAcc:
      step_acc(state, i, motion, view, ahead);
      break;
    case ControllerKind::kDynamics:
      if (entity.pose_command) {
        // FollowTrajectoryAction in position mode places the entity on the path (ideal).
        state.controls[i].dynamics.reset();
        ideal.step(entity, motion);
      } else {
        finish_dynamics(state, i, motion);
      }
      break;
    case ControllerKind::kExternal:
      step_commanded(state, i, ideal, motion);
      break;
    case ControllerKind::kFollowGhost:
      step_follow_ghost(state, i, motion);
      break;
    case ControllerKind::kEsminiVehicle:
      step_esmini_driver(state, i, motion, view);
      break;
    case ControllerKind::kNaturalDriver:
      break;  // after every other entity (step_natural_drivers)
    case ControllerKind::kAlksR157:
      break;  // after the others (EntityMover::move)
    case ControllerKind::kSloppyDriver:
      break;  // after the others, in entity order (step_sloppy_drivers)
  }
}

// Asks the memory for the cache lines from `from` to `to` (inclusive).
void prefetch_lines(const void* from, const void* to) {
  constexpr uintptr_t kLine = 64;
  const auto end = reinterpret_cast<uintptr_t>(to);
  for (uintptr_t at = reinterpret_cast<uintptr_t>(from) & ~(kLine - 1); at <= end; at += kLine) {
    __builtin_prefetch(reinterpret_cast<const void*>(at));
  }
}

// Asks the memory for entity `i`'s records one move ahead of its own: the movers go in lane
// order, which is not the order of the entities' storage, so each move began by waiting on the
// first loads of its entity and its control record (in `step_acc` and `move_one`). Only what
// every move reads: the entity up to its info's performance (Entity's fields are in the order a
// step reads them; the info's name and model, the still step memo's copy of the motion and what
// follows are read by few entities or none, and asking for them took room in the cache from
// what the step reads) and the control record's first line. A hint only: nothing is read or
// written.
void prefetch_mover_records(const SimState& state, uint32_t i) {
  const Entity& entity = state.world.entities[i];
  prefetch_lines(&entity, &entity.info.max_deceleration_rate);
  __builtin_prefetch(&state.controls[i]);
}

// Moves the entities order[begin, end) in that order; ahead[k] is entity order[k]'s.
[[gnu::hot]] void move_range(SimState& state, const MotionContext& motion, const FollowView& view,
                             std::vector<LanesAhead>& ahead, const std::vector<uint32_t>& order,
                             size_t begin, size_t end) {
  if (order.size() < kArrangedEntities) {
    for (size_t k = begin; k < end; ++k) {
      move_one(state, order[k], motion, view, ahead[k]);
    }
    return;
  }
  for (size_t k = begin; k < end; ++k) {
    if (k + 1 < end) {
      prefetch_mover_records(state, order[k + 1]);
    }
    move_one(state, order[k], motion, view, ahead[k]);
  }
}

}  // namespace

struct EntityMover::Impl {
  // More threads than cores would only wait for each other.
  explicit Impl(unsigned threads_in)
      : threads(std::clamp(threads_in, 1u, std::max(1u, std::thread::hardware_concurrency()))) {}

  unsigned threads;
  std::unique_ptr<WorkerPool> pool;  ///< made on the first parallel step
  /// Whether a step is shared out among the threads, from the steps' times.
  ThreadChoice choice;
  bool could_share = false;  ///< the last step had enough entities to be shared out
  FollowView view;
  /// Generated vehicles' claims on junction conflict zones (made with the first of them).
  std::unique_ptr<GiveWay> give_way;
  /// Car following's lanes ahead, in move order: ahead[k] belongs to entity order[k] (so that
  /// the movers read them one after the other).
  std::vector<LanesAhead> ahead;
  /// Per worker: lane span scratch, and neighbour query scratch.
  std::vector<std::vector<xodr::LaneSpan>> scratch;
  std::vector<CurvatureMemo> curvatures;  ///< per worker (motion/controller.h)
  std::vector<std::vector<uint32_t>> nearby;
  /// The order entities are moved in: by lane, so that one after the other they read the same
  /// parts of the map (the result does not depend on it; with many vehicles spread over a city
  /// map, memory traffic is most of a move's time). Sorted again every kArrangeSteps steps;
  /// below kArrangedEntities the entities' own order.
  std::vector<uint32_t> order;
  uint32_t steps_since_arranged = 0;

  // The worker pool's set-up and the moves shared out among the workers are out of line: with
  // one worker the step runs neither, and its code stays small.
  [[gnu::noinline]] void prepare_pool() {
    if (!pool) {
      pool = std::make_unique<WorkerPool>(threads);
    }
    pool->prepare();
  }

  // Each entity's move depends only on itself and the picture taken before, so how the
  // entities are shared out among threads does not change any result. The movers also make
  // the moved entities' contact boxes (each its own entity's slot), which the contacts'
  // update, serial on this thread, then takes where the entity has not moved again since.
  [[gnu::noinline]] void move_shared(SimState& state, const MotionContext& motion) {
    state.contacts.premade.resize(state.world.entities.size());
    state.contacts.premade_fresh = true;
    pool->run(order.size(), kChunkEntities, [&](size_t begin, size_t end, unsigned worker) {
      MotionContext worker_context = motion;
      worker_context.scratch = &scratch[worker];
      worker_context.nearby = &nearby[worker];
      worker_context.curvatures = &curvatures[worker];
      move_range(state, worker_context, view, ahead, order, begin, end);
      for (size_t k = begin; k < end; ++k) {
        premake_contact_box(state, order[k]);
      }
    });
  }

  // The picture of the others, its per-entity part shared out as the moves will be: each
  // thread fills first the entities of its own share of the moves (the same count and chunks:
  // WorkerPool::run), those it moved in the last steps, so what the picture reads of an
  // entity is mostly in that thread's cache, and only the filled targets cross to this thread
  // for the gathering. The worker waits awake for the moves, which follow once the picture is
  // gathered and the give-way claims are settled. The picture is the same on any number of
  // threads (FollowView::begin).
  [[gnu::noinline]] void picture_shared(const SimState& state, bool neighbours) {
    view.begin(state, neighbours);
    pool->run(
        order.size(), kChunkEntities,
        [&](size_t begin, size_t end, unsigned) {
          for (size_t k = begin; k < end; ++k) {
            view.fill(state, order[k]);
          }
        },
        WorkerPool::After::kAwait);
    view.finish();
  }

  [[gnu::hot]] void arrange(const SimState& state) {
    const auto count = static_cast<uint32_t>(state.world.entities.size());
    if (order.size() == count &&
        (count < kArrangedEntities || ++steps_since_arranged < kArrangeSteps)) {
      return;
    }
    rearrange(state, count);
  }

  // The sorting itself, out of line: most steps keep the order, and the per-step code stays
  // small (it shares the instruction cache with the rest of the step).
  [[gnu::noinline]] void rearrange(const SimState& state, uint32_t count) {
    steps_since_arranged = 0;
    // Each entity's lanes ahead go with it to its new place in the order (entities added
    // since the last arrangement start without any).
    std::vector<LanesAhead> by_entity(count);
    for (size_t k = 0; k < order.size() && k < ahead.size(); ++k) {
      by_entity[order[k]] = std::move(ahead[k]);
    }
    order.resize(count);
    std::vector<std::pair<uint64_t, uint32_t>> keys(count);
    for (uint32_t i = 0; i < count; ++i) {
      const LaneFollow& lane = state.world.entities[i].lane;
      keys[i] = {lane.on_road ? uint64_t{lane.node} : UINT64_MAX, i};
    }
    if (count >= kArrangedEntities) {
      std::sort(keys.begin(), keys.end());
    }
    ahead.resize(count);
    for (uint32_t k = 0; k < count; ++k) {
      order[k] = keys[k].second;
      ahead[k] = std::move(by_entity[order[k]]);
    }
  }
};

EntityMover::EntityMover(unsigned threads) : impl_(std::make_unique<Impl>(threads)) {}
EntityMover::~EntityMover() = default;
EntityMover::EntityMover(EntityMover&&) noexcept = default;
EntityMover& EntityMover::operator=(EntityMover&&) noexcept = default;

bool EntityMover::times_steps() const { return impl_->threads > 1; }

void EntityMover::charge_step(std::chrono::steady_clock::duration step) {
  if (impl_->could_share) {
    impl_->choice.charge(step);
  }
}

void EntityMover::share(size_t count, const std::function<void(size_t, size_t)>& work) {
  Impl& impl = *impl_;
  if (impl.threads == 1 || count < kParallelLightEntities) {
    work(0, count);
    return;
  }
  if (!impl.pool) {
    impl.pool = std::make_unique<WorkerPool>(impl.threads);
  }
  impl.pool->run(count, 2 * kChunkEntities,
                 [&](size_t begin, size_t end, unsigned) { work(begin, end); });
}

namespace {

// What EntityMover::move needs to know of the entities before it moves them.
struct MoverScan {
  std::vector<uint32_t> dynamic;  ///< moved by the dynamics controller this step
  bool following = false;         ///< some controller reads the others in the picture
  bool natural = false;           ///< some entity has esmini's NaturalDriver
  bool alks = false;              ///< some entity has esmini's ALKS R157 controller
  bool sloppy = false;            ///< some entity (or split partner) has esmini's sloppyDriver
};

constexpr uint32_t kind_bit(ControllerKind kind) { return 1u << static_cast<unsigned>(kind); }

// Looks at every entity's controllers once, and hands the lateral partner of a split the speed
// and heading its step begins with. The kinds met are gathered as one bit each and the flags in
// locals, the records read through the vectors' data (the compiler kept flags in memory and read
// the vectors' bounds again for every entity, the list of dynamic entities might have aliased
// them).
MoverScan scan_for_move(SimState& state, uint32_t count) {
  MoverScan scan;
  const Entity* const entities = state.world.entities.data();
  ControlState* const controls = state.controls.data();
  uint32_t kinds = 0;
  bool following = false;
  bool natural = false;
  for (uint32_t i = 0; i < count; ++i) {
    ControlState& control = controls[i];
    const Entity& entity = entities[i];
    const ControllerKind kind = control.effective();
    kinds |= kind_bit(kind);
    if (OutOfLine<DomainPartner>& partner = control.partner) {
      // The lateral controller of a split steers with the speed and heading the step began with.
      partner->step_start_speed = entity.state().speed;
      partner->step_start_heading = entity.lane.heading_offset;
      if (partner->kind == ControllerKind::kSloppyDriver) {
        kinds |= kind_bit(ControllerKind::kSloppyDriver);
      }
    }
    // Moved by the dynamics controller this step (a FollowTrajectoryAction in position mode
    // places the entity on its path instead: ideal motion).
    if (kind == ControllerKind::kDynamics && entity.state().placed && !entity.pose_command &&
        !entity.towed_by) {
      scan.dynamic.push_back(i);
    }
    // Car following and esmini's offroadFollower read the others in the picture (esmini's
    // interactiveDriver does not: without it the picture is not taken). Once one does, the
    // entities after it are not read for it (with many vehicles each read is a cache miss).
    following = following || ((kind == ControllerKind::kAcc ||
                               (kind == ControllerKind::kEsminiVehicle &&
                                esmini_driver_reads_view(control.esmini_driver.get()))) &&
                              entity.state().placed);
    natural |= control.natural != nullptr;
  }
  scan.alks = (kinds & kind_bit(ControllerKind::kAlksR157)) != 0;
  scan.sloppy = (kinds & kind_bit(ControllerKind::kSloppyDriver)) != 0;
  scan.following = following;
  scan.natural = natural;
  return scan;
}

}  // namespace

[[gnu::hot]] void EntityMover::move(SimState& state, const MotionContext& motion) {
  Impl& impl = *impl_;
  const auto count = static_cast<uint32_t>(state.world.entities.size());
  if (count == 0) {
    return;
  }
  // A control state for every entity, also those added by traffic (control_of).
  if (state.controls.size() < count) {
    state.controls.resize(count);
  }
  const MoverScan scan = scan_for_move(state, count);
  // The vehicle models of the dynamics controller step first, all integrated as one system: a
  // model's step reads only its own entity.
  if (!scan.dynamic.empty()) {
    begin_dynamics(state, scan.dynamic, motion);
  }
  // Generated traffic looks around itself (controllers/npc_caution.h): the view then also
  // holds the grid of the others.
  const bool generated = !state.traffic.lifetimes.empty();
  impl.could_share = impl.threads > 1 && count >= kParallelEntities;
  const unsigned workers = impl.could_share && impl.choice.shared() ? impl.threads : 1;
  if (workers > 1) {
    // The worker wakes up while this thread arranges the order (below) and joins the picture's
    // run, or the moves' when there is no picture, when it starts.
    impl.prepare_pool();
  }
  // The order depends only on the entities' lanes, not on the picture.
  impl.arrange(state);
  if (scan.following || generated) {
    if (workers > 1) {
      impl.picture_shared(state, generated);
    } else {
      impl.view.build(state, generated);
    }
  }
  if (generated && state.map != nullptr) {
    if (!impl.give_way) {
      impl.give_way = std::make_unique<GiveWay>();
    }
    impl.give_way->begin_step(state);
  }
  impl.view.set_give_way(impl.give_way.get());
  const std::vector<uint32_t>& order = impl.order;
  if (impl.scratch.size() < workers) {  // one per worker, kept from step to step
    impl.scratch.resize(workers);
    impl.nearby.resize(workers);
    impl.curvatures.resize(workers);
  }
  MotionContext context = motion;
  context.scratch = &impl.scratch[0];
  context.nearby = &impl.nearby[0];
  context.curvatures = &impl.curvatures[0];
  if (workers == 1) {
    move_range(state, context, impl.view, impl.ahead, order, 0, order.size());
  } else {
    impl.move_shared(state, motion);
  }
  // esmini's NaturalDriver entities move after all others, one after the other.
  if (scan.natural) {
    step_natural_drivers(state, context);
  }
  // esmini's ALKS controller sees the others where they are after their moves (its controllers
  // step after its default controller), in entity order on this thread.
  if (scan.alks) {
    step_alks_r157_entities(state, context);
  }
  // esmini's sloppyDriver entities draw from the run's one generator: in entity order, here.
  if (scan.sloppy) {
    step_sloppy_drivers(state, context);
  }
}

}  // namespace corsa::engine::detail
