#pragma once

// esmini's NaturalDriver controller (its ControllerNaturalDriver), emulated: a driver model on the
// longitudinal domain that keeps its speed by the Intelligent Driver Model (Treiber, Hennecke,
// Helbing 2000) and changes lanes by itself by a MOBIL-style rule (Kesting, Treiber, Helbing
// 2007), each change a LaneChangeAction to the neighbouring lane (sinusoidal, over
// `laneChangeDuration` s) that the lateral domain then performs. docs/openscenario.md, "esmini's
// NaturalDriver", says what it does and where it reads as esmini does rather than as written.
//
// Its entity moves after every other entity of the step (EntityMover::move), sees them where
// they have moved to and itself where it was, as esmini steps its controllers after the default
// controller has moved everyone else. Several NaturalDriver entities move one after the other in
// entity order, each seeing those before it moved: the same whatever the number of threads.

#include <cstdint>
#include <memory>

namespace corsa::xosc {
struct ObjectController;
}  // namespace corsa::xosc

namespace corsa::engine::detail {

struct SimState;
struct MotionContext;
struct NaturalDriverState;

/// Whether this ObjectController asks for esmini's NaturalDriver (its `esminiController`
/// property, else the Controller's name).
bool is_natural_driver(const xosc::ObjectController& oc);

/// The driver's parameters from the Controller's Properties (esmini's names: desiredSpeed,
/// desiredDistance, maxAcc, maxDec, thw, lookAheadDistance, laneChangeDuration, laneChangeDelay,
/// maxImposedBraking, politeness, laneChangeAccGain, route), esmini's defaults for those absent.
/// For a controller read in place of a catalog entry the catalog lacks, the reference's
/// ParameterAssignments stand for the properties of the same name with a lower-case first letter
/// (warned once, located at the reference).
std::shared_ptr<NaturalDriverState> make_natural_driver(SimState& state,
                                                        const xosc::ObjectController& oc);

/// Moves every present entity whose NaturalDriver is active this step, in entity order, after
/// the others have moved; an entity whose driver is not active is left alone (its driver starts
/// afresh when activated again).
void step_natural_drivers(SimState& state, const MotionContext& motion);

}  // namespace corsa::engine::detail
