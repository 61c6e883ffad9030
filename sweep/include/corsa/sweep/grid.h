#pragma once

// Quick grids from the command line: `--param NAME=SPEC`, one axis per option.

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace corsa::sweep {

/// One axis of a grid: a parameter and the values it takes, in order.
struct GridAxis {
  std::string name;
  std::vector<std::string>
      values;        ///< as OpenSCENARIO text, e.g. "20", "-1", "2024-03-21T12:00:00"
  std::string spec;  ///< the option text as given, e.g. "speed=20:40:5"
};

/// Parses `NAME=SPEC` where SPEC is
///   - `LOW:HIGH:STEP`: LOW, LOW + STEP, ... up to HIGH inclusive (within 1e-9 of a step), the
///     same rule and number format as an OpenSCENARIO DistributionRange (§10.3.2);
///   - `A,B,C`: a list of values taken as written;
///   - a single value.
/// A value with colons is a range only when it has exactly three numeric parts, so a dateTime
/// such as 2024-03-21T12:00:00 stays one value. Throws InputError located at the option
/// ("--param speed=40:20:5: error: ...") for an empty name or value, an empty range (HIGH below
/// LOW), a step that is not positive, or more than `max_values` values (10 million; what the
/// axes before it left of 10 million for a later axis, so that the values of all axes together
/// stay bounded: four ranges of 9 million values took 20 s and 1.1 GB).
GridAxis parse_grid_axis(std::string_view text, size_t max_values = 10'000'000);

}  // namespace corsa::sweep
