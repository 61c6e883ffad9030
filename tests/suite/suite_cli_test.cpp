// `corsa test` end to end: the bundled regression suite, a failing suite with its JUnit report,
// updating goldens, and malformed manifests.

#include <tinyxml2.h>

#include <catch2/catch.hpp>
#include <filesystem>

#include "corsa/core/atomic_file.h"
#include "run_corsa.h"
#include "temp_dir.h"

namespace fs = std::filesystem;
using corsa::read_file;
using corsa::write_file_atomic;
using corsa::test::run_corsa;
using corsa::test::TempDir;

namespace {

const fs::path kScenario =
    fs::path(CORSA_SOURCE_DIR) / "tests" / "sweep" / "fixtures" / "follow.xosc";

std::string manifest(const std::string& tests) {
  return "<?xml version=\"1.0\"?>\n<Suite version=\"1\" name=\"tmp\" dt=\"0.02\">\n" + tests +
         "</Suite>\n";
}

std::string test(const std::string& name, const std::string& body) {
  return "  <Test name=\"" + name + "\" scenario=\"" + kScenario.string() + "\">\n" + body +
         "  </Test>\n";
}

}  // namespace

TEST_CASE("the bundled regression suite passes and writes a JUnit report", "[suite][cli]") {
  TempDir dir;
  const fs::path junit = dir.path() / "report.xml";
  const auto result = run_corsa({"test", "scenarios/suites/regression", "--junit", junit.string()});
  INFO(result.out << result.err);
  REQUIRE(result.exit_code == 0);
  CHECK(result.out.find("regression: ") != std::string::npos);
  CHECK(result.out.find(" 0 failed, 0 errors") != std::string::npos);
  tinyxml2::XMLDocument doc;
  REQUIRE(doc.LoadFile(junit.c_str()) == tinyxml2::XML_SUCCESS);
  const auto* suite = doc.RootElement()->FirstChildElement("testsuite");
  REQUIRE(suite != nullptr);
  CHECK(suite->IntAttribute("tests") >= 4);
  CHECK(suite->IntAttribute("failures") == 0);
}

TEST_CASE("a failing test exits 1 and its JUnit testcase carries the failure", "[suite][cli]") {
  TempDir dir;
  write_file_atomic(
      dir.path() / "suite.xml",
      manifest(test("fine", "    <Expect collision=\"false\"/>\n") +
               test("too_strict",
                    "    <Expect>\n      <Metric name=\"min_distance\" min=\"100\"/>\n"
                    "    </Expect>\n") +
               test("bad_parameter", "    <Parameter name=\"Nope\" value=\"1\"/>\n")));
  const fs::path junit = dir.path() / "junit.xml";
  const auto result =
      run_corsa({"test", dir.path().string(), "--junit", junit.string(), "-j", "2"});
  CHECK(result.exit_code == 1);
  CHECK(result.out.find("PASS  fine") != std::string::npos);
  CHECK(result.err.find("FAIL  too_strict") != std::string::npos);
  CHECK(result.err.find("min_distance is ") != std::string::npos);
  CHECK(result.err.find("below the minimum 100 m") != std::string::npos);
  CHECK(result.err.find("ERROR bad_parameter") != std::string::npos);
  CHECK(result.out.find("tmp: 3 tests, 1 passed, 1 failed, 1 error") != std::string::npos);
  tinyxml2::XMLDocument doc;
  REQUIRE(doc.LoadFile(junit.c_str()) == tinyxml2::XML_SUCCESS);
  const auto* suite = doc.RootElement()->FirstChildElement("testsuite");
  CHECK(suite->IntAttribute("failures") == 1);
  CHECK(suite->IntAttribute("errors") == 1);
  const auto* strict = suite->FirstChildElement("testcase")->NextSiblingElement("testcase");
  REQUIRE(strict->FirstChildElement("failure") != nullptr);
  CHECK(std::string(strict->FirstChildElement("failure")->Attribute("message"))
            .find("min_distance") == 0);
  const auto* bad = strict->NextSiblingElement("testcase");
  REQUIRE(bad->FirstChildElement("error") != nullptr);
  CHECK(std::string(bad->FirstChildElement("error")->Attribute("message")).find("Nope") !=
        std::string::npos);
}

TEST_CASE("--update-goldens writes goldens that the next run matches", "[suite][cli][golden]") {
  TempDir dir;
  write_file_atomic(dir.path() / "suite.xml",
                    manifest(test("follow", "    <Golden every=\"25\"/>\n")));
  const auto missing = run_corsa({"test", dir.path().string()});
  CHECK(missing.exit_code == 1);
  CHECK(missing.err.find("does not exist (write it with --update-goldens)") != std::string::npos);
  const auto update = run_corsa({"test", dir.path().string(), "--update-goldens"});
  REQUIRE(update.exit_code == 0);
  CHECK(update.out.find("golden written") != std::string::npos);
  const fs::path golden = dir.path() / "goldens" / "follow.csv";
  REQUIRE(fs::exists(golden));
  CHECK(read_file(golden).rfind("time,entity,x,y,z,h,p,r,speed,road,lane,s,t\n0,Ego,", 0) == 0);
  const auto again = run_corsa({"test", dir.path().string(), "--verbose"});
  CHECK(again.exit_code == 0);
  CHECK(again.out.find("golden x: worst 0, tolerance 0.01") != std::string::npos);

  // A golden from another run fails with the worst deviation named.
  std::string text = read_file(golden);
  write_file_atomic(golden, text.substr(0, text.rfind('\n', text.size() - 2) + 1));
  const auto shorter = run_corsa({"test", dir.path().string()});
  CHECK(shorter.exit_code == 1);
  CHECK(shorter.err.find("golden follow.csv: the run has ") != std::string::npos);
}

TEST_CASE("a folder without manifest runs every scenario in it", "[suite][cli][folder]") {
  const auto result = run_corsa({"test", "tests/sweep/fixtures", "--quiet"});
  CHECK(result.exit_code == 0);
  CHECK(result.out.find("fixtures: 1 test, 1 passed") != std::string::npos);
}

TEST_CASE("a malformed manifest is located and exits 2", "[suite][cli][errors]") {
  TempDir dir;
  write_file_atomic(dir.path() / "suite.xml",
                    "<Suite version=\"1\" name=\"x\">\n  <Test name=\"a\" scenario=\"" +
                        kScenario.string() +
                        "\">\n    <Expect endReason=\"never\"/>\n  </Test>\n"
                        "</Suite>\n");
  const auto result = run_corsa({"test", (dir.path() / "suite.xml").string()});
  CHECK(result.exit_code == 2);
  CHECK(result.err.find("suite.xml:3: error: attribute 'endReason' of <Expect> is 'never'") !=
        std::string::npos);
  const auto missing = run_corsa({"test", (dir.path() / "nothing").string()});
  CHECK(missing.exit_code == 2);
}
