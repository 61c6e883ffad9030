#pragma once

// The strip between the two directions of a road where a B2 centre mark pairs them: a centre mark
// (yellow, or Kind 501) naming a link on its right, with another centre mark naming a link of
// the opposite direction at most 1.6 m to its left (K-City's double yellow lines digitised as two
// marks), or one mark naming links of both directions. Across each such pair, every metre along it,
// the line from 0.3 m inside one mark to 0.3 m inside the other is sampled every 2 cm and each
// sample looked up in the map (Map::locate, any lane type): the longest run of samples on no
// lane is the gap between the two roads there. Computed from the B2 layer and the map only.

#include <cstddef>
#include <string>

#include "corsa/ngii/layers.h"
#include "corsa/xodr/map.h"

namespace corsa::test {

struct CentreGapFigures {
  size_t stations = 0;  ///< stations across paired centre marks
  size_t over = 0;      ///< of those, with a gap over 5 cm between the roads
  double max = 0.0;     ///< largest gap (m)
  std::string worst;    ///< the B2 mark id there
};

CentreGapFigures centre_gaps(const ngii::Layers& layers, const xodr::Map& map);

}  // namespace corsa::test
