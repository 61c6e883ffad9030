// The trajectory CSV's number text (engine/src/output/decimal_text.h): fixed decimals without
// trailing zeros for lengths, speeds and angles, the shortest exact text for times, and the
// shortest round-trip text beyond exact scaling.

#include <bit>
#include <catch2/catch.hpp>
#include <charconv>
#include <cmath>
#include <limits>
#include <random>
#include <string>

#include "output/decimal_text.h"

namespace {

std::string decimal(double value, int decimals) {
  char buffer[corsa::engine::detail::kDecimalTextMax];
  return std::string(buffer, corsa::engine::detail::write_decimal(buffer, value, decimals));
}

std::string exact(double value) {
  char buffer[corsa::engine::detail::kDecimalTextMax];
  return std::string(buffer, corsa::engine::detail::write_exact(buffer, value));
}

std::string shortest(double value) {
  char buffer[64];
  return std::string(buffer, std::to_chars(buffer, buffer + sizeof buffer, value).ptr);
}

double read(const std::string& text) {
  double value = 0.0;
  std::from_chars(text.data(), text.data() + text.size(), value);
  return value;
}

}  // namespace

TEST_CASE("trajectory numbers are rounded to fixed decimals without trailing zeros",
          "[engine][output]") {
  CHECK(decimal(50.0, 6) == "50");
  CHECK(decimal(-5.625, 6) == "-5.625");
  CHECK(decimal(32.19999999999999, 6) == "32.2");
  CHECK(decimal(0.05, 6) == "0.05");
  CHECK(decimal(-0.0000504, 6) == "-0.00005");
  CHECK(decimal(1.125, 2) == "1.13");  // halves away from zero
  CHECK(decimal(-2.5, 0) == "-3");
  CHECK(decimal(0.9999999996, 9) == "1");  // the carry reaches the integer part
  CHECK(decimal(-0.0000004, 6) == "0");    // never "-0"
  CHECK(decimal(-0.0, 6) == "0");
  CHECK(decimal(3.14159265358979, 9) == "3.141592654");
  CHECK(decimal(-1e-9, 9) == "-0.000000001");
  CHECK(decimal(7.5, 0) == "8");
}

TEST_CASE("numbers beyond exact scaling fall back to the shortest round-trip text",
          "[engine][output]") {
  CHECK(decimal(1e20, 6) == "1e+20");
  CHECK(decimal(-2.5e10, 6) == "-2.5e+10");
  CHECK(decimal(std::numeric_limits<double>::infinity(), 6) == "inf");
  CHECK(decimal(std::nan(""), 9) == "nan");
  // Just below the limit the text is still the rounded fixed-decimal one.
  CHECK(decimal(8.9e9 + 0.25, 6) == "8900000000.25");
}

TEST_CASE("trajectory times are exact: the shortest text of every step's time",
          "[engine][output]") {
  CHECK(exact(0.0) == "0");
  CHECK(exact(0.49) == "0.49");
  CHECK(exact(0.1 + 0.2) == "0.30000000000000004");  // off the 9-decimal grid: to_chars
  CHECK(exact(1e-12) == "1e-12");
  CHECK(exact(1e12 / 3.0) == shortest(1e12 / 3.0));
  for (int k = 1; k < 200000; ++k) {
    // Times as a fixed step gives them (tick / steps per second), and as a product that may be
    // off the decimal grid (tick * dt): each reads back exactly, and matches to_chars.
    for (const double t : {k / 100.0, k * 0.01, k / 60.0, k * 0.001}) {
      const std::string text = exact(t);
      REQUIRE(read(text) == t);
      if (t >= 0.001) REQUIRE(text == shortest(t));
    }
  }
}

TEST_CASE("fixed-decimal text reads back within half a unit of its last place",
          "[engine][output]") {
  std::mt19937_64 random(20261122);
  std::uniform_real_distribution<double> value(-5000.0, 5000.0);
  std::uniform_int_distribution<int> places(0, 9);
  for (int i = 0; i < 20000; ++i) {
    const double v = value(random) / std::pow(10.0, places(random));
    const int decimals = places(random);
    const std::string text = decimal(v, decimals);
    REQUIRE(text.find('e') == std::string::npos);
    const double half_unit = 0.5 * std::pow(10.0, -decimals);
    CHECK(std::fabs(read(text) - v) <= half_unit * (1.0 + 1e-9) + 1e-12 * std::fabs(v));
    CHECK(text.back() != '.');
    CHECK((text.find('.') == std::string::npos || text.back() != '0'));
  }
}

namespace {

// The text of `units` x 10^-Decimals built the plain way: the integer part, a point and the
// decimals padded to full width, then the trailing zeros and a bare point dropped.
template <int Decimals>
std::string plain_units(int64_t units) {
  const uint64_t magnitude = units < 0 ? 0 - static_cast<uint64_t>(units) : units;
  uint64_t unit = 1;
  for (int k = 0; k < Decimals; ++k) unit *= 10;
  std::string fraction = Decimals == 0 ? "" : std::to_string(magnitude % unit);
  fraction.insert(0, Decimals - fraction.size(), '0');
  while (!fraction.empty() && fraction.back() == '0') fraction.pop_back();
  const std::string text =
      std::to_string(magnitude / unit) + (fraction.empty() ? "" : "." + fraction);
  return units < 0 ? "-" + text : text;
}

template <int Decimals>
void check_units(int64_t units) {
  char buffer[corsa::engine::detail::kDecimalTextMax];
  const std::string text(buffer, corsa::engine::detail::write_units<Decimals>(buffer, units));
  REQUIRE(text == plain_units<Decimals>(units));
}

}  // namespace

TEST_CASE("fixed-decimal text of a number's integer equals the plain division's text",
          "[engine][output]") {
  std::mt19937_64 random(20261127);
  // Magnitudes of every order up to the exact-scaling bound (9e15 units), both signs, and
  // numbers ending in runs of zeros.
  std::uniform_int_distribution<int> order(0, 15);
  std::uniform_int_distribution<int> zeros(0, 9);
  for (int i = 0; i < 200000; ++i) {
    const double magnitude =
        std::pow(10.0, order(random) + std::generate_canonical<double, 53>(random));
    int64_t units = static_cast<int64_t>(std::min(magnitude, 8.999e15));
    int64_t step = 1;
    for (int z = zeros(random); z > 0; --z) step *= 10;
    units = units / step * step;  // the last few digits zero
    units = (i % 2 == 0) ? units : -units;
    check_units<6>(units);
    check_units<9>(units);
    check_units<2>(units);
    check_units<1>(units);
    check_units<0>(units);
  }
  for (const int64_t units :
       {int64_t{1}, int64_t{9}, int64_t{10}, int64_t{99}, int64_t{100}, int64_t{999'999},
        int64_t{1'000'000}, int64_t{1'000'001}, int64_t{10'000'000}, int64_t{99'999'999},
        int64_t{8'999'999'999'999'999}}) {
    check_units<6>(units);
    check_units<6>(-units);
    check_units<9>(units);
    check_units<0>(units);
  }
}

TEST_CASE("rounding to units takes halves away from zero, as llround does", "[engine][output]") {
  using corsa::engine::detail::decimal_text::round_half_away;
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> magnitude(-12.0, 15.0);
  for (int i = 0; i < 200000; ++i) {
    const double value = std::copysign(std::pow(10.0, magnitude(random)), i % 2 == 0 ? 1.0 : -1.0);
    REQUIRE(round_half_away(value) == std::llround(value));
  }
  for (const double value : {0.5, -0.5, 1.5, -1.5, 2.5, -2.5, 0.49999999999999994, -0.0, 0.0,
                             4503599627370495.5, -4503599627370495.5}) {
    REQUIRE(round_half_away(value) == std::llround(value));
  }
}

TEST_CASE("the binary coder's rounding is round_half_away, and far values are told apart",
          "[engine][output]") {
  using namespace corsa::engine::detail::decimal_text;
  // round_or_far against the range test and round_half_away it replaces, for one value.
  int64_t checked = 0;
  const auto check = [&checked](double scaled) {
    ++checked;
    const bool exact = std::fabs(scaled) < kExactLimit;
    const int64_t units = round_or_far(scaled);
    REQUIRE(near_units(units) == exact);
    if (exact) {
      REQUIRE(units == round_half_away(scaled));
    }
  };
  // Every half and its neighbours a few ulps away, with |whole| up to 4000, and around each
  // power of two.
  for (int64_t whole = -4000; whole <= 4000; ++whole) {
    for (const double base : {0.5, 0.0, 0.25}) {
      double value = static_cast<double>(whole) + base;
      for (int ulp = 0; ulp < 3; ++ulp) {
        check(value);
        check(std::nextafter(value, -1e300));
        value = std::nextafter(value, 1e300);
      }
    }
  }
  for (int exponent = -2; exponent < 64; ++exponent) {
    const double power = std::ldexp(1.0, exponent);
    for (const double offset : {-1.5, -1.0, -0.5, 0.0, 0.5, 1.0, 1.5}) {
      for (const double value : {power + offset, -(power + offset)}) {
        check(value);
        check(std::nextafter(value, 0.0));
        check(std::nextafter(value, 1e300));
        check(std::nextafter(value, -1e300));
      }
    }
  }
  // The range's edge, what cannot be scaled, and the halves' neighbours near 0.
  for (const double value :
       {9e15, 9e15 - 1, 9e15 - 0.5, -9e15, -9e15 + 1, 9e15 + 2, 9.2233720368547758e18,
        -9.2233720368547758e18, 1e300, -1e300, std::numeric_limits<double>::infinity(),
        -std::numeric_limits<double>::infinity(), std::numeric_limits<double>::quiet_NaN(),
        0.49999999999999994, -0.49999999999999994, 0.0, -0.0, 5e-324, -5e-324}) {
    check(value);
  }
  // Any bits at all, and magnitudes spread over the decimals' range.
  std::mt19937_64 random(11);
  std::uniform_real_distribution<double> magnitude(-12.0, 17.0);
  for (int i = 0; i < 200000; ++i) {
    check(std::bit_cast<double>(random()));
    const double value = std::pow(10.0, magnitude(random));
    check(value);
    check(-value);
  }
  REQUIRE(checked > 700000);
}

namespace {

// The `Count` digits of `value`, leading zeros included, one division by 10 at a time.
template <int Count>
std::string plain_digits(uint64_t value) {
  std::string text(Count, '0');
  for (int k = Count - 1; k >= 0; --k, value /= 10) text[k] = static_cast<char>('0' + value % 10);
  return text;
}

template <int Count>
void check_fixed_digits(uint64_t value) {
  char buffer[16];
  corsa::engine::detail::decimal_text::fixed_digits<Count>(buffer, value);
  REQUIRE(std::string(buffer, Count) == plain_digits<Count>(value));
}

// write_fixed's text the plain way: the value scaled and rounded by llround, then plain_units;
// the shortest round-trip text beyond exact scaling.
template <int Decimals>
std::string plain_fixed(double value) {
  const double scaled = value * std::pow(10.0, Decimals);
  return std::fabs(scaled) < 9.0e15 ? plain_units<Decimals>(std::llround(scaled))
                                    : shortest(value + 0.0);
}

template <int Decimals>
void check_fixed(double value) {
  char buffer[corsa::engine::detail::kDecimalTextMax];
  const std::string text(buffer, corsa::engine::detail::write_fixed<Decimals>(buffer, value));
  REQUIRE(text == plain_fixed<Decimals>(value));
}

}  // namespace

TEST_CASE("fixed-width decimals by multiplication equal the digits of repeated division",
          "[engine][output]") {
  // Every value of 1 to 6 digits, and 7 to 9 digits at random and at the ends of their range.
  for (uint64_t v = 0; v < 1'000'000; ++v) {
    check_fixed_digits<6>(v);
    if (v < 100'000) check_fixed_digits<5>(v);
    if (v < 10'000) check_fixed_digits<4>(v);
    if (v < 1'000) check_fixed_digits<3>(v);
    if (v < 100) check_fixed_digits<2>(v);
    if (v < 10) check_fixed_digits<1>(v);
  }
  std::mt19937_64 random(20261127);
  for (int i = 0; i < 300000; ++i) {
    const uint64_t v = random() % 1'000'000'000;
    check_fixed_digits<9>(v);
    check_fixed_digits<8>(v % 100'000'000);
    check_fixed_digits<7>(v % 10'000'000);
  }
  for (const uint64_t v : {0ULL, 1ULL, 9ULL, 10ULL, 99ULL, 100ULL, 999'999ULL, 1'000'000ULL,
                           9'999'999ULL, 99'999'999ULL, 100'000'000ULL, 999'999'999ULL}) {
    check_fixed_digits<9>(v);
    if (v < 100'000'000) check_fixed_digits<8>(v);
    if (v < 10'000'000) check_fixed_digits<7>(v);
  }
}

TEST_CASE("fixed-decimal text equals llround and the plain division on values of every kind",
          "[engine][output]") {
  std::mt19937_64 random(27112026);
  std::uniform_real_distribution<double> exponent(-10.0, 16.0);
  std::uniform_int_distribution<int64_t> halves(-2'000'000'000, 2'000'000'000);
  for (int i = 0; i < 200000; ++i) {
    const double sign = i % 2 == 0 ? 1.0 : -1.0;
    const double v = sign * std::pow(10.0, exponent(random));
    check_fixed<6>(v);
    check_fixed<9>(v);
    check_fixed<2>(v);
    // Halves of the last place (rounded away from zero), as far as the scaling keeps them.
    const double half = (static_cast<double>(halves(random)) + 0.5);
    check_fixed<6>(half / 1e6);
    check_fixed<9>(half / 1e9);
    check_fixed<0>(half);
  }
  for (const double v :
       {-0.0,          0.0,        0.5e-6,    -0.5e-6,       0.4999999e-6,
        -0.4999999e-9, 0.5e-9,     1e-300,    -1e-300,       8.99e9,
        -8.99e9,       8.99e6,     9.0e9,     1e300,         -1e300,
        9999.9999995,  99.9999995, 0.9999995, -9999.9999995, 123456789.123456789}) {
    check_fixed<6>(v);
    check_fixed<9>(v);
    check_fixed<0>(v);
  }
  CHECK(plain_fixed<6>(-0.0) == "0");  // the reference says "0" for negative zero too
}
