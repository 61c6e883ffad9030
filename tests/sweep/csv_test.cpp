#include "corsa/sweep/csv.h"

#include <catch2/catch.hpp>

using corsa::sweep::csv_field;
using corsa::sweep::csv_line;
using corsa::sweep::parse_csv;

TEST_CASE("csv fields are quoted only when they need it", "[sweep][csv]") {
  CHECK(csv_field("plain") == "plain");
  CHECK(csv_field("a,b") == "\"a,b\"");
  CHECK(csv_field("say \"hi\"") == "\"say \"\"hi\"\"\"");
  CHECK(csv_field(" padded") == "\" padded\"");
  CHECK(csv_field("two\nlines") == "\"two\nlines\"");
  CHECK(csv_field("") == "");
}

TEST_CASE("csv lines read back to the same fields", "[sweep][csv]") {
  const std::vector<std::string> fields = {
      "0", "a,b", "", "x \"y\"", "file.xosc:3: error: bad\nthing", "-1"};
  std::vector<std::vector<std::string>> rows;
  REQUIRE(parse_csv(csv_line(fields) + csv_line({"1", "2"}), rows));
  REQUIRE(rows.size() == 2);
  CHECK(rows[0] == fields);
  CHECK(rows[1] == std::vector<std::string>{"1", "2"});
}

TEST_CASE("csv parsing keeps a last line without newline and rejects an open quote",
          "[sweep][csv]") {
  std::vector<std::vector<std::string>> rows;
  REQUIRE(parse_csv("a,b\r\n\nc,", rows));
  REQUIRE(rows.size() == 2);
  CHECK(rows[0] == std::vector<std::string>{"a", "b"});
  CHECK(rows[1] == std::vector<std::string>{"c", ""});
  std::vector<std::vector<std::string>> broken;
  CHECK_FALSE(parse_csv("a,\"b\n", broken));
}
