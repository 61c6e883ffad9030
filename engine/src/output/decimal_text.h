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

// "00" to "99": two digits per division instead of one.
inline constexpr char kDigitPairs[] =
    "00010203040506070809101112131415161718192021222324252627282930313233343536373839"
    "40414243444546474849505152535455565758596061626364656667686970717273747576777879"
    "8081828384858687888990919293949596979899";

/// Writes the decimal digits of `value` so that they end just before `end`; returns their start.
inline char* digits_before(char* end, uint64_t value) {
  while (value >= 100) {
    const uint64_t pair = value % 100;
    value /= 100;
    end -= 2;
    end[0] = kDigitPairs[2 * pair];
    end[1] = kDigitPairs[2 * pair + 1];
  }
  if (value >= 10) {
    end -= 2;
    end[0] = kDigitPairs[2 * value];
    end[1] = kDigitPairs[2 * value + 1];
  } else {
    *--end = static_cast<char>('0' + value);
  }
  return end;
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
  uint64_t fraction = magnitude % unit;
  // Built backwards from the last digit: fraction (zero-padded, trailing zeros dropped: they
  // say nothing), point, integer part.
  char text[kDecimalTextMax];
  char* const end = text + kDecimalTextMax;
  char* first = end;
  if (fraction != 0) {
    int places = decimals;
    while (fraction % 10 == 0) {
      fraction /= 10;
      --places;
    }
    first = digits_before(first, fraction);
    while (end - first < places) *--first = '0';
    *--first = '.';
  }
  first = digits_before(first, magnitude / unit);
  for (char* c = first; c != end; ++c) *out++ = *c;
  return out;
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
