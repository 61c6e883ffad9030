#include "file_paths.h"

#include <system_error>

namespace corsa::xosc {
namespace {

bool exists_as(const std::filesystem::path& path, PathKind kind) {
  std::error_code error;
  return kind == PathKind::kFile ? std::filesystem::is_regular_file(path, error)
                                 : std::filesystem::is_directory(path, error);
}

}  // namespace

std::filesystem::path resolve_named_path(ParseContext& ctx, const Element* element,
                                         const std::string& path, PathKind kind,
                                         std::string_view what) {
  const std::filesystem::path written(path);
  const std::filesystem::path& base = ctx.file().directory;
  const std::filesystem::path direct = (base / written).lexically_normal();
  if (!ctx.options().check_files || written.is_absolute() || exists_as(direct, kind)) {
    return direct;
  }
  // Ancestors of the absolute folder, so that a relative scenario path has them too.
  std::error_code error;
  std::filesystem::path folder = std::filesystem::absolute(base, error).lexically_normal();
  if (error) return direct;
  for (int level = 1; level <= kAncestorLevels; ++level) {
    if (!folder.has_relative_path()) break;  // the root has no ancestor
    folder = folder.parent_path();
    const std::filesystem::path candidate = (folder / written).lexically_normal();
    if (exists_as(candidate, kind)) {
      ctx.lenient(element,
                  std::string(what) + " '" + clip(path) + "' is not in the scenario's folder (" +
                      clip(direct.string()) + ")",
                  clip(candidate.string()) + ", the same path from " + std::to_string(level) +
                      (level == 1 ? " folder" : " folders") + " up, as esmini finds it from its " +
                      "working folder");
      return candidate;
    }
  }
  return direct;
}

}  // namespace corsa::xosc
