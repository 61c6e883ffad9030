#include "corsa/core/diagnostic.h"

#include <catch2/catch.hpp>
#include <thread>
#include <vector>

TEST_CASE("a diagnostic prints as file:line: severity: message", "[core][diagnostic]") {
  SECTION("with a line") {
    const auto d = corsa::make_error("cut_in.xosc", 42, "unknown entity 'Ego2'");
    CHECK(d.format() == "cut_in.xosc:42: error: unknown entity 'Ego2'");
  }
  SECTION("with an element path") {
    const auto d = corsa::make_warning("m.xodr", 7, "unknown element 'foo'", "OpenDRIVE/road");
    CHECK(d.format() == "m.xodr:7: warning: unknown element 'foo' [in OpenDRIVE/road]");
  }
  SECTION("with a DBF record instead of a line") {
    corsa::Diagnostic d = corsa::make_error("A2_LINK.dbf", 0, "missing field LaneNo");
    d.record = 17;
    CHECK(d.format() == "A2_LINK.dbf: record 17: error: missing field LaneNo");
  }
  SECTION("without a file") {
    const auto d = corsa::make_error("", 0, "no scenario given");
    CHECK(d.format() == "error: no scenario given");
  }
}

TEST_CASE("InputError carries its diagnostic and says where in what()", "[core][diagnostic]") {
  try {
    throw corsa::InputError(corsa::make_error("a.xosc", 3, "bad"));
  } catch (const corsa::InputError& error) {
    CHECK(std::string(error.what()) == "a.xosc:3: error: bad");
    CHECK(error.diagnostic().line == 3);
  }
}

TEST_CASE("warn-once keeps only the first diagnostic of a key", "[core][diagnostic]") {
  int heard = 0;
  corsa::Diagnostics diagnostics([&](const corsa::Diagnostic&) { ++heard; });
  CHECK(diagnostics.add_once("unknown:foo", corsa::make_warning("f", 1, "unknown foo")));
  CHECK_FALSE(diagnostics.add_once("unknown:foo", corsa::make_warning("f", 9, "unknown foo")));
  diagnostics.add(corsa::make_error("f", 2, "bad"));
  CHECK(diagnostics.size() == 2);
  CHECK(heard == 2);
  CHECK(diagnostics.count(corsa::Severity::kWarning) == 1);
  CHECK(diagnostics.has_errors());
  CHECK(diagnostics.all().front().line == 1);
}

TEST_CASE("diagnostics can be added from several threads", "[core][diagnostic]") {
  corsa::Diagnostics diagnostics;
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t) {
    threads.emplace_back([&] {
      for (int i = 0; i < 1000; ++i) {
        diagnostics.add(corsa::make_warning("f", i, "w"));
        diagnostics.add_once(std::to_string(i), corsa::make_warning("f", i, "once"));
      }
    });
  }
  for (auto& thread : threads) {
    thread.join();
  }
  CHECK(diagnostics.size() == 5000);
}
