#pragma once

// Loads a small scenario leniently and strictly and checks the `(read as ...)` warning and its
// --strict error (the lenient-reading tests of corsa_xosc).

#include <catch2/catch.hpp>
#include <optional>
#include <string>
#include <utility>
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

/// Loads `xml` leniently in a folder of its own and requires that it loaded without an error
/// (the first shown otherwise).
inline Loaded load_without_errors(const std::string& xml, bool esmini_booleans = false) {
  TempDir dir;
  Loaded loaded = lenient_load(dir, xml, false, esmini_booleans);
  INFO((loaded.errors.empty() ? std::string() : loaded.errors[0].format()));
  REQUIRE(loaded.errors.empty());
  REQUIRE(loaded.scenario);
  return loaded;
}

/// load_without_errors, requiring a warning containing `text` (at `line` when given): the
/// scenario read.
inline xosc::Scenario load_with_warning(const std::string& xml, const std::string& text,
                                        int line = 0) {
  Loaded loaded = load_without_errors(xml);
  const auto warning = warning_with(loaded, text);
  if (line > 0) CHECK(warning.line == line);
  return std::move(*loaded.scenario);
}

/// Loads leniently (a warning with `(read as`, at `line`) and strictly (an error at `line`);
/// the lenient load.
inline Loaded check_both_ways(const std::string& xml, const std::string& text, int line) {
  Loaded lenient = load_without_errors(xml);
  const auto warning = warning_with(lenient, text);
  CHECK(warning.line == line);
  CHECK_THAT(warning.message, Catch::Contains("(read as "));
  TempDir dir;
  const Loaded strict = lenient_load(dir, xml, true);
  REQUIRE(!strict.errors.empty());
  CHECK(strict.errors[0].line == line);
  CHECK_THAT(strict.errors[0].message, Catch::Contains(text));
  CHECK_THAT(strict.errors[0].message, Catch::Contains("--strict"));
  return lenient;
}

}  // namespace corsa::test
