#pragma once

// OpenDRIVE 1.4-1.8 reader: .xodr text -> MapData (model.h). Bad input throws corsa::InputError
// with file:line; unknown elements and tolerated oddities are reported once per kind to the
// Diagnostics the caller passes in.

#include <filesystem>
#include <string>
#include <string_view>

#include "corsa/core/diagnostic.h"
#include "corsa/xodr/model.h"

namespace corsa::xodr {

/// Reads an OpenDRIVE file. Throws InputError (file:line: error: ...) for unreadable or
/// malformed XML, a missing or non-numeric required attribute, NaN/inf, a negative geometry
/// length and the like. Cross-references (links to roads and junctions) are checked by
/// Map::build, not here, so that a converter can build MapData piecewise.
MapData parse_xodr(const std::filesystem::path& path, corsa::Diagnostics& diagnostics);

/// Same, from text in memory; `source_name` is used in messages and MapData::source_file.
MapData parse_xodr_text(std::string_view text, const std::string& source_name,
                        corsa::Diagnostics& diagnostics);

/// Refuses a map read leniently (`--strict`): throws InputError with each of
/// `data.lenient_readings` as an error at its line, `message (an error under --strict; otherwise
/// read as read_as)`. Does nothing when there are none.
void refuse_lenient_readings(const MapData& data);

/// LaneType from its OpenDRIVE name (case-insensitive); kOther for an unknown name.
LaneType lane_type_from_name(std::string_view name);
/// The OpenDRIVE name of a lane type ("driving", "sidewalk", ...); "none" for kOther.
std::string_view lane_type_name(LaneType type);

}  // namespace corsa::xodr
