// `corsa test SUITE`: a regression suite (manifest or folder) with expectations, golden
// trajectories and a JUnit report. The work is in corsa_suite (suite/); this file parses,
// wires and prints.

#include <filesystem>
#include <iostream>

#include "args.h"
#include "commands.h"
#include "corsa/core/atomic_file.h"
#include "corsa/core/diagnostic.h"
#include "corsa/core/progress.h"
#include "corsa/core/strings.h"
#include "corsa/suite/junit.h"
#include "corsa/suite/suite.h"
#include "corsa/suite/suite_run.h"
#include "output_paths.h"
#include "plugin_api.h"
#include "run_options.h"
#include "sweep_options.h"

namespace corsa::cli {
namespace {

ArgParser test_parser() {
  ArgParser parser("test SUITE [options]",
                   "Runs a regression suite: each test runs a scenario and checks its end reason,\n"
                   "collisions, metric bounds and golden trajectory.");
  parser.positional("SUITE", "suite manifest (schemas/suite.xsd) or folder");
  parser.option("--junit", "FILE.xml", "write a JUnit XML report");
  parser.flag("--update-goldens",
              "write the golden trajectories from this run instead of "
              "comparing them");
  parser.flag("--goldens-outside",
              "let --update-goldens write goldens outside the suite folder (a manifest's\n"
              "file=\"../...\" or an absolute path, or through a linked folder)");
  parser.option("-j", "N", "threads (default: every core)");
  parser.option("-o", "DIR", "keep each test's trajectory.csv and summary.json in DIR/<test>/");
  parser.flag("--verbose", "also print the worst golden deviation of every column");
  parser.flag("--quiet", "print only failures and errors");
  parser.flag("--strict", "refuse lenient readings ('(read as ...)' warnings) in every test");
  parser.option("--semantics", "standard|esmini",
                "where the standard's text and esmini differ, read as the standard (default) or "
                "as esmini, in every test; what the standard leaves open is read as esmini "
                "either way (docs/openscenario.md, differences from esmini)");
  parser.epilog(
      "A folder suite uses its suite.xml, or else runs every scenario in it, comparing with\n"
      "goldens/<name>.csv when present. Exit 0 when every test passed, 1 when one failed or could\n"
      "not run, 2 for a malformed suite. --update-goldens writes only inside the suite folder\n"
      "unless --goldens-outside is given.\n"
      "example: corsa test scenarios/suites/regression --junit report.xml");
  return parser;
}

void print_outcome(const suite::TestOutcome& outcome, bool quiet, bool verbose) {
  if (quiet && outcome.verdict == suite::Verdict::kPassed) return;
  std::ostream& out = outcome.verdict == suite::Verdict::kPassed ? std::cout : std::cerr;
  out << std::string(to_string(outcome.verdict))
      << (outcome.verdict == suite::Verdict::kError ? " " : "  ") << outcome.name << " ("
      << format_fixed(outcome.run.wall_seconds, 2) << " s)";
  if (outcome.golden_written) out << ", golden written";
  out << '\n';
  if (outcome.verdict == suite::Verdict::kError) out << "    " << outcome.error << '\n';
  for (const auto& failure : outcome.failures) out << "    " << failure << '\n';
  if (verbose && outcome.golden) {
    for (const auto& d : outcome.golden->deviations) {
      out << "    golden " << d.column << ": worst " << format_double(d.worst);
      if (d.worst > 0.0) out << " at t=" << format_double(d.time) << " s (" << d.entity << ")";
      out << ", tolerance " << format_double(d.tolerance) << '\n';
    }
  }
}

}  // namespace

// A filesystem error (an unreadable suite folder, an unwritable -o) reaches guarded(), which
// reports it as bad input like every command's.
int command_test(std::span<const std::string> args) {
  const ArgParser parser = test_parser();
  const ParsedArgs parsed = parser.parse(split_jobs_option(args));
  if (parsed.help()) {
    parser.print_help(std::cout);
    return kExitOk;
  }
  suite::SuiteOptions options;
  options.geo_projection = proj_plugin_geo_projection();
  if (const auto jobs = parsed.integer("-j")) {
    if (*jobs < 1) throw UsageError("-j expects a positive number of threads");
    options.jobs = static_cast<size_t>(*jobs);
  }
  options.update_goldens = parsed.flag("--update-goldens");
  options.goldens_outside = parsed.flag("--goldens-outside");
  if (options.goldens_outside && !options.update_goldens) {
    throw UsageError("--goldens-outside only goes with --update-goldens");
  }
  options.strict = parsed.flag("--strict");
  if (parsed.value("--semantics")) options.semantics = read_semantics(parsed);
  if (const auto output = output_folder(parsed, "-o")) options.output = *output;
  const std::optional<std::filesystem::path> junit = output_file(parsed, "--junit");
  const bool quiet = parsed.flag("--quiet");
  const bool verbose = parsed.flag("--verbose");
  const suite::Suite suite = suite::load_suite(parsed.positionals().front());
  Diagnostics diagnostics([](const Diagnostic& d) { std::cerr << d.format() << '\n'; });
  ProgressBar progress("test", static_cast<double>(suite.tests.size()), !quiet);
  size_t done = 0;
  const suite::SuiteReport report = suite::run_suite(
      suite, options, diagnostics,
      [&](const suite::TestOutcome&) { progress.update(static_cast<double>(++done)); });
  progress.finish();
  // Printed in the suite's order once all have run, so the log reads the same at any -j.
  for (const auto& outcome : report.outcomes) print_outcome(outcome, quiet, verbose);
  if (junit) {
    write_file_atomic(*junit, suite::junit_xml(suite, report));
  }
  std::cout << suite.name << ": " << report.outcomes.size() << " test"
            << (report.outcomes.size() == 1 ? "" : "s") << ", " << report.passed << " passed, "
            << report.failed << " failed, " << report.errors << " error"
            << (report.errors == 1 ? "" : "s") << " (" << format_fixed(report.wall_seconds, 2)
            << " s)\n";
  return report.ok() ? kExitOk : kExitFailed;
}

}  // namespace corsa::cli
