#include "corsa/core/json.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <string>

#include "corsa/core/diagnostic.h"

using corsa::Json;

TEST_CASE("JSON strings are escaped: quotes, backslashes and control characters", "[core][json]") {
  CHECK(corsa::json_line(Json("a\"b\\\n\x01")) == "\"a\\\"b\\\\\\n\\u0001\"");
  CHECK(corsa::json_line(Json("tab\there")) == "\"tab\\there\"");
  CHECK(corsa::json_line(Json("한국")) == "\"한국\"");  // UTF-8 passes as it is
}

TEST_CASE("bytes that are not UTF-8 are replaced, never written raw", "[core][json]") {
  // A Latin-1 'é' (0xE9) and a lone continuation byte (0x80) in an entity name.
  const std::string latin1 = "Caf\xE9 \x80!";
  const std::string text = corsa::json_line(Json(latin1));
  CHECK(text == "\"Caf\\ufffd \\ufffd!\"");  // U+FFFD each
  CHECK(text.find('\xE9') == std::string::npos);
  // The text is valid JSON again: it reads back.
  CHECK(corsa::parse_json(text, "t.json").get<std::string>() == "Caf\xEF\xBF\xBD \xEF\xBF\xBD!");
  // Inside documents and as member names too.
  const Json object = {{"name\xFF", latin1}};
  CHECK(corsa::json_document(object).find('\xFF') == std::string::npos);
  CHECK(corsa::json_compact(object) == "{\"name\\ufffd\":\"Caf\\ufffd \\ufffd!\"}");
}

TEST_CASE("JSON strings stay valid UTF-8 whatever bytes the input held", "[core][json]") {
  // Well-formed sequences of 2, 3 and 4 bytes are kept as they are.
  CHECK(corsa::json_line(Json("\xC3\xA9\xED\x95\x9C\xF0\x9F\x9A\x97")) ==
        "\"\xC3\xA9\xED\x95\x9C\xF0\x9F\x9A\x97\"");
  // A stray continuation byte, a lead byte without its continuation, an overlong form, a
  // surrogate, a code point above U+10FFFF and a cut sequence each become U+FFFD per byte.
  CHECK(corsa::json_line(Json("a\x80"
                              "b")) == "\"a\\ufffdb\"");
  CHECK(corsa::json_line(Json("\xC3(")) == "\"\\ufffd(\"");
  CHECK(corsa::json_line(Json("\xC0\xAF")) == "\"\\ufffd\\ufffd\"");
  CHECK(corsa::json_line(Json("\xED\xA0\x80")) == "\"\\ufffd\\ufffd\\ufffd\"");
  CHECK(corsa::json_line(Json("\xF4\x90\x80\x80")) == "\"\\ufffd\\ufffd\\ufffd\\ufffd\"");
  CHECK(corsa::json_line(Json("\xE2\x82")) == "\"\\ufffd\\ufffd\"");
  CHECK(corsa::json_line(Json("\xFF\xFE")) == "\"\\ufffd\\ufffd\"");
}

TEST_CASE("JSON numbers are the shortest text that reads back exactly", "[core][json]") {
  CHECK(corsa::json_line(Json(10.0)) == "10");
  CHECK(corsa::json_line(Json(0.1)) == "0.1");
  CHECK(corsa::json_line(Json(640.0000000000001)) == "640.0000000000001");
  CHECK(corsa::json_line(Json(1e-7)) == "1e-07");
  CHECK(corsa::json_line(Json(-0.0)) == "-0");
  CHECK(corsa::json_line(Json(int64_t{-42})) == "-42");
  CHECK(corsa::json_line(Json(uint64_t{18446744073709551615u})) == "18446744073709551615");
  // JSON has no infinities or NaN.
  CHECK(corsa::json_line(Json(std::numeric_limits<double>::infinity())) == "null");
  CHECK(corsa::json_line(Json(std::nan(""))) == "null");
  // Round trip, bit for bit, over the whole range of magnitudes.
  std::mt19937_64 random(5);
  for (int i = 0; i < 20000; ++i) {
    uint64_t bits = random();
    double value = 0.0;
    std::memcpy(&value, &bits, sizeof value);
    if (!std::isfinite(value)) continue;
    const Json back = corsa::parse_json(corsa::json_line(Json(value)), "n.json");
    REQUIRE(back.get<double>() == value);
    REQUIRE(std::signbit(back.get<double>()) == std::signbit(value));
  }
}

TEST_CASE("Corsa's JSON layout: members a line, arrays of objects an object a line",
          "[core][json]") {
  const Json summary = {{"scenario", "cut_in.xosc"},
                        {"parameters", {{"Gap", "10"}, {"Speed", "20"}}},
                        {"seed", 42},
                        {"entities", {{{"name", "Ego"}, {"x", 650.5}}, {{"name", "Cutter"}}}},
                        {"collisions", Json::array()},
                        {"grid", Json::array({"a=1:2:1"})}};
  CHECK(corsa::json_document(summary) ==
        "{\n"
        "  \"scenario\": \"cut_in.xosc\",\n"
        "  \"parameters\": {\"Gap\": \"10\", \"Speed\": \"20\"},\n"
        "  \"seed\": 42,\n"
        "  \"entities\": [\n"
        "    {\"name\": \"Ego\", \"x\": 650.5},\n"
        "    {\"name\": \"Cutter\"}\n"
        "  ],\n"
        "  \"collisions\": [],\n"
        "  \"grid\": [\"a=1:2:1\"]\n"
        "}\n");
  CHECK(corsa::json_document(Json::object()) == "{}\n");
  CHECK(corsa::json_line({{"K", {{1, 0}, {0, 1}}}, {"ok", true}, {"none", nullptr}}) ==
        "{\"K\": [[1, 0], [0, 1]], \"ok\": true, \"none\": null}");
  CHECK(corsa::json_compact({{"valid", false}, {"files", {1, 2}}}) ==
        "{\"valid\":false,\"files\":[1,2]}");
}

TEST_CASE("JSON that cannot be read is located at its file and line", "[core][json]") {
  try {
    corsa::parse_json("{\n  \"plan\": \"1\",\n  \"variants\": \n}\n", "out/sweep.json");
    FAIL("no error");
  } catch (const corsa::InputError& error) {
    CHECK_THAT(error.what(), Catch::StartsWith("out/sweep.json:4: error: not valid JSON: "));
  }
  CHECK_THROWS_WITH(corsa::parse_json("{\"a\": \"\xFF\"}", "bad.json"),
                    Catch::StartsWith("bad.json:1: error: not valid JSON: "));
  CHECK_THROWS_AS(corsa::parse_json("", "empty.json"), corsa::InputError);
  // A number beyond the range of doubles: an InputError at its line (it escaped as nlohmann's
  // out_of_range, an internal error).
  CHECK_THROWS_WITH(corsa::parse_json("{\n  \"dt\": 0.01,\n  \"seed\": 117e401\n}\n", "sweep.json"),
                    "sweep.json:3: error: not valid JSON: number overflow parsing '117e401'");
  CHECK_THROWS_WITH(corsa::parse_json("[-1e400]", "a.json"),
                    "a.json:1: error: not valid JSON: number overflow parsing '-1e400'");
  // Members keep their order when read.
  const Json read = corsa::parse_json(R"({"b": 1, "a": 2})", "o.json");
  CHECK(read.begin().key() == "b");
}
