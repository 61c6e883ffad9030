#include <tinyxml2.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <stdexcept>
#include <string>

#include "corsa/core/diagnostic.h"
#include "corsa/core/xml_entities.h"
#include "corsa/core/xml_errors.h"
#include "corsa/core/xsd_validator.h"

namespace {

// A schema of the subset Corsa's own formats use: a root with a required bounded attribute, a
// defaulted one, and a sequence of one to two children.
constexpr const char* kSchema = R"(<?xml version="1.0"?>
<xs:schema xmlns:xs="http://www.w3.org/2001/XMLSchema">
  <xs:element name="Root" type="RootType"/>
  <xs:simpleType name="Rate">
    <xs:restriction base="xs:double">
      <xs:minExclusive value="0"/>
      <xs:maxInclusive value="100"/>
    </xs:restriction>
  </xs:simpleType>
  <xs:complexType name="RootType">
    <xs:sequence>
      <xs:element name="Item" type="ItemType" minOccurs="1" maxOccurs="2"/>
    </xs:sequence>
    <xs:attribute name="rate" type="Rate" use="required"/>
    <xs:attribute name="mode" type="xs:string" default="plain"/>
  </xs:complexType>
  <xs:complexType name="ItemType">
    <xs:attribute name="name" type="xs:string" use="required"/>
  </xs:complexType>
</xs:schema>)";

corsa::Diagnostic error_of(const corsa::XsdSchema& schema, const std::string& xml) {
  try {
    schema.validate(xml, "doc.xml");
  } catch (const corsa::InputError& error) {
    return error.diagnostic();
  }
  FAIL("expected an InputError for: " << xml);
  return {};
}

}  // namespace

TEST_CASE("tinyxml2 parse errors are told in words", "[core][xml]") {
  CHECK(corsa::xml_error_words(tinyxml2::XML_ERROR_MISMATCHED_ELEMENT) == "mismatched closing tag");
  CHECK(corsa::xml_error_words(tinyxml2::XML_ERROR_EMPTY_DOCUMENT) == "empty document");
  CHECK_THAT(corsa::xml_error_words(tinyxml2::XML_ELEMENT_DEPTH_EXCEEDED),
             Catch::Contains("nested too deeply"));
  // An error without words of its own still names tinyxml2's id rather than saying nothing.
  CHECK_THAT(corsa::xml_error_words(tinyxml2::XML_ERROR_FILE_NOT_FOUND),
             Catch::Contains("XML_ERROR_FILE_NOT_FOUND"));
}

TEST_CASE("entity references XML does not predefine are found at their line", "[core][xml]") {
  // Predefined entities, character references, a bare '&' and any '&' in comments, CDATA and
  // processing instructions are fine.
  CHECK_FALSE(corsa::find_undeclared_entity(
      "<a b=\"&lt;&gt;&amp;&apos;&quot;&#38;&#x26; & c\">\n<!-- &x; -->\n<![CDATA[&y;]]>"
      "<?pi &z;?></a>"));
  const auto entity = corsa::find_undeclared_entity("<a>\n<!-- &x;\n-->\n<b c=\"&speed;\"/></a>");
  REQUIRE(entity);
  CHECK(entity->line == 4);
  CHECK_THAT(entity->message, Catch::StartsWith("entity '&speed;' is not declared"));
  const auto doctype = corsa::find_undeclared_entity(
      "<?xml version=\"1.0\"?>\n<!DOCTYPE a [<!ENTITY x \"1\">]>\n<a/>");
  REQUIRE(doctype);
  CHECK(doctype->line == 2);
  CHECK_THAT(doctype->message, Catch::StartsWith("a DOCTYPE with declarations is not read"));
  CHECK_FALSE(corsa::find_undeclared_entity("<!DOCTYPE a SYSTEM \"a.dtd\">\n<a/>"));
}

TEST_CASE("character references are plain digits naming a character XML allows", "[core][xml]") {
  CHECK(corsa::xml_character_reference("9") == 9u);
  CHECK(corsa::xml_character_reference("x0041") == 0x41u);  // leading zeros are fine
  CHECK(corsa::xml_character_reference("X1F600") == 0x1F600u);
  CHECK(corsa::xml_character_reference("xFFFD") == 0xFFFDu);
  CHECK(corsa::xml_character_reference("1114111") == 0x10FFFFu);
  // A sign or blank (strtoul reads "-18446744073709551615" as 1), no digits, NUL and other
  // control characters, surrogates, U+FFFE/U+FFFF, past U+10FFFF.
  for (const char* body : {"-18446744073709551615", "+65", " 65", "", "x", "0", "1", "x1F", "xD800",
                           "xDFFF", "xFFFE", "x110000", "99999999999999999999"}) {
    INFO(body);
    CHECK_FALSE(corsa::xml_character_reference(body));
  }
  const auto found =
      corsa::find_undeclared_entity("<a>\n<!-- &#0; -->\n<b c=\"&#65;&#xD800;\"/></a>");
  REQUIRE(found);
  CHECK(found->line == 3);
  CHECK_THAT(found->message, Catch::StartsWith("bad character reference '&#xD800;' (XML 1.0"));
  CHECK(corsa::find_undeclared_entity("<a b=\"&#65\"/>")->message ==
        corsa::bad_character_reference_message("65\"/>"));
}

TEST_CASE("a document that follows the schema comes back with its defaults", "[core][xml][xsd]") {
  const corsa::XsdSchema schema(kSchema);
  const corsa::ValidatedElement root =
      schema.validate("<Root rate=\"10\">\n  <Item name=\"a\"/>\n</Root>", "doc.xml");
  CHECK(root.name == "Root");
  REQUIRE(root.find("mode") != nullptr);
  CHECK(*root.find("mode") == "plain");
  REQUIRE(root.children.size() == 1);
  CHECK(root.children[0].line == 2);
  CHECK(*root.children[0].find("name") == "a");
}

TEST_CASE("documents that break the schema are located errors", "[core][xml][xsd]") {
  const corsa::XsdSchema schema(kSchema);
  const corsa::Diagnostic missing = error_of(schema, "<Root>\n<Item name=\"a\"/>\n</Root>");
  CHECK(missing.file == "doc.xml");
  CHECK(missing.line == 1);
  CHECK_THAT(missing.message, Catch::Contains("<Root> needs the attribute 'rate'"));
  const corsa::Diagnostic bound = error_of(schema, "<Root rate=\"0\"><Item name=\"a\"/></Root>");
  CHECK_THAT(bound.message,
             Catch::Contains("attribute 'rate' of <Root> is 0; it must be greater than 0"));
  const corsa::Diagnostic extra = error_of(
      schema,
      "<Root rate=\"1\">\n<Item name=\"a\"/>\n<Item name=\"b\"/>\n<Item name=\"c\"/>\n</Root>");
  CHECK(extra.line == 4);
  const corsa::Diagnostic broken =
      error_of(schema, "<Root rate=\"1\">\n<Item name=\"a\">\n</Root>");
  CHECK_THAT(broken.message, Catch::StartsWith("not well-formed XML: "));
}

TEST_CASE("a schema outside the supported subset is a bug, not bad input", "[core][xml][xsd]") {
  CHECK_THROWS_AS(corsa::XsdSchema("<xs:schema"), std::logic_error);
}

TEST_CASE("a DOCTYPE's internal entities are expanded, keeping every line's number",
          "[core][xml]") {
  std::string out;
  const std::string xml =
      "<?xml version=\"1.0\"?>\n<!-- <!DOCTYPE no [ ] > -->\n"
      "<!DOCTYPE a [ <!ENTITY car 'sedan \"blue\"' >\n<!ENTITY car \"second\">\n"
      "<!ELEMENT a ANY> ]>\n<a b=\"&car;&amp;\">&car;<!-- &car; --><![CDATA[&car;]]>&other;</a>\n";
  REQUIRE_FALSE(corsa::expand_internal_entities(xml, out));
  CHECK(out ==
        "<?xml version=\"1.0\"?>\n<!-- <!DOCTYPE no [ ] > -->\n"
        "<!DOCTYPE a " +
            std::string(31, ' ') + "\n" + std::string(22, ' ') + "\n" + std::string(18, ' ') +
            ">\n<a b=\"sedan &quot;blue&quot;&amp;\">sedan &quot;blue&quot;"
            "<!-- &car; --><![CDATA[&car;]]>&other;</a>\n");
  CHECK(std::count(out.begin(), out.end(), '\n') == std::count(xml.begin(), xml.end(), '\n'));

  // No internal subset: nothing to expand.
  REQUIRE_FALSE(corsa::expand_internal_entities("<!DOCTYPE a SYSTEM \"a.dtd\">\n<a/>", out));
  CHECK(out.empty());
  // A '[' or '>' inside the system id's quotes neither opens a subset nor ends the DOCTYPE.
  REQUIRE_FALSE(corsa::expand_internal_entities("<!DOCTYPE a SYSTEM \"a[b.dtd\">\n<a/>", out));
  CHECK(out.empty());
  REQUIRE_FALSE(corsa::expand_internal_entities(
      "<!DOCTYPE a SYSTEM 'a>b.dtd' [<!ENTITY x \"1\">]>\n<a>&x;</a>", out));
  CHECK_THAT(out, Catch::EndsWith("\n<a>1</a>"));
  // A predefined entity declared as XML 1.0 section 4.6 allows keeps its meaning.
  REQUIRE_FALSE(corsa::expand_internal_entities(
      "<!DOCTYPE a [<!ENTITY lt \"&#38;#60;\"><!ENTITY quot '&#34;'>]>\n<a>&lt;&quot;</a>", out));
  CHECK_THAT(out, Catch::EndsWith("\n<a>&lt;&quot;</a>"));

  const auto refused = [&](const std::string& text, int line, const std::string& start) {
    const auto problem = corsa::expand_internal_entities(text, out);
    REQUIRE(problem);
    CHECK(problem->line == line);
    CHECK_THAT(problem->message, Catch::StartsWith(start));
  };
  refused("<!DOCTYPE a [\n<!ENTITY % p \"x\">]>\n<a/>", 2, "a parameter entity is not read");
  refused("<!DOCTYPE a [\n\n<!ENTITY e SYSTEM \"e.xml\">]>\n<a/>", 3,
          "the external entity 'e' is not read");
  // Entities referring to entities could multiply the text without bound.
  refused("<!DOCTYPE a [<!ENTITY x \"1\">\n<!ENTITY y \"&x;&x;\">]>\n<a/>", 2,
          "the value of entity 'y' holds a reference or markup");
  refused("<!DOCTYPE a [\n<!ENTITY amp \"x\">]>\n<a>&amp;</a>", 2,
          "the predefined entity 'amp' may be declared only as \"&#38;#38;\"");
  refused("<!DOCTYPE a [<!ENTITY x \"1\">\n\n<!ENTITY gt 'y'>]>\n<a/>", 3,
          "the predefined entity 'gt' may be declared only as \"&#62;\"");
  refused("<!DOCTYPE a [\n<!ATTLIST a b CDATA \"1\">]>\n<a/>", 2,
          "a DOCTYPE declaration other than <!ENTITY>");
  refused("<!DOCTYPE a [\n<!ENTITY x \"1\">\n", 1, "the DOCTYPE's internal subset is not closed");
  const std::string big_value(1 << 20, 'v');
  std::string many = "<!DOCTYPE a [<!ENTITY x \"" + big_value + "\">]>\n<a>";
  for (int i = 0; i < 17; ++i) many += "&x;";
  refused(many + "</a>", 2, "entity expansion grows the file by more than 16 MiB");
}
