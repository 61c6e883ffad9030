#pragma once

#include <string_view>

namespace corsa {

/// Corsa's version, "major.minor.patch", from the top-level CMake project.
std::string_view version();

}  // namespace corsa
