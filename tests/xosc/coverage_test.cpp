// docs/osc-coverage.md lists every OpenSCENARIO 1.3 element with its status; this keeps it in
// step with the element list the loader itself checks documents against.

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "corsa/core/strings.h"
#include "corsa/xosc/schema.h"

using namespace corsa::xosc;

namespace {

// Rows of the table: "| `Element` | status | notes |".
std::map<std::string, std::string> documented_elements() {
  std::ifstream in(std::filesystem::path(CORSA_SOURCE_DIR) / "docs" / "osc-coverage.md");
  REQUIRE(in.good());
  std::map<std::string, std::string> rows;
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("| `", 0) != 0) continue;
    const auto cells = corsa::split(line, '|');
    REQUIRE(cells.size() >= 4);
    std::string name(corsa::trim(cells[1]));
    name = name.substr(1, name.size() - 2);  // strip the backquotes
    const std::string status(corsa::trim(cells[2]));
    CHECK(rows.emplace(name, status).second);
  }
  return rows;
}

}  // namespace

TEST_CASE("docs/osc-coverage.md lists exactly the elements the loader knows, with their status",
          "[xosc][coverage]") {
  const auto documented = documented_elements();
  const auto known = known_elements();
  CHECK(known.size() > 250);
  for (const auto& element : known) {
    INFO(element.name);
    const auto found = documented.find(std::string(element.name));
    REQUIRE(found != documented.end());
    // Which parsed elements are also performed is the engine's to say (tests/engine/coverage_test).
    if (element.support == Support::kParsed) {
      CHECK((found->second == "parsed" || found->second == "performed"));
    } else {
      CHECK(found->second == "not yet");
    }
  }
  for (const auto& [name, status] : documented) {
    INFO(name);
    bool present = false;
    for (const auto& element : known) present = present || element.name == name;
    CHECK(present);
  }
}

TEST_CASE("the element list is sorted and has no duplicates", "[xosc][coverage]") {
  const auto known = known_elements();
  for (size_t i = 1; i < known.size(); ++i) {
    CHECK(known[i - 1].name < known[i].name);
  }
}
