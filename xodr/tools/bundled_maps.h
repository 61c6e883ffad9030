#pragma once

// The maps Corsa ships in scenarios/maps/ (we cannot ship ../shared), built in code and written
// with the OpenDRIVE writer. tests/xodr checks that the committed files are exactly what these
// functions produce and that they load without warnings.

#include "corsa/xodr/model.h"

namespace corsa::xodr::bundled {

/// A straight, flat 2 km motorway: three 3.75 m driving lanes and a 2.5 m shoulder each way,
/// marked (double centre line, broken lane lines, solid edge lines), 130 km/h.
MapData motorway();

/// An urban four-way intersection: four 100 m arms (one 3.5 m lane each way, 2 m raised
/// sidewalks), a default junction with twelve connecting roads (straight, left and right turns
/// from every arm; the right turns carry the corner sidewalks), 50 km/h.
MapData intersection();

}  // namespace corsa::xodr::bundled
