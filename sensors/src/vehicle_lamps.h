#pragma once

// Which lamps of a vehicle are lit in a frame (private): the snapshot's light state, and for the
// lights nobody set the renderer's own choices. The camera's shading and its labels both read it,
// so that a label says what the image shows.

#include <cstdint>

#include "corsa/engine/world_snapshot.h"

namespace corsa::sensors::detail {

/// A vehicle's lights as a frame draws them.
struct VehicleLampState {
  uint32_t lit = 0;       ///< VehicleLight bits emitting in this frame
  uint32_t flashing = 0;  ///< VehicleLight bits in a flashing mode (lit or not)
  uint32_t roles = 0;     ///< LightRole bits of the lamps lit (kAlways included)
};

/// The lights of `e` in a frame that is `dark` (Lighting::headlights): what the scenario set,
/// and otherwise headlights and tail lamps when it is dark, brake lamps and indicators as the
/// engine reports them, reversing lamps when the vehicle backs up. The daytime running lights
/// light the headlamps, the warning lights both indicators; fog lamps, the licence plate light
/// and special-purpose lights have no lamp of their own.
VehicleLampState vehicle_lamp_state(const engine::EntitySnapshot& e, bool dark);

}  // namespace corsa::sensors::detail
