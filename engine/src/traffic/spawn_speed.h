#pragma once

// The speed a generated object starts at (OpenSCENARIO 1.3 §7.5.6). TrafficSourceAction has an
// optional `speed`, TrafficSwarmAction an InitialSpeedRange (or the deprecated `velocity`),
// TrafficAreaAction none; a TrafficDistributionEntry's Properties are "tool specific properties
// for spawning of the entity group (e.g. ... overwrite speed range for slower vehicles/trucks)".
// In this order:
//   1. the entry's property `corsa:speed`: metres per second, "V" or a range "LO..HI" drawn
//      uniformly for each object;
//   2. the speed the action gives (`given`);
//   3. the object's controller's cruise speed: a `setSpeed` property of its ObjectController,
//      whatever the controller's type and mode (esmini reads it only for its ACCController in
//      mode "override"; here any controller of a traffic template may give its objects'
//      starting speed); a value that is no non-negative number warns at the property and is
//      passed over;
//   4. walkers: 1.3 m/s;
//   5. the speed limit where it spawns: the OpenDRIVE lane's <speed> record, else the road's
//      <type> speed;
//   6. 13.9 m/s (50 km/h).

#include <cstddef>
#include <cstdint>
#include <optional>

namespace corsa {
class RandomStream;
}

namespace corsa::engine::detail {

struct SimState;
struct ResolvedPosition;
class TrafficMix;

/// The starting speed (m/s) of `mix` prototype `kind` spawned at `at`; `given` is the action's
/// own speed, if any. Throws InputError at a `corsa:speed` property that is not a speed.
double spawn_speed(const SimState& state, RandomStream& random, const TrafficMix& mix, size_t kind,
                   const ResolvedPosition& at, std::optional<double> given);

/// The speed limit (m/s) at road `road`, `s`, lane `lane` of the map: the lane's <speed>
/// record in force at s, else the road's <type> speed there; nothing when neither gives one.
std::optional<double> speed_limit(const SimState& state, uint32_t road, double s, int lane);

}  // namespace corsa::engine::detail
