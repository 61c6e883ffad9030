// Every variation file of the ASAM ALKS scenarios and both parameter sets of the ASAM 1.3
// examples sweep without a failed variant. The largest ALKS file has 52,500 variants; the test
// runs one shard of each (every N-th variant, so the whole grid is spread over), at most
// kVariantsPerFile of them; `corsa sweep FILE` runs them all.

#include <catch2/catch.hpp>
#include <cmath>
#include <string>

#include "conformance_files.h"
#include "corsa/sweep/sweep.h"
#include "corsa/xosc/scenario.h"
#include "temp_dir.h"

namespace fs = std::filesystem;
using corsa::test::kConformanceDir;
using corsa::test::xosc_files;

namespace {

constexpr size_t kVariantsPerFile = 24;

struct Swept {
  corsa::sweep::SweepReport report;
  size_t plan_size = 0;
};

Swept sweep_sample(const fs::path& file) {
  corsa::Diagnostics diagnostics;
  const auto distribution = corsa::xosc::load_distribution(file, diagnostics);
  Swept swept;
  const auto plan =
      corsa::sweep::VariantPlan::from_distribution(file, distribution, {}, /*default_seed=*/0);
  swept.plan_size = plan.size();
  corsa::test::TempDir dir;
  corsa::sweep::SweepOptions options;
  options.output = dir.path() / "sweep";
  options.jobs = 2;
  options.trajectories = false;
  options.shard.count =
      std::max<size_t>(1, (plan.size() + kVariantsPerFile - 1) / kVariantsPerFile);
  swept.report = corsa::sweep::run_sweep(plan, options, diagnostics);
  return swept;
}

std::string failures(const corsa::sweep::SweepReport& report) {
  std::string text;
  for (const auto& [index, error] : report.first_failures) {
    text += "variant " + std::to_string(index) + ": " + error + "\n";
  }
  return text;
}

}  // namespace

TEST_CASE("every ALKS variation file sweeps without a failed variant", "[conformance][alks]") {
  const auto files =
      xosc_files(kConformanceDir / "alks" / "Variations", "<ParameterValueDistribution");
  REQUIRE(files.size() == 15);  // 4.4_2 has none of its own; 4.3_2 has a reference set too
  size_t ran = 0;
  size_t skipped = 0;
  for (const auto& file : files) {
    INFO(file.filename().string());
    const Swept swept = sweep_sample(file);
    INFO(failures(swept.report));
    CHECK(swept.plan_size > 0);
    CHECK(swept.report.failed == 0);
    CHECK(swept.report.variants > 0);
    ran += swept.report.variants;
    skipped += swept.report.skipped;
  }
  // The files say their ranges also give combinations outside the scenarios' constraints, to be
  // discarded: some are skipped, most run.
  CHECK(skipped > 0);
  CHECK(skipped < ran / 2);
}

TEST_CASE("both ASAM parameter sets sweep without a failed variant", "[conformance][asam]") {
  const auto files = xosc_files(kConformanceDir / "asam-osc-1.3", "<ParameterValueDistribution");
  REQUIRE(files.size() == 2);
  for (const auto& file : files) {
    INFO(file.filename().string());
    const Swept swept = sweep_sample(file);
    INFO(failures(swept.report));
    CHECK(swept.report.failed == 0);
    CHECK(swept.report.skipped == 0);
    CHECK(swept.report.variants > 0);
    CHECK(swept.report.variants <= kVariantsPerFile);
  }
}
