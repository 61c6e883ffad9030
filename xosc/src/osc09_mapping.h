#pragma once

// Internal: reading OpenSCENARIO 0.9 drafts as 1.0 (docs/openscenario.md, "Published
// scenarios").

#include <tinyxml2.h>

#include "parse_context.h"

namespace corsa::xosc {

/// When `document` says revMajor="0" revMinor="9", rewrites its 0.9 forms into their 1.0
/// equivalents in place, each keeping the line of the 0.9 element it came from, and warns once at
/// the FileHeader naming the forms translated (an error under --strict); the header then says
/// 1.0. A 0.9 header over a document already in 1.0 forms is left alone.
void map_osc09_to_osc10(ParseContext& ctx, tinyxml2::XMLDocument& document);

/// map_osc09_to_osc10 for a catalog file read once for many loads: what it warns about or finds
/// in error is kept in `file.mapping_notes`, for each load that reads the file to report (with too
/// many errors, those found until the mapping stopped).
void map_osc09_catalog_file(XmlFile& file);

}  // namespace corsa::xosc
