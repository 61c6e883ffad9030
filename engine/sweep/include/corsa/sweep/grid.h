#pragma once

// Quick grids from the command line: `--param NAME=SPEC`, one axis per option.

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
/// LOW), a step that is not positive, or more than 10 million values.
GridAxis parse_grid_axis(std::string_view text);

}  // namespace corsa::sweep
