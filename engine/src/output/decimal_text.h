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
#include <cstring>

#if defined(__x86_64__) && defined(__SSE2__)
#include <emmintrin.h>
#endif

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

// 10^0 .. 10^18: the integer part's digit count.
inline constexpr uint64_t kPowers[19] = {1ULL,
                                         10ULL,
                                         100ULL,
                                         1'000ULL,
                                         10'000ULL,
                                         100'000ULL,
                                         1'000'000ULL,
                                         10'000'000ULL,
                                         100'000'000ULL,
                                         1'000'000'000ULL,
                                         10'000'000'000ULL,
                                         100'000'000'000ULL,
                                         1'000'000'000'000ULL,
                                         10'000'000'000'000ULL,
                                         100'000'000'000'000ULL,
                                         1'000'000'000'000'000ULL,
                                         10'000'000'000'000'000ULL,
                                         100'000'000'000'000'000ULL,
                                         1'000'000'000'000'000'000ULL};

// "00" to "99": two digits per division instead of one.
inline constexpr char kDigitPairs[] =
    "00010203040506070809101112131415161718192021222324252627282930313233343536373839"
    "40414243444546474849505152535455565758596061626364656667686970717273747576777879"
    "8081828384858687888990919293949596979899";

/// Writes the two digits of `pair` (< 100) at `out`: one two-byte copy.
inline void put_pair(char* out, uint64_t pair) { std::memcpy(out, &kDigitPairs[2 * pair], 2); }

/// Writes the decimal digits of `value` so that they end just before `end`; returns their start.
inline char* digits_before(char* end, uint64_t value) {
  while (value >= 100) {
    const uint64_t pair = value % 100;
    value /= 100;
    end -= 2;
    put_pair(end, pair);
  }
  if (value >= 10) {
    end -= 2;
    put_pair(end, value);
  } else {
    *--end = static_cast<char>('0' + value);
  }
  return end;
}

/// `scaled` rounded to the nearest integer, halves away from zero (std::llround, inline: the
/// libm call was a tenth of the text's cost). |scaled| < kExactLimit, so the truncation is exact
/// and so is the remainder (scaled and its truncation share their binade, or the truncation is
/// 0). The two comparisons are added, not branched on: which way a moving value rounds follows
/// no pattern, and a mispredicted branch per number cost more than the arithmetic.
inline int64_t round_half_away(double scaled) {
  const auto whole = static_cast<int64_t>(scaled);
  const double rest = scaled - static_cast<double>(whole);
  return whole + static_cast<int64_t>(rest >= 0.5) - static_cast<int64_t>(rest <= -0.5);
}

/// The integers of kExactLimit units and beyond (in magnitude), which round_or_far gives for
/// every value that is not exact.
inline constexpr int64_t kFarUnits = 9'000'000'000'000'000;
static_assert(static_cast<double>(kFarUnits) == kExactLimit);

/// Whether round_or_far's `units` is a rounded value (|scaled| < kExactLimit).
inline bool near_units(int64_t units) {
  return static_cast<uint64_t>(units) + static_cast<uint64_t>(kFarUnits - 1) <
         static_cast<uint64_t>(2 * kFarUnits - 1);
}

/// round_half_away(scaled) when |scaled| < kExactLimit, else an integer of kFarUnits or more in
/// magnitude (near_units false: NaN, infinities, the far values): the range test and the
/// rounding in about half the instructions of the two apart, for the binary trajectory's coder.
/// The truncation of scaled + copysign(0.5 - 2^-54, scaled) is the rounding of halves away from
/// zero: below a half (at most 0.5 - ulp) the sum stays below the next integer, at a half or
/// above it reaches it, and from 2^52 on, where every double is an integer, the sum rounds back
/// to scaled. (0.5 itself would take 0.5 - ulp/2 up to 1.) tests/engine/trajectory_text_test.cpp
/// compares it with round_half_away across the range and at every half.
inline int64_t round_or_far(double scaled) {
#if defined(__x86_64__) && defined(__SSE2__)
  // cvttsd2si: NaN and magnitudes of 2^63 and more give INT64_MIN (no undefined conversion).
  return _mm_cvttsd_si64(_mm_set_sd(scaled + std::copysign(0x1.fffffffffffffp-2, scaled)));
#else
  return std::fabs(scaled) < kExactLimit ? round_half_away(scaled) : kFarUnits;
#endif
}

}  // namespace decimal_text

/// A number as the trajectory files hold it: its integer of `Decimals` decimals (rounded, halves
/// away from zero), or, when it cannot be scaled exactly (NaN, infinities, magnitudes of 9e15
/// units and more), the value itself. Written as text by write_scaled / write_fixed; the binary
/// trajectory (output/trajectory_binary.cpp) stores the same integers, so that its CSV export
/// gives the same bytes.
struct Scaled {
  bool exact = true;
  int64_t units = 0;  ///< value x 10^Decimals, rounded (when exact)
  double raw = 0.0;   ///< the value (when not exact)
};

template <int Decimals>
Scaled scale_decimal(double value) {
  static_assert(Decimals >= 0 && Decimals <= kMaxDecimals);
  using namespace decimal_text;
  const double scaled = value * kScale[Decimals];
  if (!(std::fabs(scaled) < kExactLimit)) {
    return Scaled{false, 0, value};
  }
  return Scaled{true, round_half_away(scaled), 0.0};
}

namespace decimal_text {

/// Writes the `Count` decimal digits of `value` (< 10^Count), leading zeros included, at `out`.
/// `value` becomes a binary fraction of its leading group (value / 10^(Count - lead), 57
/// fraction bits, rounded up): each next pair is the integer part of the rest times 100, a mask,
/// a multiplication and a shift instead of a division by 100 and a remainder per pair. Exact
/// while 10^(2 Count - lead) < 2^57 (the rounding error, under 10^Count / 2^57, stays below the
/// smallest distance 10^-(Count - lead) of a true fraction to the next integer): Count <= 9.
template <int Count>
inline void fixed_digits(char* out, uint64_t value) {
  static_assert(Count >= 1 && Count <= kMaxDecimals);
  constexpr int kLead = 2 - Count % 2;  // digits of the first group
  constexpr int kShift = 57;
  constexpr uint64_t kOne = uint64_t{1} << kShift;
  constexpr uint64_t kDivisor = kIntScale[Count - kLead];
  constexpr uint64_t kReciprocal = (kOne + kDivisor - 1) / kDivisor;
  uint64_t y = value * kReciprocal;  // < 100 * 2^57 < 2^64
  if constexpr (kLead == 1) {
    out[0] = static_cast<char>('0' + (y >> kShift));
  } else {
    put_pair(out, y >> kShift);
  }
  for (int k = kLead; k < Count; k += 2) {
    y = (y & (kOne - 1)) * 100;  // < 2^57 * 100 < 2^64
    put_pair(out + k, y >> kShift);
  }
}

/// Writes the digits of `value` at `out` and returns their end; values below 10^4 (most integer
/// parts of a trajectory: speeds, headings, lateral offsets, coordinates on a map of a few km)
/// without counting digits.
inline char* whole_digits(char* out, uint64_t value) {
  if (value < 10) {
    *out = static_cast<char>('0' + value);
    return out + 1;
  }
  if (value < 100) {
    put_pair(out, value);
    return out + 2;
  }
  if (value < 10'000) {
    const uint64_t high = value / 100;
    const bool four = high >= 10;
    if (four) {
      put_pair(out, high);
    } else {
      out[0] = static_cast<char>('0' + high);
    }
    put_pair(out + 1 + four, value - 100 * high);
    return out + 3 + four;
  }
  int digits = 5;
  while (digits < 19 && value >= kPowers[digits]) ++digits;
  digits_before(out + digits, value);
  return out + digits;
}

}  // namespace decimal_text

/// Writes a number of `Decimals` decimals given by its integer `units` (|units| < 9e15): "0" for
/// 0 (never "-0"), trailing zeros and a bare point left out. The decimals are written in full
/// (fixed width) and the trailing zeros then dropped from the text.
template <int Decimals>
char* write_units(char* out, int64_t units) {
  using namespace decimal_text;
  if (units == 0) {
    *out++ = '0';
    return out;
  }
  if (units < 0) {
    *out++ = '-';
  }
  const uint64_t magnitude = static_cast<uint64_t>(units < 0 ? -units : units);
  constexpr uint64_t kUnit = kIntScale[Decimals];
  out = whole_digits(out, magnitude / kUnit);
  if constexpr (Decimals > 0) {
    const uint64_t fraction = magnitude % kUnit;
    if (fraction == 0) {
      return out;
    }
    *out = '.';
    fixed_digits<Decimals>(out + 1, fraction);
    char* end = out + 1 + Decimals;
    while (end[-1] == '0') --end;  // trailing zeros say nothing; fraction > 0 keeps a digit
    return end;
  }
  return out;
}

/// Writes a Scaled number: its decimals, or the shortest round-trip text of the raw value.
template <int Decimals>
char* write_scaled(char* out, const Scaled& number) {
  if (!number.exact) {
    return std::to_chars(out, out + kDecimalTextMax, number.raw + 0.0).ptr;  // + 0.0: no "-0"
  }
  return write_units<Decimals>(out, number.units);
}

/// Writes `value` rounded to `Decimals` places (0..kMaxDecimals; halves away from zero) at
/// `out`, which has room for kDecimalTextMax characters, and returns the end. A value that
/// rounds to zero is "0" (never "-0"). NaN, infinities and magnitudes too large to scale exactly
/// are written as their shortest round-trip text instead. A template so that the divisions by
/// the power of ten are multiplications.
template <int Decimals>
char* write_fixed(char* out, double value) {
  return write_scaled<Decimals>(out, scale_decimal<Decimals>(value));
}

/// write_fixed with the number of decimals chosen at run time.
inline char* write_decimal(char* out, double value, int decimals) {
  switch (decimals) {
    case 0:
      return write_fixed<0>(out, value);
    case 1:
      return write_fixed<1>(out, value);
    case 2:
      return write_fixed<2>(out, value);
    case 3:
      return write_fixed<3>(out, value);
    case 4:
      return write_fixed<4>(out, value);
    case 5:
      return write_fixed<5>(out, value);
    case 6:
      return write_fixed<6>(out, value);
    case 7:
      return write_fixed<7>(out, value);
    case 8:
      return write_fixed<8>(out, value);
    default:
      return write_fixed<9>(out, value);
  }
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
      return write_fixed<kMaxDecimals>(out, value);
    }
  }
  return std::to_chars(out, out + kDecimalTextMax, value + 0.0).ptr;
}

}  // namespace corsa::engine::detail
