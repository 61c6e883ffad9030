#pragma once

// Articulated trailers (OpenSCENARIO 1.3 §6.2.4 Trailer, §7.4.8 TrailerAction): a trailer
// connected to a vehicle is not moved by a controller of its own; after every step its coupler is
// put on the tower's hitch and it turns about its reference point (its rear axle) the way a
// towed axle does: the rear axle moves straight toward the hitch (a tractrix), so the trailer
// cuts corners and swings back out on the straight. Chains (tractor, semi-trailer, trailer)
// follow link by link.

#include <cstdint>

namespace corsa::engine::detail {

struct SimState;

/// Hitch (tower) and coupler (trailer) points, metres ahead of each entity's reference point:
/// TrailerHitch / TrailerCoupler dx, else the rear / front of the bounding box.
double hitch_dx(const SimState& state, uint32_t tower);
double coupler_dx(const SimState& state, uint32_t trailer);

/// Connects `trailer` to `tower` (ConnectTrailerAction, a Vehicle's initial Trailer). With
/// `align`, the trailer is put behind the tower in line with it (its coupler on the hitch); else
/// it keeps its place and turns toward the hitch at the next step.
void connect_trailer(SimState& state, uint32_t tower, uint32_t trailer, bool align);
/// Disconnects the trailer of `tower`, if any (DisconnectTrailerAction): it stops where it is.
void disconnect_trailer(SimState& state, uint32_t tower);

/// Puts every connected trailer behind its tower after the towers moved over `dt` seconds.
void move_trailers(SimState& state, double dt);

}  // namespace corsa::engine::detail
