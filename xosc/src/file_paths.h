#pragma once

// Internal: the files and folders a scenario names (LogicFile, catalog directories), resolved
// against the folder of the file that names them, with esmini's working-folder paths read
// leniently.

#include <filesystem>
#include <string>
#include <string_view>

#include "parse_context.h"

namespace corsa::xosc {

enum class PathKind { kFile, kDirectory };

/// How many folders above the naming file's folder a relative path is also tried from.
inline constexpr int kAncestorLevels = 3;

/// `path` as written at `element`, resolved against the folder of the file being read
/// (ctx.file().directory). When nothing of `kind` is there and the path is relative, the same
/// path is tried against that folder's ancestors, nearest first, up to kAncestorLevels: esmini
/// resolves such paths from its working folder as well (its examples name their maps
/// `../resources/xodr/...`, a path from esmini's bin folder). The first that exists is used,
/// with a lenient-reading warning naming it (`what` names the file, e.g. "map file"). When none
/// exists (or LoadOptions::check_files is off) the path against the file's own folder is
/// returned, for the caller to report.
std::filesystem::path resolve_named_path(ParseContext& ctx, const Element* element,
                                         const std::string& path, PathKind kind,
                                         std::string_view what);

}  // namespace corsa::xosc
