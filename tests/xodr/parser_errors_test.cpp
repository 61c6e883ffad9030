// Bad input gives located errors (file:line), never a crash; oddities warn once.

#include <algorithm>
#include <catch2/catch.hpp>
#include <string>

#include "corsa/core/atomic_file.h"
#include "corsa/xodr/map.h"
#include "corsa/xodr/parser.h"
#include "xodr_test_util.h"

using namespace corsa::xodr;

namespace {

const char* kRoad = R"(<?xml version="1.0"?>
<OpenDRIVE>
  <header revMajor="1" revMinor="6" name="t"/>
  <road id="1" length="100" junction="-1">
    <link>
      <successor elementType="road" elementId="2" contactPoint="start"/>
    </link>
    <planView>
      <geometry s="0" x="0" y="0" hdg="0" length="100"><line/></geometry>
    </planView>
    <lanes>
      <laneSection s="0">
        <center><lane id="0" type="none"/></center>
        <right><lane id="-1" type="driving"><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane></right>
      </laneSection>
    </lanes>
  </road>
  <road id="2" length="50" junction="-1">
    <planView>
      <geometry s="0" x="100" y="0" hdg="0" length="50"><line/></geometry>
    </planView>
    <lanes>
      <laneSection s="0">
        <center><lane id="0"/></center><right><lane id="-1" type="driving"/></right>
      </laneSection>
    </lanes>
  </road>
</OpenDRIVE>
)";

std::string replace(std::string text, const std::string& from, const std::string& to) {
  const auto pos = text.find(from);
  REQUIRE(pos != std::string::npos);
  return text.replace(pos, from.size(), to);
}

/// The formatted error of loading `text`, or "" when it loads.
std::string load_error(const std::string& text) {
  corsa::Diagnostics diagnostics;
  try {
    Map::build(parse_xodr_text(text, "bad.xodr", diagnostics), diagnostics);
  } catch (const corsa::InputError& error) {
    return error.diagnostic().format();
  }
  return "";
}

}  // namespace

TEST_CASE("the small test document loads", "[xodr][errors]") { CHECK(load_error(kRoad).empty()); }

TEST_CASE("a truncated file is reported with its line", "[xodr][errors]") {
  const std::string text(kRoad);
  const std::string error = load_error(text.substr(0, text.find("<lanes>", 300)));
  CHECK(error.rfind("bad.xodr:", 0) == 0);
  CHECK(error.find("truncated") != std::string::npos);
  CHECK(error.find("error:") != std::string::npos);
}

TEST_CASE("every prefix of a file either loads or fails cleanly", "[xodr][errors]") {
  const std::string text(kRoad);
  size_t failures = 0;
  for (size_t n = 0; n < text.size(); n += 3) {
    const std::string error = load_error(text.substr(0, n));
    failures += error.empty() ? 0 : 1;
    if (!error.empty()) {
      CHECK(error.rfind("bad.xodr", 0) == 0);
    }
  }
  CHECK(failures > text.size() / 4);
}

TEST_CASE("a negative geometry length is an error at its line", "[xodr][errors]") {
  const std::string error =
      load_error(replace(kRoad, R"(hdg="0" length="100")", R"(hdg="0" length="-100")"));
  CHECK(error.rfind("bad.xodr:9: error:", 0) == 0);
  CHECK(error.find("must not be negative") != std::string::npos);
}

TEST_CASE("a link to a missing road is an error at the road", "[xodr][errors]") {
  const std::string error = load_error(replace(kRoad, R"(elementId="2")", R"(elementId="7")"));
  CHECK(error.rfind("bad.xodr:4: error:", 0) == 0);
  CHECK(error.find("road '7' does not exist") != std::string::npos);
}

TEST_CASE("NaN or text where a number belongs is an error", "[xodr][errors]") {
  SECTION("NaN") {
    const std::string error = load_error(replace(kRoad, R"(x="100")", R"(x="nan")"));
    CHECK(error.rfind("bad.xodr:20: error:", 0) == 0);
    CHECK(error.find("'x'") != std::string::npos);
  }
  SECTION("text") {
    const std::string error = load_error(replace(kRoad, R"(a="3.5")", R"(a="wide")"));
    CHECK(error.rfind("bad.xodr:14: error:", 0) == 0);
    CHECK(error.find("'wide'") != std::string::npos);
  }
  SECTION("missing attribute") {
    const std::string error = load_error(replace(kRoad, R"( hdg="0" length="50")", ""));
    CHECK(error.rfind("bad.xodr:20: error:", 0) == 0);
    CHECK(error.find("needs attribute 'hdg'") != std::string::npos);
  }
}

TEST_CASE("malformed XML is reported with its line", "[xodr][errors]") {
  CHECK(load_error(replace(kRoad, "</planView>", "</plan>")).rfind("bad.xodr:10: error:", 0) == 0);
  CHECK(load_error(replace(kRoad, R"(length="50")", R"(length=50)")).rfind("bad.xodr:18:", 0) == 0);
  CHECK(load_error("").find("no root element") != std::string::npos);
  CHECK(load_error("<?xml version=\"1.0\"?><OpenSCENARIO/>").find("not an OpenDRIVE") !=
        std::string::npos);
  CHECK(load_error(replace(kRoad, "type=\"none\"/>", "type=\"none\"/><x>&bogus;</x>"))
            .find("unknown entity") != std::string::npos);
}

TEST_CASE("unknown elements warn once per kind", "[xodr][errors]") {
  const std::string text =
      replace(replace(kRoad, "<planView>", "<planView><foo/><foo/>"), "<lanes>", "<lanes><bar/>");
  corsa::Diagnostics diagnostics;
  const MapData data = parse_xodr_text(text, "odd.xodr", diagnostics);
  CHECK(data.roads.size() == 2);
  for (const auto& d : diagnostics.all()) {
    UNSCOPED_INFO(d.format());
  }
  REQUIRE(diagnostics.size() == 2);
  const auto all = diagnostics.all();
  CHECK(all[0].format().rfind("odd.xodr:8: warning: unknown element <foo>", 0) == 0);
  CHECK(all[1].message.find("<bar>") != std::string::npos);
}

TEST_CASE("entities, CDATA and comments are read", "[xodr][errors]") {
  const std::string text = replace(
      replace(
          kRoad, R"(name="t"/>)",
          R"(name="a &amp; b &#x41;"><!-- c --><geoReference><![CDATA[+proj=utm]]></geoReference></header>)"),
      "<road id=\"2\"", "<!-- comment with <road> inside -->\n  <road id=\"2\"");
  corsa::Diagnostics diagnostics;
  const MapData data = parse_xodr_text(text, "x.xodr", diagnostics);
  CHECK(data.header.name == "a & b A");
  CHECK(data.header.geo_reference == "+proj=utm");
  CHECK(data.header.rev_minor == 6);
  CHECK(data.roads.at(1).line == 19);  // one line more: the comment
}

TEST_CASE("the header keeps its source line for messages about it", "[xodr][errors]") {
  corsa::Diagnostics diagnostics;
  CHECK(parse_xodr_text(kRoad, "x.xodr", diagnostics).header.line == 3);
  const std::string lower = replace(kRoad, "<OpenDRIVE>", "<OpenDRIVE>\n\n  <!-- two lines -->");
  CHECK(parse_xodr_text(lower, "x.xodr", diagnostics).header.line == 5);
  CHECK(MapData{}.header.line == 0);  // built in memory
}

TEST_CASE("character references are digits naming a character XML allows", "[xodr][errors]") {
  // XML 1.0 §4.1 [66] and §2.2 [2]: tab, line feed, carriage return and U+0020 up, except the
  // surrogates, U+FFFE and U+FFFF; leading zeros are fine.
  corsa::Diagnostics diagnostics;
  const MapData data =
      parse_xodr_text(replace(kRoad, R"(name="t")",
                              R"(name="&#9;&#x0041;&#0066;&#xD7FF;&#xE000;&#x1F600;&#xFFFD;")"),
                      "x.xodr", diagnostics);
  CHECK(data.header.name == "\tAB\xED\x9F\xBF\xEE\x80\x80\xF0\x9F\x98\x80\xEF\xBF\xBD");
  // A sign, a blank or a wrapped number (strtoul read -18446744073709551615 as 1), NUL, another
  // control character, a surrogate (no UTF-8 for it), a non-character, past U+10FFFF.
  for (const std::string ref :
       {"&#-18446744073709551615;", "&#+65;", "&# 65;", "&#x;", "&#0;", "&#1;", "&#x1F;",
        "&#xD800;", "&#xDFFF;", "&#xFFFE;", "&#x110000;", "&#99999999999999999999;"}) {
    INFO(ref);
    const std::string error = load_error(replace(kRoad, R"(name="t")", "name=\"" + ref + "\""));
    CHECK(error.rfind("bad.xodr:3: error: malformed XML: bad character reference '" + ref + "'",
                      0) == 0);
  }
}

TEST_CASE("a missing file is an error naming it", "[xodr][errors]") {
  corsa::Diagnostics diagnostics;
  CHECK_THROWS_WITH(parse_xodr("/nonexistent/map.xodr", diagnostics),
                    Catch::Contains("/nonexistent/map.xodr"));
}

namespace {

// 1-based line of the first occurrence of `needle` in `text`.
int line_of(const std::string& text, const std::string& needle) {
  const size_t at = text.find(needle);
  REQUIRE(at != std::string::npos);
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + at, '\n'));
}

}  // namespace

TEST_CASE("an object without s is placed by its repeat, or left out, with a lenient warning",
          "[xodr][parser][lenient]") {
  // esmini's crest-curve.xodr: a barrier written only by its <repeat> (1.8 §13.4: a repeat's
  // attributes overrule the object's).
  const std::string text = replace(
      kRoad, "    <lanes>\n",
      "    <objects>\n"
      "      <object type=\"barrier\" id=\"8\" length=\"5\">\n"
      "        <repeat s=\"20\" length=\"55\" distance=\"0\" tStart=\"-15\" tEnd=\"-40\"/>\n"
      "      </object>\n"
      "      <object type=\"pole\" id=\"9\" t=\"2\"/>\n"
      "      <object type=\"pole\" id=\"10\" s=\"5\" t=\"3\"/>\n"
      "    </objects>\n"
      "    <lanes>\n");
  corsa::Diagnostics diagnostics;
  const MapData data = parse_xodr_text(text, "objects.xodr", diagnostics);
  const Road& road = data.roads.at(0);
  REQUIRE(road.objects.size() == 2);
  CHECK(road.objects[0].id == "8");
  CHECK(road.objects[0].s == 20.0);
  CHECK(road.objects[0].t == -15.0);
  REQUIRE(road.objects[0].repeats.size() == 1);
  CHECK(road.objects[0].repeats[0].t_end == -40.0);
  CHECK(road.objects[1].id == "10");
  REQUIRE(data.lenient_readings.size() == 2);
  const int placed = line_of(text, "<object type=\"barrier\"");
  const int dropped = line_of(text, "<object type=\"pole\" id=\"9\"");
  CHECK(data.lenient_readings[0].line == placed);
  CHECK(data.lenient_readings[1].line == dropped);
  std::vector<std::string> warnings;
  for (const auto& d : diagnostics.all()) warnings.push_back(d.format());
  CHECK_THAT(warnings.at(0),
             Catch::Equals("objects.xodr:" + std::to_string(placed) +
                           ": warning: <object> '8' without s and t (read as s 20, t -15: its "
                           "<repeat>'s start, whose attributes overrule the object's) [in "
                           "OpenDRIVE/road/objects/object]"));
  const std::string dropped_at = "objects.xodr:" + std::to_string(dropped);
  CHECK_THAT(warnings.at(1),
             Catch::StartsWith(dropped_at + ": warning: <object> '9' without s "
                                            "(read as no object: nothing places it on its "
                                            "road)"));
  // Refused where lenient readings are (--strict): every one, at its line.
  try {
    refuse_lenient_readings(data);
    FAIL("a map read leniently was not refused");
  } catch (const corsa::InputError& error) {
    REQUIRE(error.diagnostics().size() == 2);
    CHECK(error.diagnostics()[0].line == placed);
    CHECK_THAT(error.diagnostics()[0].message,
               Catch::Contains("(an error under --strict; otherwise read as s 20, t -15"));
  }
  // A map read as written has nothing to refuse.
  corsa::Diagnostics plain;
  CHECK_NOTHROW(refuse_lenient_readings(parse_xodr_text(kRoad, "plain.xodr", plain)));
}
