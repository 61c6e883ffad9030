#include "corsa/suite/suite_run.h"

#include <sys/stat.h>

#include <chrono>
#include <map>
#include <memory>
#include <mutex>
#include <optional>

#include "corsa/core/atomic_file.h"
#include "corsa/suite/expectations.h"
#include "corsa/suite/golden.h"
#include "corsa/sweep/parallel.h"
#include "corsa/sweep/shared_inputs.h"

namespace corsa::suite {
namespace {

namespace fs = std::filesystem;

// One SharedInputs per scenario file, so tests of one scenario share its map and catalogs; a
// file that cannot be read is that test's error.
class InputsByScenario {
 public:
  InputsByScenario(const Suite& suite, Diagnostics& diagnostics) {
    for (const TestCase& test : suite.tests) {
      if (inputs_.count(test.scenario) != 0 || errors_.count(test.scenario) != 0) continue;
      try {
        inputs_.emplace(test.scenario,
                        std::make_unique<sweep::SharedInputs>(test.scenario, diagnostics));
      } catch (const InputError& error) {
        errors_.emplace(test.scenario, error.brief());
      }
    }
  }
  sweep::SharedInputs* find(const fs::path& scenario, std::string& error) {
    const auto found = inputs_.find(scenario);
    if (found != inputs_.end()) return found->second.get();
    error = errors_.at(scenario);
    return nullptr;
  }

 private:
  std::map<fs::path, std::unique_ptr<sweep::SharedInputs>> inputs_;
  std::map<fs::path, std::string> errors_;
};

// The path of `file` below `folder`, or nothing when it lies outside (compared lexically, as
// absolute paths).
std::optional<fs::path> path_inside(const fs::path& folder, const fs::path& file) {
  const fs::path base = fs::absolute(folder.empty() ? fs::path(".") : folder).lexically_normal();
  const fs::path relative = fs::absolute(file).lexically_normal().lexically_relative(base);
  if (relative.empty() || relative.is_absolute() || *relative.begin() == "..") return std::nullopt;
  return relative;
}

// The first folder on the way from `folder` to `relative` that is a symbolic link, if any.
std::optional<fs::path> linked_folder(const fs::path& folder, const fs::path& relative) {
  fs::path path = folder;
  for (const fs::path& part : relative.parent_path()) {
    path /= part;
    struct stat status {};
    if (::lstat(path.c_str(), &status) != 0) return std::nullopt;  // made when written
    if (S_ISLNK(status.st_mode)) return path;
  }
  return std::nullopt;
}

// --update-goldens writes inside the suite folder only (unless goldens_outside): every golden
// that would be written elsewhere, by its path or through a linked folder, is reported at its
// manifest line before any test runs.
void check_goldens_inside(const Suite& suite, const std::vector<TestCase>& tests,
                          Diagnostics& diagnostics) {
  const std::string manifest =
      suite.manifest.empty() ? suite.folder.string() : suite.manifest.string();
  std::vector<Diagnostic> errors;
  for (const TestCase& test : tests) {
    if (!test.golden) continue;
    const GoldenSpec& golden = *test.golden;
    const auto relative = path_inside(suite.folder, golden.file);
    if (!relative) {
      errors.push_back(make_error(
          manifest, golden.line,
          "golden file " + golden.file.string() + " of test '" + test.name +
              "' is outside the suite folder; --update-goldens writes only inside it (pass "
              "--goldens-outside to write there)"));
    } else if (const auto link = linked_folder(suite.folder, *relative)) {
      errors.push_back(make_error(manifest, golden.line,
                                  "golden file " + golden.file.string() + " of test '" + test.name +
                                      "' lies in " + link->string() +
                                      ", a symbolic link; --update-goldens writes only into "
                                      "real folders of the suite (pass --goldens-outside to "
                                      "write there)"));
    }
  }
  if (errors.empty()) return;
  for (size_t i = 0; i + 1 < errors.size(); ++i) diagnostics.add(errors[i]);
  throw InputError(errors.back());
}

void judge_golden(const TestCase& test, const SuiteOptions& options, const Suite& suite,
                  TestOutcome& outcome) {
  if (!test.golden) return;
  if (options.update_goldens) {
    const auto relative = path_inside(suite.folder, test.golden->file);
    if (options.goldens_outside || !relative) {
      fs::create_directories(test.golden->file.parent_path());
    } else {
      create_folder_inside(suite.folder.empty() ? fs::path(".") : suite.folder,
                           relative->parent_path());
    }
    write_file_atomic(test.golden->file, outcome.run.trajectory_text);
    outcome.golden_written = true;
    return;
  }
  std::error_code error;
  if (!fs::is_regular_file(test.golden->file, error)) {
    outcome.failures.push_back("golden file " + test.golden->file.string() +
                               " does not exist (write it with --update-goldens)");
    return;
  }
  outcome.golden = compare_trajectories(read_file(test.golden->file), outcome.run.trajectory_text,
                                        test.golden->tolerances);
  for (const auto& failure : outcome.golden->failures) {
    outcome.failures.push_back("golden " + test.golden->file.filename().string() + ": " + failure);
  }
}

TestOutcome run_test(const TestCase& test, const SuiteOptions& options, const Suite& suite,
                     InputsByScenario& inputs, Diagnostics& diagnostics) {
  TestOutcome outcome;
  outcome.name = test.name;
  sweep::SharedInputs* shared = inputs.find(test.scenario, outcome.error);
  if (shared == nullptr) {
    outcome.verdict = Verdict::kError;
    return outcome;
  }
  sweep::VariantSpec spec{test.parameters, test.simulation, test.ego};
  spec.simulation.geo_projection = options.geo_projection;
  spec.simulation.strict = spec.simulation.strict || options.strict;
  if (options.semantics) spec.simulation.semantics = *options.semantics;
  sweep::VariantOutputs outputs;
  if (options.output) {
    const fs::path folder = *options.output / test.name;
    fs::create_directories(folder);
    outputs.trajectory = folder / "trajectory.csv";
    outputs.summary = folder / "summary.json";
  }
  outputs.keep_trajectory_text = test.golden.has_value();
  outputs.record_every = test.golden ? test.golden->every : 1;
  outcome.run = sweep::run_variant(*shared, spec, outputs, diagnostics);
  if (!outcome.run.ok()) {
    outcome.verdict = Verdict::kError;
    outcome.error = outcome.run.error;
    return outcome;
  }
  outcome.failures = check_expectations(test.expect, outcome.run);
  judge_golden(test, options, suite, outcome);
  outcome.verdict = outcome.failures.empty() ? Verdict::kPassed : Verdict::kFailed;
  return outcome;
}

}  // namespace

std::string_view to_string(Verdict verdict) {
  switch (verdict) {
    case Verdict::kPassed:
      return "PASS";
    case Verdict::kFailed:
      return "FAIL";
    case Verdict::kError:
      return "ERROR";
  }
  return "ERROR";
}

SuiteReport run_suite(const Suite& suite, const SuiteOptions& options, Diagnostics& diagnostics,
                      const TestFinished& finished) {
  const auto start = std::chrono::steady_clock::now();
  std::vector<TestCase> tests = suite.tests;
  if (options.update_goldens && suite.manifest.empty()) {
    // A folder suite compares with goldens/<stem>.csv when it exists; updating writes them all.
    for (TestCase& test : tests) {
      if (!test.golden)
        test.golden = GoldenSpec{suite.folder / "goldens" / (test.name + ".csv"), 10, {}, 0};
    }
  }
  if (options.update_goldens && !options.goldens_outside) {
    check_goldens_inside(suite, tests, diagnostics);
  }
  if (!options.update_goldens) {
    // A golden that exists but cannot be read is bad input of the suite: found before any test
    // runs (a missing one is the test's failure, with a hint to write it).
    for (const TestCase& test : tests) {
      std::error_code error;
      if (test.golden && fs::is_regular_file(test.golden->file, error)) {
        check_golden_file(test.golden->file);
      }
    }
  }
  InputsByScenario inputs(suite, diagnostics);
  SuiteReport report;
  report.outcomes.resize(tests.size());
  std::mutex finished_mutex;
  sweep::parallel_for(tests.size(), options.jobs, [&](size_t i) {
    report.outcomes[i] = run_test(tests[i], options, suite, inputs, diagnostics);
    if (finished) {
      std::lock_guard lock(finished_mutex);
      finished(report.outcomes[i]);
    }
  });
  for (const TestOutcome& outcome : report.outcomes) {
    report.passed += outcome.verdict == Verdict::kPassed ? 1 : 0;
    report.failed += outcome.verdict == Verdict::kFailed ? 1 : 0;
    report.errors += outcome.verdict == Verdict::kError ? 1 : 0;
  }
  report.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return report;
}

}  // namespace corsa::suite
