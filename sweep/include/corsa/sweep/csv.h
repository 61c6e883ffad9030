#pragma once

// The small CSV dialect of Corsa's sweep tables (RFC 4180): fields separated by commas, a field
// quoted with '"' when it holds a comma, a quote, a line break or leading/trailing blanks, quotes
// inside doubled. Lines end with '\n'.

#include <string>
#include <string_view>
#include <vector>

namespace corsa::sweep {

/// One field as it is written: quoted only when needed.
std::string csv_field(std::string_view text);

/// A line of fields (with the trailing newline).
std::string csv_line(const std::vector<std::string>& fields);

/// Parses CSV text into rows of fields. A final line without newline counts; empty lines are
/// skipped. Returns false (and leaves `rows` partial) when a quoted field is not closed.
bool parse_csv(std::string_view text, std::vector<std::vector<std::string>>& rows);

}  // namespace corsa::sweep
