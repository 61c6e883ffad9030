#pragma once

// Street furniture generated from a seed (private): litter bins, bollards, fire hydrants,
// benches, bus shelters, bus-stop and street-name signs. Each is built in its own frame (x
// forward = the way it faces, z up, the foot at the origin, centred on its footprint) and placed
// by the world builder (world_furniture.cpp). Sizes are those of common European and Korean
// street furniture; classes follow CARLA's: the objects themselves `static`, sign posts `pole`,
// sign faces `traffic_sign`.

#include "corsa/core/random.h"
#include "mesh_builder.h"

namespace corsa::sensors::detail {

/// A litter bin about 0.95 m high and 0.45 m across: a metal body (dark green, grey or black)
/// with a rim and a dark opening, on a short foot.
ArticulatedMesh make_litter_bin(RandomStream& rng);
/// A bollard 0.9-1.0 m high and 0.2 m across with a rounded cap and a reflective band.
ArticulatedMesh make_bollard(RandomStream& rng);
/// A pillar fire hydrant about 0.75 m high (red or yellow) with two side outlets facing ±y and a
/// pumper outlet facing +x.
ArticulatedMesh make_fire_hydrant(RandomStream& rng);
/// A park bench 1.8 m long along y, seat facing +x: wooden slats on two cast frames.
ArticulatedMesh make_bench(RandomStream& rng);
/// A bus shelter `length` metres long along y and 1.4 m deep, open towards +x: posts, a roof,
/// glass back and side panels, a seat and an advertising panel at one end.
ArticulatedMesh make_bus_shelter(RandomStream& rng, double length);
/// A bus-stop sign on a post (class pole): a round face 0.45 m across facing +x at 2.2 m.
ArticulatedMesh make_bus_stop_sign();
/// A street-name sign: a post (class pole) with two name blades at 2.5 m, one along x and one
/// along y (the two streets of a corner; the second reaches over the walking path, above head
/// height, never over the road), blue or green with a white border.
ArticulatedMesh make_street_name_sign(RandomStream& rng);

}  // namespace corsa::sensors::detail
