#pragma once

// The layer CRS: the .prj (ESRI WKT) read through PROJ, so that the converter never assumes
// one (NGII ships UTM 52N, UTM-K and Korea 2000 variants of the same product).

#include <filesystem>

#include "corsa/ngii/layers.h"

namespace corsa::ngii::detail {

/// Reads and interprets a .prj file. Throws InputError naming the file when it is unreadable,
/// PROJ cannot parse it, or it is not a projected CRS in metres.
Crs read_crs(const std::filesystem::path& prj);

}  // namespace corsa::ngii::detail
