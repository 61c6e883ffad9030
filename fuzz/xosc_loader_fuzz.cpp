// libFuzzer target: any bytes as an OpenSCENARIO document (scenario, catalog or distribution).
// The document "lives" in the ASAM example folder so that its catalog references resolve
// against real catalogs. Bad input must end in corsa::InputError, never a crash or a hang.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string_view>
#include <variant>

#include "corsa/core/diagnostic.h"
#include "corsa/xosc/scenario.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const std::filesystem::path kPath =
      std::filesystem::path(CORSA_SHARED_DIR) / "conformance" / "asam-osc-1.3" / "fuzz.xosc";
  corsa::xosc::LoadOptions options;
  options.check_files = false;
  corsa::Diagnostics diagnostics;
  try {
    const auto document = corsa::xosc::parse_document(
        std::string_view(reinterpret_cast<const char*>(data), size), kPath, options, diagnostics);
    if (const auto* distribution =
            std::get_if<corsa::xosc::ParameterValueDistribution>(&document)) {
      // Enumerate a few variants too (bounded: a fuzzed count may be huge).
      const size_t count = corsa::xosc::variant_count(*distribution);
      for (size_t i = 0; i < count && i < 8; ++i) {
        corsa::xosc::variant_at(*distribution, i);
      }
    }
  } catch (const corsa::InputError&) {
    // Expected for bad input.
  }
  return 0;
}
