#pragma once

// Loads a small scenario leniently and strictly and checks the `(read as ...)` warning and its
// --strict error (the lenient-reading tests of corsa_xosc).

#include <catch2/catch.hpp>
#include <optional>
#include <string>
#include <vector>

#include "corsa/xosc/scenario.h"
#include "scenario_text.h"
#include "temp_dir.h"

namespace corsa::test {

struct Loaded {
  std::optional<xosc::Scenario> scenario;
  std::vector<corsa::Diagnostic> warnings;
  std::vector<corsa::Diagnostic> errors;
};

inline Loaded lenient_load(const TempDir& dir, const std::string& xml, bool strict = false,
                           bool esmini_booleans = false) {
  write_text(dir.path() / "map.xodr", minimal_xodr());
  write_text(dir.path() / "s.xosc", xml);
  corsa::Diagnostics diagnostics;
  Loaded loaded;
  xosc::LoadOptions options;
  options.strict = strict;
  options.esmini_booleans = esmini_booleans;
  try {
    loaded.scenario = xosc::load_scenario(dir.path() / "s.xosc", options, diagnostics);
  } catch (const corsa::InputError& error) {
    loaded.errors = error.diagnostics();
  }
  for (const auto& diagnostic : diagnostics.all()) {
    if (diagnostic.severity == corsa::Severity::kWarning) loaded.warnings.push_back(diagnostic);
  }
  return loaded;
}

/// The warning containing `text`, or a failed check.
inline corsa::Diagnostic warning_with(const Loaded& loaded, const std::string& text) {
  for (const auto& warning : loaded.warnings) {
    if (warning.message.find(text) != std::string::npos) return warning;
  }
  FAIL("no warning containing '" << text << "'");
  return {};
}

/// Loads leniently (a warning with `(read as`, at `line`) and strictly (an error at `line`).
inline void check_both_ways(const std::string& xml, const std::string& text, int line) {
  TempDir dir;
  const Loaded lenient = lenient_load(dir, xml);
  INFO((lenient.errors.empty() ? std::string() : lenient.errors[0].format()));
  REQUIRE(lenient.errors.empty());
  const auto warning = warning_with(lenient, text);
  CHECK(warning.line == line);
  CHECK_THAT(warning.message, Catch::Contains("(read as "));
  const Loaded strict = lenient_load(dir, xml, true);
  REQUIRE(!strict.errors.empty());
  CHECK(strict.errors[0].line == line);
  CHECK_THAT(strict.errors[0].message, Catch::Contains(text));
  CHECK_THAT(strict.errors[0].message, Catch::Contains("--strict"));
}

}  // namespace corsa::test
