#pragma once

// Where a Stochastic distribution's randomSeed stops being a seed.

namespace corsa::xosc {

/// A randomSeed (a double in the schema) is taken as a seed when its magnitude is below this,
/// where it fits a 64-bit integer; beyond it, or not finite, the run's seed is used instead,
/// with a warning at its line.
inline constexpr double kLargestRandomSeed = 9.2e18;

}  // namespace corsa::xosc
