#pragma once

// Angles in the horizontal plane (rad, counter-clockwise from +x as in OpenDRIVE and
// OpenSCENARIO).

namespace corsa::engine::detail {

/// Wraps an angle (rad) into (-pi, pi].
double wrap_angle(double angle);

}  // namespace corsa::engine::detail
