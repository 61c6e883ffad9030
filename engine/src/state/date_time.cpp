#include "state/date_time.h"

#include <cmath>

namespace corsa::engine::detail {
namespace {

bool read_int(std::string_view text, size_t at, size_t count, int& out) {
  if (at + count > text.size()) {
    return false;
  }
  int value = 0;
  for (size_t i = at; i < at + count; ++i) {
    if (text[i] < '0' || text[i] > '9') {
      return false;
    }
    value = value * 10 + (text[i] - '0');
  }
  out = value;
  return true;
}

// Days since 1970-01-01 of a civil date (H. Hinnant's days_from_civil algorithm).
long long days_from_civil(int y, int m, int d) {
  y -= m <= 2 ? 1 : 0;
  const long long era = (y >= 0 ? y : y - 399) / 400;
  const long long yoe = y - era * 400;
  const long long doy = (153 * (m + (m > 2 ? -3 : 9)) + 2) / 5 + d - 1;
  const long long doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
  return era * 146097 + doe - 719468;
}

void civil_from_days(long long z, int& y, int& m, int& d) {
  z += 719468;
  const long long era = (z >= 0 ? z : z - 146096) / 146097;
  const long long doe = z - era * 146097;
  const long long yoe = (doe - doe / 1460 + doe / 36524 - doe / 146096) / 365;
  const long long doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
  const long long mp = (5 * doy + 2) / 153;
  d = static_cast<int>(doy - (153 * mp + 2) / 5 + 1);
  m = static_cast<int>(mp < 10 ? mp + 3 : mp - 9);
  y = static_cast<int>(yoe + era * 400 + (m <= 2 ? 1 : 0));
}

}  // namespace

std::optional<DateTime> parse_date_time(std::string_view text) {
  DateTime out;
  int hour = 0, minute = 0, second = 0;
  if (!read_int(text, 0, 4, out.year) || text.size() < 19 || text[4] != '-' ||
      !read_int(text, 5, 2, out.month) || text[7] != '-' || !read_int(text, 8, 2, out.day) ||
      text[10] != 'T' || !read_int(text, 11, 2, hour) || text[13] != ':' ||
      !read_int(text, 14, 2, minute) || text[16] != ':' || !read_int(text, 17, 2, second)) {
    return std::nullopt;
  }
  if (out.month < 1 || out.month > 12 || out.day < 1 || out.day > 31 || hour > 24 || minute > 59 ||
      second > 60) {
    return std::nullopt;
  }
  double fraction = 0.0;
  size_t i = 19;
  if (i < text.size() && text[i] == '.') {
    double scale = 0.1;
    for (++i; i < text.size() && text[i] >= '0' && text[i] <= '9'; ++i) {
      fraction += (text[i] - '0') * scale;
      scale *= 0.1;
    }
  }
  out.seconds_of_day = hour * 3600.0 + minute * 60.0 + second + fraction;
  if (i < text.size()) {
    if (text[i] == 'Z' && i + 1 == text.size()) {
      out.utc_offset_hours = 0.0;
      return out;
    }
    int zh = 0, zm = 0;
    if ((text[i] != '+' && text[i] != '-') || i + 6 != text.size() ||
        !read_int(text, i + 1, 2, zh) || text[i + 3] != ':' || !read_int(text, i + 4, 2, zm)) {
      return std::nullopt;
    }
    out.utc_offset_hours = (text[i] == '-' ? -1.0 : 1.0) * (zh + zm / 60.0);
  }
  return out;
}

double epoch_seconds(const DateTime& value) {
  return static_cast<double>(days_from_civil(value.year, value.month, value.day)) * 86400.0 +
         value.seconds_of_day - value.utc_offset_hours.value_or(0.0) * 3600.0;
}

DateTime advance(const DateTime& value, double seconds) {
  DateTime out = value;
  const double total = value.seconds_of_day + seconds;
  const double days = std::floor(total / 86400.0);
  out.seconds_of_day = total - days * 86400.0;
  civil_from_days(
      days_from_civil(value.year, value.month, value.day) + static_cast<long long>(days), out.year,
      out.month, out.day);
  return out;
}

}  // namespace corsa::engine::detail
