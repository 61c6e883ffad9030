// docs/osc-coverage.md says "performed" for exactly the elements the engine acts on
// (engine::performed_elements()), and each of them is one the loader reads.

#include <algorithm>
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include "corsa/core/strings.h"
#include "corsa/engine/performed_elements.h"
#include "corsa/xosc/schema.h"

namespace {

// Names of the table rows "| `Element` | performed | notes |".
std::set<std::string> documented_performed() {
  std::ifstream in(std::filesystem::path(CORSA_SOURCE_DIR) / "docs" / "osc-coverage.md");
  REQUIRE(in.good());
  std::set<std::string> names;
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("| `", 0) != 0) continue;
    const auto cells = corsa::split(line, '|');
    REQUIRE(cells.size() >= 4);
    std::string name(corsa::trim(cells[1]));
    if (corsa::trim(cells[2]) == "performed") names.insert(name.substr(1, name.size() - 2));
  }
  return names;
}

}  // namespace

TEST_CASE("docs/osc-coverage.md marks performed exactly the elements the engine performs",
          "[engine][coverage]") {
  const auto performed = corsa::engine::performed_elements();
  const std::set<std::string> engine(performed.begin(), performed.end());
  CHECK(engine.size() == performed.size());
  CHECK(documented_performed() == engine);
}

TEST_CASE("every performed element is one the loader reads, in sorted order",
          "[engine][coverage]") {
  const auto performed = corsa::engine::performed_elements();
  const auto known = corsa::xosc::known_elements();
  for (size_t i = 0; i < performed.size(); ++i) {
    INFO(performed[i]);
    if (i > 0) CHECK(performed[i - 1] < performed[i]);
    const bool read = std::any_of(known.begin(), known.end(), [&](const auto& element) {
      return element.name == performed[i] && element.support == corsa::xosc::Support::kParsed;
    });
    CHECK(read);
  }
}
