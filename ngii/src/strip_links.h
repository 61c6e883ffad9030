#pragma once

// Lane links of the centre strips (centre_gaps.h). A strip is lane +1 of a one-section road;
// where two roads with strips meet end to start (road to road, or through a junction's
// connection), the strips continue into each other, so a lane-link check sees no dead end in the
// middle of a double centre line. Links follow OpenDRIVE 1.8 §9.6 (lane predecessor/successor
// between roads) and §10.4 (a connection's laneLink); a strip leaving a default junction gets
// a connection of its own from the outgoing road (contactPoint end on the connecting road), as
// left lanes of two-way roads do.

#include <cstddef>

#include "corsa/xodr/model.h"

namespace corsa::ngii::detail {

/// Largest distance (m) between the inner edges (the centre lane) of two strip ends that are
/// joined; farther ends stay unjoined (their roads meet elsewhere than at the strip).
constexpr double kStripJoinReach = 0.5;

/// Joins the centre-strip lanes of roads linked to each other; returns the number of joins made
/// (each pair of strip ends counted once).
size_t link_centre_strips(xodr::MapData& map);

}  // namespace corsa::ngii::detail
