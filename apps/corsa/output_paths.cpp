#include "output_paths.h"

#include "corsa/core/atomic_file.h"

namespace corsa::cli {
namespace {

std::string required_value(const ParsedArgs& parsed, const std::string& option,
                           const std::string& missing) {
  const std::optional<std::string> value = parsed.value(option);
  if (!value || value->empty()) {
    throw UsageError("missing " + option + " " + missing);
  }
  return *value;
}

}  // namespace

std::optional<std::filesystem::path> output_file(const ParsedArgs& parsed,
                                                 const std::string& option) {
  const std::optional<std::string> value = parsed.value(option);
  if (!value) {
    return std::nullopt;
  }
  check_output_file(*value);
  return std::filesystem::path(*value);
}

std::filesystem::path required_output_file(const ParsedArgs& parsed, const std::string& option,
                                           const std::string& missing,
                                           const OutputNameCheck& check_name) {
  const std::filesystem::path path = required_value(parsed, option, missing);
  if (check_name) {
    check_name(path);
  }
  check_output_file(path);
  return path;
}

std::filesystem::path output_folder(const ParsedArgs& parsed, const std::string& option,
                                    const std::filesystem::path& fallback) {
  const std::filesystem::path path = parsed.value_or(option, fallback.string());
  check_output_folder(path);
  return path;
}

std::optional<std::filesystem::path> output_folder(const ParsedArgs& parsed,
                                                   const std::string& option) {
  const std::optional<std::string> value = parsed.value(option);
  if (!value) {
    return std::nullopt;
  }
  check_output_folder(*value);
  return std::filesystem::path(*value);
}

std::filesystem::path required_output_folder(const ParsedArgs& parsed, const std::string& option,
                                             const std::string& missing) {
  const std::filesystem::path path = required_value(parsed, option, missing);
  check_output_folder(path);
  return path;
}

}  // namespace corsa::cli
