#pragma once

// esmini's ALKS_R157SM_Controller: driver models for UN R157 (ALKS) evaluation that esmini's
// example scenarios assign to their ego. It watches the vehicle ahead and the vehicles in the
// neighbouring lanes, recognises a cut-in, a cut-out or a braking leader, and when that is
// critical brakes; otherwise it keeps the speed (or, with `cruise`, drives a simple car
// following at the speed it had when activated). Of esmini's four models two are emulated:
//   - Regulation (UN R157 5.2.5): a neighbour whose front wheel is 0.3 m inside the ego's lane
//     cuts in; critical when TTC < dv / (2 x 6 m/s^2) + 0.35 s + 0.1 s; then -6 m/s^2 (until
//     standstill with fullStop).
//   - ReferenceDriver (UN R157 Annex 3, the "competent and careful driver"): a cut-in is
//     perceived once the neighbour has moved 0.375 m (lane wandering) toward the ego, or
//     `lateralTrigDistance`; after 0.4 s (perception time, or 0.72 m more with
//     cutInPerceptionDelayMode=Dist) it is critical when TTC < 2 s (cut-out, deceleration:
//     headway < 2 s); the foot leaves the accelerator (-0.4 m/s^2) for the 0.75 s reaction
//     time, then the brake builds up to 0.774 g in 0.6 s; an AEB joins (0.85 g in 0.6 s) when
//     TTC < aebTTC and the object covers the ego's front.
// The controller moves the entity along its lane at the model's speed (esmini's override mode;
// its additive mode is read the same way), after every other entity has moved in the step (as
// esmini steps its controllers after the default controller), so that it sees them where they
// are now; ALKS entities are stepped one after the other in entity order.
// Limitations: objects are seen only on the ego's own road (esmini follows the road links).

#include <memory>

#include "motion/controller.h"

namespace corsa::xosc {
struct Controller;
struct ObjectController;
}  // namespace corsa::xosc

namespace corsa::engine::detail {

struct SimState;
struct AlksR157;

/// Whether `controller` is esmini's ALKS_R157SM_Controller (Property esminiController, else
/// the Controller's name).
bool is_alks_r157(const xosc::Controller& controller);

/// The controller's settings from its Properties (model, cruise, fullStop, ...), warned about
/// where they are out of range (located). Nothing, with a warning, for a model not emulated
/// (RSS, FSM): the caller substitutes.
std::shared_ptr<AlksR157> make_alks_r157(SimState& state, const xosc::ObjectController& oc);

/// The controller was (re)activated on the longitudinal domain: its set speed becomes the
/// entity's speed at its next step (esmini's Activate).
void activate_alks_r157(AlksR157& alks);

/// One step of every entity driven by the controller, in entity order, after the other moves.
void step_alks_r157_entities(SimState& state, const MotionContext& motion);

}  // namespace corsa::engine::detail
