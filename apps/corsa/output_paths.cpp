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

/// Levels of folders below an output folder that Corsa writes into: a sweep's variants/<i>/, a
/// dataset's kitti/image_2/.
constexpr int kOutputFolderDepth = 2;

/// What a killed run left: Corsa's own temporaries no live process holds (see AtomicFile), in
/// the output file's folder, or in the output folder and the folders Corsa writes below it.
void clean_after_killed_runs(const std::filesystem::path& folder, int depth) {
  remove_stale_temporaries(folder.empty() ? std::filesystem::path(".") : folder, depth);
}

}  // namespace

std::optional<std::filesystem::path> output_file(const ParsedArgs& parsed,
                                                 const std::string& option) {
  const std::optional<std::string> value = parsed.value(option);
  if (!value) {
    return std::nullopt;
  }
  check_output_file(*value);
  clean_after_killed_runs(std::filesystem::path(*value).parent_path(), 0);
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
  clean_after_killed_runs(path.parent_path(), 0);
  return path;
}

std::filesystem::path output_folder(const ParsedArgs& parsed, const std::string& option,
                                    const std::filesystem::path& fallback) {
  const std::filesystem::path path = parsed.value_or(option, fallback.string());
  check_output_folder(path);
  clean_after_killed_runs(path, kOutputFolderDepth);
  return path;
}

std::optional<std::filesystem::path> output_folder(const ParsedArgs& parsed,
                                                   const std::string& option) {
  const std::optional<std::string> value = parsed.value(option);
  if (!value) {
    return std::nullopt;
  }
  check_output_folder(*value);
  clean_after_killed_runs(*value, kOutputFolderDepth);
  return std::filesystem::path(*value);
}

std::filesystem::path required_output_folder(const ParsedArgs& parsed, const std::string& option,
                                             const std::string& missing) {
  const std::filesystem::path path = required_value(parsed, option, missing);
  check_output_folder(path);
  clean_after_killed_runs(path, kOutputFolderDepth);
  return path;
}

}  // namespace corsa::cli
