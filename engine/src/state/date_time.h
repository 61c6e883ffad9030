#pragma once

// xsd:dateTime values as OpenSCENARIO uses them (TimeOfDay, TimeOfDayCondition):
// YYYY-MM-DDThh:mm:ss[.fraction][Z|(+|-)hh:mm].

#include <optional>
#include <string_view>

namespace corsa::engine::detail {

struct DateTime {
  int year = 1970;
  int month = 1;
  int day = 1;
  double seconds_of_day = 0.0;  ///< local time, s since midnight
  /// Local minus UTC, hours ("Z" is 0); nothing when the text gives no zone (xsd:dateTime's
  /// "untimezoned" value), which Corsa reads as local solar time at the map's place.
  std::optional<double> utc_offset_hours;
};

std::optional<DateTime> parse_date_time(std::string_view text);

/// Seconds since 1970-01-01T00:00:00 UTC (proleptic Gregorian calendar); a time without a zone
/// counts as UTC here (two such times compare as they read).
double epoch_seconds(const DateTime& value);

/// The local date and time `seconds` later (rolls over midnight and month ends).
DateTime advance(const DateTime& value, double seconds);

}  // namespace corsa::engine::detail
