#include <algorithm>
#include <catch2/catch.hpp>
#include <filesystem>
#include <string>
#include <variant>
#include <vector>

#include "corsa/xosc/scenario.h"
#include "shared_data.h"

namespace fs = std::filesystem;
using namespace corsa::xosc;

using corsa::test::kAsamExamples;

namespace {

std::vector<fs::path> all_xosc_files() {
  std::vector<fs::path> files;
  for (const auto& entry : fs::recursive_directory_iterator(kAsamExamples)) {
    if (entry.is_regular_file() && entry.path().extension() == ".xosc") {
      files.push_back(entry.path());
    }
  }
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace

TEST_CASE("every ASAM OpenSCENARIO 1.3 example, catalog and parameter set loads without error",
          "[xosc][conformance]") {
  const auto files = all_xosc_files();
  REQUIRE(files.size() == 20);  // 14 scenarios, 2 parameter sets, 4 catalogs
  size_t scenarios = 0;
  size_t catalogs = 0;
  size_t distributions = 0;
  for (const auto& file : files) {
    INFO(file.string());
    corsa::Diagnostics diagnostics;
    Document document;
    REQUIRE_NOTHROW(document = load_document(file, {}, diagnostics));
    CHECK_FALSE(diagnostics.has_errors());
    scenarios += std::holds_alternative<Scenario>(document) ? 1 : 0;
    catalogs += std::holds_alternative<Catalog>(document) ? 1 : 0;
    distributions += std::holds_alternative<ParameterValueDistribution>(document) ? 1 : 0;
    if (const auto* scenario = std::get_if<Scenario>(&document)) {
      CHECK(scenario->header.rev_major == 1);
      CHECK_FALSE(scenario->entities.objects.empty());
      if (scenario->road_network.logic_file) {
        CHECK(scenario->road_network.logic_file_path.is_absolute());
        CHECK(fs::is_regular_file(scenario->road_network.logic_file_path));
      }
    }
  }
  CHECK(scenarios == 14);
  CHECK(catalogs == 4);
  CHECK(distributions == 2);
}

TEST_CASE("the only warnings on the ASAM examples are deprecations and missing .osgb files",
          "[xosc][conformance]") {
  for (const auto& file : all_xosc_files()) {
    INFO(file.string());
    corsa::Diagnostics diagnostics;
    load_document(file, {}, diagnostics);
    for (const auto& diagnostic : diagnostics.all()) {
      INFO(diagnostic.format());
      const bool expected = diagnostic.message.find("deprecated") != std::string::npos ||
                            diagnostic.message.find(".osgb") != std::string::npos;
      CHECK(expected);
    }
  }
}
