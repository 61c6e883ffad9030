// The decisions of esmini's ALKS_R157SM_Controller models, step by step as esmini makes them
// (controllers/alks_r157_model.h): which object to focus on, whether the situation is critical
// and how to brake. The constants are esmini's, from UN R157 (5.2.5 and Annex 3).

#include "controllers/alks_r157_model.h"

#include <algorithm>
#include <cmath>

namespace corsa::engine::detail {
namespace {

constexpr double kAlksG = 9.8;                    // m/s^2, as esmini's model computes the braking
constexpr double kAlksRegulationMaxDec = 6.0;     // m/s^2 (UN R157 5.2.5.3)
constexpr double kAlksRegulationReaction = 0.35;  // s
constexpr double kAlksRegulationRange = 46.0;     // m
constexpr double kAlksDriverReaction = 0.75;      // s (Annex 3)
constexpr double kAlksDriverRange = 100.0;        // m
constexpr double kAlksDriverBrake = 0.774;        // g, reached in kAlksBrakeBuildUp
constexpr double kAlksAebBrake = 0.85;            // g
constexpr double kAlksBrakeBuildUp = 0.6;         // s
constexpr double kAlksReleaseDeceleration = 0.4;  // m/s^2, the foot off the accelerator
constexpr double kAlksCriticalTtc = 2.0;          // s
constexpr double kAlksCriticalThw = 2.0;          // s
constexpr double kAlksWandering = 0.375;          // m, lane wandering (Annex 3 3.4.1)
constexpr double kAlksPerceptionDistance = 0.72;  // m, cutInPerceptionDelayMode Dist
constexpr double kAlksPerceptionTime = 0.4;       // s
constexpr double kAlksLeaderDeceleration = -5.0;  // m/s^2: a leader braking harder is perceived

// esmini's SIGN: 0 counts as positive.
double alks_sign(double x) { return x < 0.0 ? -1.0 : 1.0; }

bool alks_near(double a, double b) { return std::abs(a - b) < kAlksSmall; }

class AlksStepper {
 public:
  AlksStepper(AlksR157& alks, const AlksView& view)
      : m_(alks), view_(view), v_(view.seen[view.ego].speed), dt_(view.dt) {}

  double step() {
    const bool driver = m_.settings.model == AlksModel::kReferenceDriver;
    if (m_.focus.entity && driver && m_.phase != AlksPhase::kInactive && m_.settings.full_stop) {
      // An ongoing reaction until standstill: only the object in focus is measured again.
      view_.measure(m_.focus, range());
    } else {
      detect();
    }
    const bool critical = driver ? driver_critical() : regulation_critical();
    if (critical) {
      return driver ? driver_react() : regulation_react();
    }
    return cruise();
  }

 private:
  double range() const {
    return m_.settings.model == AlksModel::kRegulation ? kAlksRegulationRange : kAlksDriverRange;
  }
  const AlksSeen& seen(uint32_t i) const { return view_.seen[i]; }
  const AlksSeen& ego() const { return view_.seen[view_.ego]; }

  double min_dist() const {
    if (m_.settings.model == AlksModel::kReferenceDriver) {
      return 2.0 + v_ * 2.0;
    }
    // UN R157 5.2.3.3: the time gap grows with the speed.
    const double gap =
        v_ * 3.6 < 10.0 ? 1.0 + (std::max(2.0, v_) - 2.0) / 7.8 : 1.0 + v_ * 3.6 / 100.0;
    return std::max(v_ * gap, 2.0);
  }

  // esmini's Detect: every entity measured in turn; the closest threat becomes the focus. The
  // record of the entity before carries over into the next one's (as in esmini, its action
  // stays unless the next one's judgement changes it).
  void detect() {
    AlksObject candidate;
    AlksObject probe;
    for (uint32_t i = 0; i < view_.seen.size(); ++i) {
      probe.entity = i;
      if (!view_.measure(probe, range()) || safe(probe)) {
        continue;
      }
      const bool candidate_cuts_out = candidate.entity && seen(*candidate.entity).vehicle &&
                                      candidate.action == AlksScenario::kCutOut;
      if (!(probe.dist_long < candidate.dist_long || (probe.d_lane == 0 && candidate_cuts_out))) {
        continue;
      }
      if (seen(i).vehicle && probe.action == AlksScenario::kCutOut && candidate.entity &&
          candidate.d_lane == 0) {
        // Cutting out in front of an object in the lane: the one with the least TTC.
        if (probe.ttc < candidate.ttc) candidate = probe;
      } else if (probe.d_lane == 0 && candidate_cuts_out) {
        // Beyond a vehicle cutting out: the one with the least TTC, still a cut-out.
        if (probe.ttc < candidate.ttc) {
          const auto cutting = candidate.entity;
          candidate = probe;
          candidate.cut_out_vehicle = cutting;
          candidate.action = AlksScenario::kCutOut;
        }
      } else {
        candidate = probe;
      }
    }
    if (candidate.entity && candidate.action != AlksScenario::kNone &&
        (candidate.entity != m_.focus.entity || candidate.action != m_.focus.action)) {
      m_.scenario = candidate.action;
    }
    m_.focus = candidate;
  }

  // esmini's CheckSafety: whether the object is no threat (not in or entering the ego's lane).
  bool safe(AlksObject& info) {
    if (!info.entity || info.dist_lat == kAlksLarge) return true;
    return m_.settings.model == AlksModel::kRegulation ? regulation_safe(info) : driver_safe(info);
  }

  bool regulation_safe(AlksObject& info) const {
    if (info.d_lane == 0) {
      info.action = AlksScenario::kDeceleration;
      return false;
    }
    const AlksSeen& o = seen(*info.entity);
    if (o.lane_width > 0.0 && info.dist_lat > -kAlksSmall) {
      // The front wheel (or the box's front) on the side toward the ego, 0.3 m inside its lane.
      const double x = o.vehicle ? o.front_x : 0.5 * o.box.length;
      const double y = -alks_sign(info.d_lane) * 0.5 * o.box.width;
      const double across = x * std::sin(o.h_rel) + y * std::cos(o.h_rel);
      const double intrusion = (o.offset + across) * -alks_sign(info.d_lane);
      if (intrusion > 0.5 * o.lane_width + 0.3) {
        info.action = AlksScenario::kCutIn;
        return false;
      }
    }
    return true;
  }

  bool driver_safe(AlksObject& info) {
    const AlksSeen& o = seen(*info.entity);
    // Lane offset of the box centre (esmini rotates the centre by the world heading).
    const double centre_offset = o.offset + o.box.center_x * std::sin(o.h);
    update_trigger(info);
    if (o.pedestrian) {
      if (info.dv_t > kAlksSmall) {
        info.action = AlksScenario::kCutIn;  // walking toward the ego's path
        return false;
      }
    } else if (info.d_lane == 0) {
      if (std::abs(centre_offset) > kAlksWandering && info.dv_t < -kAlksSmall) {
        info.action = AlksScenario::kCutOut;
      } else if (-alks_sign(o.road.lane) * o.acc_s < kAlksLeaderDeceleration + kAlksSmall) {
        info.action = AlksScenario::kDeceleration;
      }
      return false;
    } else {
      if (trigger_fired()) {
        info.action = AlksScenario::kCutIn;
        return false;
      }
      if (info.action == AlksScenario::kCutIn) info.action = AlksScenario::kNone;
    }
    return true;
  }

  // The lateral trigger follows the last object moving toward the ego; any object that does not
  // (or none) disarms it.
  void update_trigger(const AlksObject& info) {
    AlksLateralTrigger& trigger = m_.trigger;
    if (!info.entity || info.dv_t < kAlksSmall) {
      if (trigger.active) {
        trigger.active = false;
        trigger.entity.reset();
        trigger.t0 = 0.0;
      }
      return;
    }
    if (info.entity == trigger.entity) return;
    const AlksSeen& o = seen(*info.entity);
    trigger.entity = info.entity;
    trigger.active = true;
    trigger.t0 = o.road.t;
    if (!trigger.wandering) return;
    // 0.375 m from the lane centre toward the ego: from where the object is now, on either side
    // of its lane centre (a motorbike moves the full 0.375 m from wherever it is).
    trigger.threshold = kAlksWandering;
    const double ego_t = ego().road.t;
    if ((o.road.t > ego_t && o.offset > 0.0) || (o.road.t < ego_t && o.offset < 0.0)) {
      trigger.threshold += std::abs(o.offset);
    } else if (!o.motorbike) {
      trigger.threshold = std::max(0.0, trigger.threshold - std::abs(o.offset));
    }
  }

  bool trigger_fired() const {
    const AlksLateralTrigger& trigger = m_.trigger;
    return trigger.active && trigger.entity &&
           std::abs(seen(*trigger.entity).road.t - trigger.t0) > trigger.threshold;
  }

  void reset_scenario() {
    m_.phase = AlksPhase::kInactive;
    m_.scenario = AlksScenario::kNone;
  }

  AlksMode sight() const {
    return m_.focus.entity ? AlksMode::kTargetInSight : AlksMode::kNoTarget;
  }

  double cruise() {
    if (m_.settings.cruise) {
      if (!m_.focus.entity) {
        m_.mode = AlksMode::kNoTarget;
        m_.acc = alks_near(v_, m_.set_speed) ? 0.0 : (v_ > m_.set_speed ? -2.0 : 2.0);
        return std::clamp(v_ + m_.acc * dt_, 0.0, m_.set_speed);
      }
      if (m_.focus.dist_long > 0.0 && m_.focus.ttc > m_.focus.dv_s / 12.0 + 0.35) {
        // Car following: equal speeds at the model's minimum distance.
        m_.mode = AlksMode::kTargetInSight;
        m_.acc =
            alks_near(v_, 0.0)
                ? 0.0
                : std::clamp(2.0 * -m_.focus.dv_s + (m_.focus.dist_long - min_dist()), -4.0, 3.0);
        return std::clamp(v_ + m_.acc * dt_, 0.0, m_.set_speed);
      }
    }
    m_.acc = 0.0;
    return v_;
  }

  bool regulation_critical() {
    if (!m_.focus.entity) {
      m_.mode = AlksMode::kNoTarget;
      return false;
    }
    if (m_.mode == AlksMode::kCritical && m_.settings.full_stop) return true;
    if (m_.focus.dv_s > 0.0 && m_.focus.dist_long > 0.0 &&
        m_.focus.ttc <
            m_.focus.dv_s / (2.0 * kAlksRegulationMaxDec) + kAlksRegulationReaction + 0.1) {
      m_.mode = AlksMode::kCritical;
      return true;
    }
    m_.mode = AlksMode::kTargetInSight;
    return false;
  }

  double regulation_react() {
    m_.acc = -kAlksRegulationMaxDec;
    return std::max(0.0, v_ + m_.acc * dt_);
  }

  bool driver_critical() {
    if (m_.phase == AlksPhase::kInactive || m_.phase == AlksPhase::kPerceive) {
      if (perceived()) {
        m_.phase = AlksPhase::kReact;
        m_.timer = kAlksDriverReaction;
      }
    } else if (m_.phase == AlksPhase::kReact) {
      m_.timer -= dt_;
    }
    if (m_.mode == AlksMode::kNoTarget && m_.focus.entity) m_.mode = AlksMode::kTargetInSight;
    if (m_.settings.full_stop && m_.mode == AlksMode::kCritical) {
      if (v_ < kAlksSmall) {  // out of the critical mode only at standstill
        reset_scenario();
        m_.mode = sight();
      }
    } else if (!m_.focus.entity) {
      reset_scenario();
      m_.mode = AlksMode::kNoTarget;
    } else if ((v_ > kAlksSmall && m_.focus.dist_long > 0.0) || m_.settings.full_stop) {
      critical_condition();
    }
    if (!m_.aeb && m_.focus.entity && m_.focus.ttc < m_.settings.aeb_ttc &&
        view_.covers_front(*m_.focus.entity, m_.settings.overlap_tolerance)) {
      m_.aeb = true;
    }
    return m_.mode == AlksMode::kCritical || m_.aeb;
  }

  // Whether the scenario has been perceived this step (the reaction time starts).
  bool perceived() {
    switch (m_.scenario) {
      case AlksScenario::kCutIn:
        return cut_in_perceived();
      case AlksScenario::kCutOut:
        return timed_perception(m_.focus.dv_s > kAlksSmall);
      case AlksScenario::kDeceleration:
        return timed_perception(m_.focus.entity &&
                                seen(*m_.focus.entity).acc_s < kAlksLeaderDeceleration);
      case AlksScenario::kNone:
        break;
    }
    return false;
  }

  bool timed_perception(bool starts) {
    if (m_.phase == AlksPhase::kInactive) {
      if (starts) {
        m_.phase = AlksPhase::kPerceive;
        m_.timer = kAlksPerceptionTime;
      }
    } else if (m_.phase == AlksPhase::kPerceive) {
      m_.timer -= dt_;
      return m_.timer < kAlksSmall;
    }
    return false;
  }

  bool cut_in_perceived() {
    const bool pedestrian = m_.focus.entity && seen(*m_.focus.entity).pedestrian;
    if (m_.phase == AlksPhase::kInactive) {
      if (pedestrian && m_.focus.dv_s > kAlksSmall) {
        m_.timer = m_.settings.pedestrian_risk_time;
        m_.phase = AlksPhase::kPerceive;
      } else if (trigger_fired() && m_.focus.entity) {
        m_.perception_t = seen(*m_.focus.entity).road.t;
        if (m_.settings.perceive_by_time) m_.timer = kAlksPerceptionTime;
        m_.phase = AlksPhase::kPerceive;
      }
      return false;
    }
    if (m_.phase != AlksPhase::kPerceive) return false;
    if (pedestrian) {
      if (m_.focus.dv_s > kAlksSmall) {
        m_.timer -= dt_;
        if (m_.timer < kAlksSmall) m_.phase = AlksPhase::kReact;
      }
    } else if (m_.settings.perceive_by_time) {
      m_.timer -= dt_;
      if (m_.timer < kAlksSmall) m_.phase = AlksPhase::kReact;
    } else if (m_.focus.entity) {
      // Dist: perceived once the object has moved kAlksPerceptionDistance more toward the ego.
      const double t = seen(*m_.focus.entity).road.t;
      const double ego_t = ego().road.t;
      if ((t > ego_t && t < m_.perception_t - kAlksPerceptionDistance) ||
          (t < ego_t && t > m_.perception_t + kAlksPerceptionDistance)) {
        m_.phase = AlksPhase::kReact;
      }
    }
    if (m_.phase == AlksPhase::kReact) {
      m_.timer = kAlksDriverReaction;
      return true;
    }
    return false;
  }

  // After the reaction time: critical when the TTC (cut-in) or headway (cut-out, deceleration)
  // is under 2 s; else the scenario ends. A critical situation lasts until the minimum distance.
  void critical_condition() {
    if (m_.scenario == AlksScenario::kNone) return;
    const bool close = m_.scenario == AlksScenario::kCutIn ? m_.focus.ttc < kAlksCriticalTtc
                                                           : m_.focus.thw < kAlksCriticalThw;
    if (m_.settings.always_trig || close) {
      if (m_.phase == AlksPhase::kReact && m_.timer < kAlksSmall) m_.mode = AlksMode::kCritical;
      return;
    }
    if (m_.phase == AlksPhase::kReact) {
      reset_scenario();  // perceived, but not critical
    } else if (m_.mode == AlksMode::kCritical && m_.focus.dist_long > min_dist()) {
      m_.mode = sight();
      if (m_.focus.dv_s < kAlksSmall) reset_scenario();  // the gap grows
    }
  }

  double driver_react() {
    if (m_.phase == AlksPhase::kReact && m_.timer < kAlksSmall) m_.phase = AlksPhase::kBrakeRef;
    if ((m_.phase == AlksPhase::kBrakeRef || m_.aeb) && v_ < kAlksSmall) {
      m_.phase = AlksPhase::kInactive;
      m_.aeb = false;
      m_.timer = 0.0;
    }
    if (m_.phase == AlksPhase::kReact) {
      m_.acc = std::min(-kAlksReleaseDeceleration, m_.acc);  // keep braking, or lift off the gas
    } else if (m_.phase == AlksPhase::kBrakeRef) {
      m_.acc -= dt_ * kAlksDriverBrake * kAlksG / kAlksBrakeBuildUp;
    }
    if (m_.aeb) m_.acc -= dt_ * kAlksAebBrake * kAlksG / kAlksBrakeBuildUp;
    m_.acc = std::max(m_.acc, -(m_.aeb ? kAlksAebBrake : kAlksDriverBrake) * kAlksG);
    return std::max(0.0, v_ + m_.acc * dt_);
  }

  AlksR157& m_;
  const AlksView& view_;
  double v_;  ///< m/s, the ego's speed when the step began
  double dt_;
};

}  // namespace

double alks_step(AlksR157& alks, const AlksView& view) { return AlksStepper(alks, view).step(); }

}  // namespace corsa::engine::detail
