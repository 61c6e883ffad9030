#pragma once

// JSON through nlohmann-json, for every file Corsa writes or reads as JSON (run summaries, sweep
// descriptions, dataset run.json, poses, calibration and labels, `validate --json`).
//
// Values are built and read as `Json` (nlohmann::ordered_json: members keep the order they were
// added, so files list them in a fixed, readable order). This header gives the text: Corsa's
// layout for files people read, one line for embedded values, compact for tools. Numbers are the
// shortest text that reads back to the same double (`0.1`, `10`, `1e-07`), so they round-trip
// exactly; infinities and NaN, which JSON lacks, are written as null. Strings are escaped by
// nlohmann-json; bytes that are not UTF-8 are replaced by U+FFFD, never written raw.

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

namespace corsa {

using Json = nlohmann::ordered_json;

/// A JSON file's text in Corsa's layout, ending in a newline: a top-level object has one member
/// a line (indented by two spaces); a member that is a non-empty array of objects has one object
/// a line (four spaces); everything else is on one line as json_line writes it. Example:
///
///     {
///       "scenario": "cut_in.xosc",
///       "parameters": {"Gap": "10"},
///       "entities": [
///         {"name": "Ego", "x": 650.5}
///       ]
///     }
std::string json_document(const Json& value);

/// One line: `{"a": 1, "b": [true, null, "x"]}` (a space after each colon and comma).
std::string json_line(const Json& value);

/// No spaces at all (`{"a":1,"b":[true]}`), as tools expect from a `--json` option.
std::string json_compact(const Json& value);

/// Parses the whole of `text` as JSON. Throws corsa::InputError located at `file`:line with
/// nlohmann-json's reason when it is not JSON (including strings that are not UTF-8).
Json parse_json(std::string_view text, const std::string& file);

/// Reads and parses a JSON file; throws corsa::InputError when it cannot be read or parsed.
Json read_json_file(const std::filesystem::path& file);

}  // namespace corsa
