// libFuzzer target: a suite manifest (schemas/suite.xsd) and a golden trajectory CSV, cut apart
// at the part separator (fuzz_parts.h). The manifest "lives" in the bundled regression suite, so
// that its scenario and golden references resolve against real files; the golden is checked as
// `corsa test` checks every golden before running, then compared with a real trajectory. Bad input
// must end in corsa::InputError.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

#include "corsa/core/atomic_file.h"
#include "corsa/core/diagnostic.h"
#include "corsa/suite/golden.h"
#include "corsa/suite/suite.h"
#include "fuzz_parts.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  namespace fs = std::filesystem;
  static const fs::path kManifest =
      fs::path(CORSA_SOURCE_DIR) / "scenarios" / "suites" / "regression" / "fuzz_suite.xml";
  static const fs::path kScratch = corsa::fuzz::scratch_folder("suite_manifest_fuzz");
  const auto parts = corsa::fuzz::split_parts(data, size, 2);
  try {
    const corsa::suite::Suite suite = corsa::suite::parse_suite_manifest(parts[0], kManifest);
    for (const auto& test : suite.tests) {
      (void)corsa::suite::to_string(test.expect.metrics.empty() ? corsa::suite::Metric::kMinTtc
                                                                : test.expect.metrics[0].metric);
    }
  } catch (const corsa::InputError&) {
    // Expected for bad input.
  }
  const fs::path golden = kScratch / "golden.csv";
  corsa::fuzz::write_bytes(golden, parts[1]);
  try {
    corsa::suite::check_golden_file(golden);
    // A golden that passed the check is compared with a real trajectory, as a test does.
    static const std::string kActual =
        corsa::read_file(kManifest.parent_path() / "goldens" / "cut_in.csv");
    (void)corsa::suite::compare_trajectories(parts[1], kActual, corsa::suite::Tolerances{});
  } catch (const corsa::InputError&) {
  }
  return 0;
}
