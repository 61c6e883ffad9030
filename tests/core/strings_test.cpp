#include "corsa/core/strings.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

TEST_CASE("numbers parse strictly", "[core][strings]") {
  CHECK(corsa::parse_double("1.5") == 1.5);
  CHECK(corsa::parse_double("  -2e3 ") == -2000.0);
  CHECK(corsa::parse_double("+4") == 4.0);
  CHECK_FALSE(corsa::parse_double(""));
  CHECK_FALSE(corsa::parse_double("1.5m"));
  CHECK_FALSE(corsa::parse_double("nan"));
  CHECK_FALSE(corsa::parse_double("inf"));
  CHECK_FALSE(corsa::parse_double("1e999"));
  CHECK(corsa::parse_int("-12") == -12);
  CHECK_FALSE(corsa::parse_int("1.0"));
  CHECK_FALSE(corsa::parse_int("99999999999999999999"));
}

TEST_CASE("doubles format to the shortest text that reads back exactly", "[core][strings]") {
  for (const double x : {0.1, 1.0 / 3.0, -1e-300, 123456789.123, 2.5}) {
    CHECK(corsa::parse_double(corsa::format_double(x)) == x);
  }
  CHECK(corsa::format_double(0.1) == "0.1");
  CHECK(corsa::format_fixed(3.14159, 2) == "3.14");
}

TEST_CASE("doubles format to N significant digits as printf's %.Ng does", "[core][strings]") {
  CHECK(corsa::format_significant(1e30, 4) == "1e+30");
  CHECK(corsa::format_significant(-1234.5678, 4) == "-1235");
  CHECK(corsa::format_significant(0.000123456, 4) == "0.0001235");
  CHECK(corsa::format_significant(12.0, 4) == "12");
  CHECK(corsa::format_significant(0.1 + 0.2, 10) == "0.3");
  CHECK(corsa::format_significant(1234567.891, 10) == "1234567.891");
  // The same text as snprintf (C locale), which the messages used before, at any magnitude.
  for (const int digits : {1, 4, 10, 17}) {
    for (const double x : {0.0, -0.0, 1.0 / 3.0, -2e-308, 5e-324, 9.99995e5, 99999.5, 1e16,
                           -1.7976931348623157e308, HUGE_VAL, -HUGE_VAL, std::nan("")}) {
      char text[64];
      std::snprintf(text, sizeof text, "%.*g", digits, x);
      INFO(text);
      CHECK(corsa::format_significant(x, digits) == text);
    }
  }
}

TEST_CASE("text helpers split, trim and compare", "[core][strings]") {
  const auto parts = corsa::split("a,,b", ',');
  REQUIRE(parts.size() == 3);
  CHECK(parts[1].empty());
  CHECK(corsa::trim("  x \n") == "x");
  CHECK(corsa::iequals("L_LinKID", "l_linkid"));
  CHECK_FALSE(corsa::iequals("a", "ab"));
  CHECK(corsa::to_lower("PostID") == "postid");
}

TEST_CASE("CSV fields are quoted only when a reader would misread them", "[core][strings]") {
  CHECK(corsa::csv_field("Ego") == "Ego");
  CHECK(corsa::csv_field("") == "");
  CHECK(corsa::csv_field("a,b") == "\"a,b\"");
  CHECK(corsa::csv_field("say \"hi\"") == "\"say \"\"hi\"\"\"");
  CHECK(corsa::csv_field("two\nlines") == "\"two\nlines\"");
  CHECK(corsa::csv_field(" padded") == "\" padded\"");
}

TEST_CASE("Long text quoted in messages is clipped between characters", "[core][strings]") {
  CHECK(corsa::clip("short") == "short");
  CHECK(corsa::clip(std::string(200, 'a')) == std::string(200, 'a'));
  CHECK(corsa::clip(std::string(5000000, 'b')) == std::string(200, 'b') + "...");
  // "é" is two bytes: a cut at byte 3 of "aaé..." would split it, so it stops before.
  CHECK(corsa::clip("aa\xC3\xA9zzzz", 3) == "aa...");
  CHECK(corsa::clip("aa\xC3\xA9zzzz", 4) == "aa\xC3\xA9...");
}

TEST_CASE("A misspelt name gets the nearest valid one as a suggestion", "[core][strings]") {
  const std::vector<std::string> keys{"fog", "rain", "snow", "clouds", "wind", "wind_dir"};
  CHECK(corsa::nearest_name("fgo", keys) == "fog");    // swapped neighbours
  CHECK(corsa::nearest_name("Rian", keys) == "rain");  // case ignored
  CHECK(corsa::nearest_name("cloud", keys) == "clouds");
  CHECK(corsa::nearest_name("winddir", keys) == "wind_dir");
  CHECK_FALSE(corsa::nearest_name("hail", keys));  // nothing near
  CHECK_FALSE(corsa::nearest_name("", keys));
  CHECK(corsa::did_you_mean("fgo", keys) == " (did you mean 'fog'?)");
  CHECK(corsa::did_you_mean("temperature", keys).empty());
  CHECK_FALSE(corsa::nearest_name(std::string(100000, 'f'), keys));  // no n*m blow-up
}
