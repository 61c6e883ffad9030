#pragma once

// Fixed-decimal number text for the trajectory CSV: a value rounded to a given number of decimal
// places, printed from the rounded integer, with trailing zeros (and a bare point) left out:
// 50 -> "50", -5.625 -> "-5.625", 32.19999999999999 -> "32.2" at 6 decimals. Several times
// cheaper than the shortest round-trip text (std::to_chars(double)), which was a quarter of a
// sweep's instructions, and deterministic: IEEE multiplication and rounding give the same digits
// on every platform.

#include <charconv>
#include <cmath>
#include <cstdint>

namespace corsa::engine::detail {

/// Space a call of write_decimal may use: the shortest round-trip text of any double (at most
/// 24 characters) or a sign, 16 integer digits, a point and 9 decimals.
inline constexpr int kDecimalTextMax = 32;

/// The most decimals write_decimal supports.
inline constexpr int kMaxDecimals = 9;

namespace decimal_text {

inline constexpr double kScale[kMaxDecimals + 1] = {1e0, 1e1, 1e2, 1e3, 1e4,
                                                    1e5, 1e6, 1e7, 1e8, 1e9};
inline constexpr uint64_t kIntScale[kMaxDecimals + 1] = {
    1, 10, 100, 1'000, 10'000, 100'000, 1'000'000, 10'000'000, 100'000'000, 1'000'000'000};
// Scaled magnitudes below 2^53 are integers exactly representable, so rounding is exact; larger
// ones (|value| >= 9e9 m at 6 decimals: no real map) fall back to the shortest text.
inline constexpr double kExactLimit = 9.0e15;

inline char* write_digits(char* out, uint64_t value) {
  char reversed[20];
  int n = 0;
  do {
    reversed[n++] = static_cast<char>('0' + value % 10);
    value /= 10;
  } while (value != 0);
  while (n > 0) *out++ = reversed[--n];
  return out;
}

/// `scaled` rounded to the nearest integer, halves away from zero (std::llround, inline: the
/// libm call was a tenth of the text's cost). |scaled| < kExactLimit, so the truncation is exact
/// and so is the remainder (scaled and its truncation share their binade, or the truncation is
/// 0).
inline int64_t round_half_away(double scaled) {
  const auto whole = static_cast<int64_t>(scaled);
  const double rest = scaled - static_cast<double>(whole);
  return rest >= 0.5 ? whole + 1 : rest <= -0.5 ? whole - 1 : whole;
}

}  // namespace decimal_text

/// Writes `value` rounded to `decimals` places (0..kMaxDecimals; halves away from zero) at
/// `out`, which has room for kDecimalTextMax characters, and returns the end. A value that
/// rounds to zero is "0" (never "-0"). NaN, infinities and magnitudes too large to scale exactly
/// are written as their shortest round-trip text instead.
inline char* write_decimal(char* out, double value, int decimals) {
  using namespace decimal_text;
  const double scaled = value * kScale[decimals];
  if (!(std::fabs(scaled) < kExactLimit)) {
    return std::to_chars(out, out + kDecimalTextMax, value + 0.0).ptr;  // + 0.0: no "-0"
  }
  const int64_t rounded = round_half_away(scaled);
  if (rounded == 0) {
    *out++ = '0';
    return out;
  }
  if (rounded < 0) {
    *out++ = '-';
  }
  const uint64_t magnitude = static_cast<uint64_t>(rounded < 0 ? -rounded : rounded);
  const uint64_t unit = kIntScale[decimals];
  out = write_digits(out, magnitude / unit);
  uint64_t fraction = magnitude % unit;
  if (fraction == 0) {
    return out;
  }
  int places = decimals;
  while (fraction % 10 == 0) {  // trailing zeros say nothing
    fraction /= 10;
    --places;
  }
  *out++ = '.';
  for (int i = places - 1; i >= 0; --i) {
    out[i] = static_cast<char>('0' + fraction % 10);
    fraction /= 10;
  }
  return out + places;
}

/// Writes `value` as write_decimal(value, kMaxDecimals) when that text reads back to exactly
/// `value` (times on the step grid: "0.49", "3.01"), else as the shortest round-trip text
/// (std::to_chars), for a fraction of its cost. Below 2^23 the digits are the shortest
/// round-trip ones too: an ulp there is under 1e-9, so at most one decimal of 9 places reads back
/// as `value` (to_chars would only write small values such as 1e-04 in exponent form). The check:
/// the decimal's integer divided by 1e9 in IEEE arithmetic is the correctly rounded value of the
/// decimal, which is what parsing its text gives.
inline char* write_exact(char* out, double value) {
  using namespace decimal_text;
  const double scaled = value * kScale[kMaxDecimals];
  if (std::fabs(scaled) < kExactLimit) {
    const int64_t rounded = round_half_away(scaled);
    if (static_cast<double>(rounded) / kScale[kMaxDecimals] == value) {
      return write_decimal(out, value, kMaxDecimals);
    }
  }
  return std::to_chars(out, out + kDecimalTextMax, value + 0.0).ptr;
}

}  // namespace corsa::engine::detail
