#pragma once

// Folders of the shared data the tests read (`../shared` beside the source folder).

#include <filesystem>

namespace corsa::test {

/// The ASAM OpenSCENARIO 1.3 example scenarios.
inline const std::filesystem::path kAsamExamples =
    std::filesystem::path(CORSA_SHARED_DIR) / "conformance" / "asam-osc-1.3";

}  // namespace corsa::test
