// esmini's ALKS_R157SM_Controller (controllers/alks_r157.h): its settings, what the ego sees of
// the others each step, and the move at the model's speed.

#include "controllers/alks_r157.h"

#include <cmath>
#include <numbers>
#include <string>
#include <variant>

#include "controllers/alks_r157_model.h"
#include "controllers/controllers.h"
#include "corsa/engine/oriented_box.h"
#include "corsa/xosc/scenario.h"
#include "geometry/angle.h"
#include "positions/relative_distance.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {
namespace {

constexpr const char* kAlksLabel = "ALKS_R157SM_Controller";

std::optional<AlksModel> alks_model_named(const std::string& name) {
  if (name == "Regulation") return AlksModel::kRegulation;
  if (name == "ReferenceDriver") return AlksModel::kReferenceDriver;
  return std::nullopt;
}

// The ReferenceDriver's own properties (esmini reads them for that model only).
void read_driver_settings(SimState& state, const xosc::Controller& controller,
                          AlksSettings& settings) {
  const xosc::Properties& properties = controller.properties;
  if (const auto mode = properties.get("cutInPerceptionDelayMode")) {
    if (*mode == "Time" || *mode == "Dist") {
      settings.perceive_by_time = *mode == "Time";
    } else {
      state.diagnostics.add(controller.properties.source.warning(
          std::string(kAlksLabel) + " cutInPerceptionDelayMode '" + *mode +
          "' is neither Dist nor Time: Dist is used"));
    }
  }
  settings.pedestrian_risk_time =
      nonnegative_property(state, controller, "pedestrianRiskEvaluationTime", kAlksLabel)
          .value_or(settings.pedestrian_risk_time);
  settings.aeb_ttc =
      nonnegative_property(state, controller, "aebTTC", kAlksLabel).value_or(settings.aeb_ttc);
  if (properties.get("lateralTrigDistance")) {
    settings.lateral_trigger =
        nonnegative_property(state, controller, "lateralTrigDistance", kAlksLabel).value_or(0.0);
  }
  settings.overlap_tolerance =
      nonnegative_property(state, controller, "overlapTolerance", kAlksLabel)
          .value_or(settings.overlap_tolerance);
}

// The front axle's distance ahead of the reference point (m); half the box length ahead of its
// centre without one.
double alks_front_x(const Entity& entity) {
  if (entity.object != nullptr) {
    if (const auto* vehicle = std::get_if<xosc::Vehicle>(&entity.object->object)) {
      if (vehicle->axles.front_axle) return vehicle->axles.front_axle->position_x;
    }
  }
  return entity.info.box.center_x + 0.5 * entity.info.box.length;
}

// What the ego sees of entity `i` now.
AlksSeen alks_seen_of(const SimState& state, uint32_t i) {
  const Entity& entity = state.world.entities[i];
  AlksSeen seen;
  const bool visible = i >= state.controls.size() || state.controls[i].traffic_visible;
  if (!entity.state().placed || entity.removed || entity.ghost || !visible ||
      !entity.state().road || state.map == nullptr) {
    return seen;
  }
  const RoadCoordinates& road = *entity.state().road;
  const auto span = state.map->lane_span(road.road, road.s, road.lane);
  if (!span) return seen;
  seen.usable = true;
  seen.vehicle = entity.info.kind == ObjectKind::kVehicle;
  seen.pedestrian = entity.info.kind == ObjectKind::kPedestrian;
  seen.motorbike = entity.info.category == EntityCategory::kMotorbike;
  seen.road = road;
  seen.speed = entity.state().speed;
  seen.offset = road.t - span->t_center();
  seen.lane_width = span->width();
  seen.h = entity.state().pose.h;
  const double road_heading = state.map->reference(road.road, road.s).hdg;
  seen.h_rel = wrap_angle(entity.state().pose.h - road_heading);
  // Velocity in the road's frame (esmini's, from the last movement): on a lane, the speed along
  // it and the lateral motion (both in the lane's direction of travel); off the lanes, the
  // speed along the heading.
  const double c = std::cos(seen.h_rel), s = std::sin(seen.h_rel);
  if (entity.lane.on_road) {
    seen.v_s = entity.state().speed * entity.lane.dir;
    seen.v_t = entity.state().lateral_speed * entity.lane.dir;
    seen.acc_s = entity.state().acceleration * entity.lane.dir;
  } else {
    seen.v_s = entity.state().speed * c;
    seen.v_t = entity.state().speed * s;
    seen.acc_s = entity.state().acceleration * c;
  }
  seen.front_x = seen.vehicle ? alks_front_x(entity) : 0.5 * entity.info.box.length;
  seen.box = entity.info.box;
  seen.pose = entity.state().pose;
  return seen;
}

}  // namespace

bool AlksView::measure(AlksObject& info, double range) const {
  if (!info.entity || *info.entity == ego) return false;
  const AlksSeen& o = seen[*info.entity];
  const AlksSeen& e = seen[ego];
  if (!o.usable || !e.usable || o.road.road != e.road.road) return false;
  const double dir = std::abs(e.h_rel) > 0.5 * std::numbers::pi ? -1.0 : 1.0;
  const double ds = (o.road.s - e.road.s) * dir;  // reference point to reference point
  if (std::abs(ds) > range) return false;
  int d_lane = o.road.lane - e.road.lane;
  // Lanes 1 and -1 are neighbours across the centre lane.
  if (d_lane == 2 && o.road.lane == 1 && e.road.lane == -1) d_lane = 1;
  if (d_lane == -2 && o.road.lane == -1 && e.road.lane == 1) d_lane = -1;
  if (!(ds > kAlksSmall && (o.pedestrian || (d_lane > -2 && d_lane < 2)))) return false;
  info.d_lane = d_lane;
  const Entity& from = state->world.entities[ego];
  const Entity& to = state->world.entities[*info.entity];
  info.dist_long = entity_distance(
      *state, from, to,
      {xosc::CoordinateSystem::kRoad, xosc::RelativeDistanceType::kLongitudinal, true});
  info.dist_lat =
      entity_distance(*state, from, to,
                      {xosc::CoordinateSystem::kRoad, xosc::RelativeDistanceType::kLateral, true});
  info.dv_s = (e.v_s - o.v_s) * dir;
  info.dv_t = (e.v_t - o.v_t) * (o.road.t - e.road.t < 0.0 ? -1.0 : 1.0);
  if (info.dv_s > 0.0) {
    info.ttc = info.dist_long / info.dv_s;
    // esmini divides as is: a standing ego gets a headway of +-inf by the distance's sign (a
    // negative one counts as close, as there). At distance 0 too its 0/0 is NaN, which no
    // comparison finds close: the large headway here, which none does either.
    info.thw = e.v_s == 0.0 && info.dist_long == 0.0 ? kAlksLarge : info.dist_long / e.v_s;
  } else {
    info.ttc = kAlksLarge;
    info.thw = kAlksLarge;
  }
  return true;
}

bool AlksView::covers_front(uint32_t other, double tolerance) const {
  // The other's box corners projected onto the ego's front edge (left to right): all on the
  // edge (inside), or some beyond each end (covering it), is more than a partial overlap.
  const AlksSeen& e = seen[ego];
  const AlksSeen& o = seen[other];
  const double c = std::cos(e.pose.h), s = std::sin(e.pose.h);
  const double front = e.box.center_x + 0.5 * e.box.length;
  const double half = 0.5 * e.box.width;
  const double lx = e.pose.x + front * c - half * s, ly = e.pose.y + front * s + half * c;
  const double dx = 2.0 * half * s, dy = -2.0 * half * c;  // left corner to right corner
  const double width = 2.0 * half;
  const OrientedBox box = box_of(o.box, o.pose);
  int inside = 0, beyond_left = 0, beyond_right = 0;
  for (const double along : {1.0, -1.0}) {
    for (const double across : {1.0, -1.0}) {
      const double px =
          box.cx + along * box.half_length * box.cos_h - across * box.half_width * box.sin_h;
      const double py =
          box.cy + along * box.half_length * box.sin_h + across * box.half_width * box.cos_h;
      const double u = width > 0.0 ? ((px - lx) * dx + (py - ly) * dy) / (width * width) : 0.0;
      if (u >= 0.0 && u <= 1.0) {
        ++inside;
        if (u * width < tolerance) {
          ++beyond_left;
        } else if ((1.0 - u) * width < tolerance) {
          ++beyond_right;
        }
      } else {
        const double beyond = u < 0.0 ? u * width : (u - 1.0) * width;  // m past the end
        if (std::abs(beyond) < tolerance) ++inside;
        (u < 0.0 ? beyond_left : beyond_right)++;
      }
    }
  }
  return inside == 4 || (beyond_left > 0 && beyond_right > 0);
}

bool is_alks_r157(const xosc::Controller& controller) {
  return esmini_type(controller) == kAlksLabel;
}

std::shared_ptr<AlksR157> make_alks_r157(SimState& state, const xosc::ObjectController& oc) {
  const xosc::Controller& controller = oc.controller;
  auto alks = std::make_shared<AlksR157>();
  AlksSettings& settings = alks->settings;
  const std::string model = controller.properties.get("model").value_or("");
  if (const auto known = alks_model_named(model)) {
    settings.model = *known;
  } else if (model == "RSS" || model == "FSM") {
    state.diagnostics.add_once(
        "alks-model:" + model,
        oc.source.warning(std::string(kAlksLabel) + " model '" + model +
                          "' is not emulated (Regulation and ReferenceDriver are)"));
    return nullptr;  // the caller substitutes (and says so)
  } else {
    // esmini stops at an unknown or missing model; the catalog's default is read instead.
    state.diagnostics.add(oc.source.warning(std::string(kAlksLabel) + " model '" + model +
                                            "' is none of Regulation, ReferenceDriver, RSS, FSM "
                                            "(read as ReferenceDriver)"));
  }
  const auto cruise = controller.properties.get("cruise");
  if (cruise == "true" || cruise == "True") settings.cruise = true;
  if (cruise == "false" || cruise == "False") settings.cruise = false;
  settings.full_stop = controller.properties.get("fullStop") == "true";
  settings.always_trig = controller.properties.get("alwaysTrigOnScenario") == "true";
  if (settings.model == AlksModel::kReferenceDriver) {
    read_driver_settings(state, controller, settings);
    if (settings.lateral_trigger) {
      alks->trigger.wandering = false;
      alks->trigger.threshold = *settings.lateral_trigger;
    }
  }
  return alks;
}

void activate_alks_r157(AlksR157& alks) { alks.pending_activation = true; }

void step_alks_r157_entities(SimState& state, const MotionContext& motion) {
  const auto count = static_cast<uint32_t>(state.world.entities.size());
  AlksView view;
  view.state = &state;
  view.dt = motion.dt;
  bool seen_now = false;
  for (uint32_t i = 0; i < count && i < state.controls.size(); ++i) {
    ControlState& control = state.controls[i];
    Entity& entity = state.world.entities[i];
    if (control.effective() != ControllerKind::kAlksR157 || !control.alks ||
        !entity.state().placed || entity.towed_by || state.frozen(i)) {
      continue;
    }
    if (!seen_now) {
      view.seen.resize(count);
      for (uint32_t k = 0; k < count; ++k) view.seen[k] = alks_seen_of(state, k);
      seen_now = true;
    }
    view.ego = i;
    // Active on either domain, the lateral alone too, it sets the speed: esmini's controller
    // steps whenever it is active and its Step does not look at the domains (unlike its
    // NaturalDriver's, controllers/natural_driver.cpp).
    AlksR157& alks = *control.alks;
    if (alks.pending_activation) {
      alks.set_speed = entity.state().speed;  // esmini's Activate: the speed then
      alks.pending_activation = false;
    }
    const double speed = alks_step(alks, view);
    move_at_controller_speed(entity, speed, [&] { DefaultController().step(entity, motion); });
    // The next ALKS entity sees this one where it is now.
    view.seen[i] = alks_seen_of(state, i);
  }
}

}  // namespace corsa::engine::detail
