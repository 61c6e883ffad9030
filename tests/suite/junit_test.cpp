#include "corsa/suite/junit.h"

#include <tinyxml2.h>

#include <catch2/catch.hpp>

using corsa::suite::junit_xml;
using corsa::suite::SuiteReport;
using corsa::suite::TestOutcome;
using corsa::suite::Verdict;
using corsa::suite::xml_escape;

TEST_CASE("the JUnit report is well-formed XML with one testcase per test", "[suite][junit]") {
  corsa::suite::Suite suite;
  suite.name = "regression";
  SuiteReport report;
  TestOutcome pass;
  pass.name = "calm";
  pass.run.wall_seconds = 0.25;
  TestOutcome fail;
  fail.name = "cut<in>";
  fail.verdict = Verdict::kFailed;
  fail.failures = {"min_ttc is 0.5 s & \"low\"", "golden x deviates"};
  TestOutcome error;
  error.name = "broken";
  error.verdict = Verdict::kError;
  error.error = "a.xosc:3: error: bad\x01";
  report.outcomes = {pass, fail, error};
  report.passed = 1;
  report.failed = 1;
  report.errors = 1;
  report.wall_seconds = 1.5;

  const std::string xml = junit_xml(suite, report);
  tinyxml2::XMLDocument doc;
  REQUIRE(doc.Parse(xml.c_str()) == tinyxml2::XML_SUCCESS);
  const auto* root = doc.RootElement();
  REQUIRE(std::string(root->Name()) == "testsuites");
  const auto* testsuite = root->FirstChildElement("testsuite");
  REQUIRE(testsuite != nullptr);
  CHECK(std::string(testsuite->Attribute("name")) == "regression");
  CHECK(testsuite->IntAttribute("tests") == 3);
  CHECK(testsuite->IntAttribute("failures") == 1);
  CHECK(testsuite->IntAttribute("errors") == 1);
  CHECK(std::string(testsuite->Attribute("time")) == "1.500");
  const auto* first = testsuite->FirstChildElement("testcase");
  REQUIRE(first != nullptr);
  CHECK(std::string(first->Attribute("name")) == "calm");
  CHECK(std::string(first->Attribute("classname")) == "regression");
  CHECK(std::string(first->Attribute("time")) == "0.250");
  CHECK(first->FirstChildElement() == nullptr);
  const auto* second = first->NextSiblingElement("testcase");
  REQUIRE(second != nullptr);
  CHECK(std::string(second->Attribute("name")) == "cut<in>");
  const auto* failure = second->FirstChildElement("failure");
  REQUIRE(failure != nullptr);
  CHECK(std::string(failure->Attribute("message")) == "min_ttc is 0.5 s & \"low\"");
  CHECK(std::string(failure->GetText()) == "min_ttc is 0.5 s & \"low\"\ngolden x deviates\n");
  const auto* third = second->NextSiblingElement("testcase");
  REQUIRE(third != nullptr);
  const auto* err = third->FirstChildElement("error");
  REQUIRE(err != nullptr);
  CHECK(std::string(err->Attribute("message")) == "a.xosc:3: error: bad\xEF\xBF\xBD");
}

TEST_CASE("xml escaping covers markup and control characters", "[suite][junit]") {
  CHECK(xml_escape("a<b>&\"c'") == "a&lt;b&gt;&amp;&quot;c&apos;");
  CHECK(xml_escape("tab\tline\n") == "tab\tline\n");
  CHECK(xml_escape(std::string("nul\0x", 5)) == "nul\xEF\xBF\xBDx");
}
