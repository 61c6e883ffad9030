#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace corsa {

/// Strict number parsing: the whole text (surrounding blanks allowed) must be a number.
/// Returns nullopt for empty text, trailing garbage, overflow, or (for doubles) NaN/inf text.
std::optional<double> parse_double(std::string_view text);
std::optional<int64_t> parse_int(std::string_view text);

/// Shortest decimal text that reads back to exactly the same double (std::to_chars).
std::string format_double(double value);
/// Fixed notation with `decimals` digits after the point, without locale effects.
std::string format_fixed(double value, int decimals);
/// `digits` significant digits (1 to 17), fixed or exponent notation as printf's "%.<digits>g"
/// writes them in the C locale (1e+30, 0.0001235, 123.5), without locale effects: for messages
/// that quote magnitudes rather than exact values.
std::string format_significant(double value, int digits);

std::string_view trim(std::string_view text);
std::vector<std::string_view> split(std::string_view text, char separator);
bool iequals(std::string_view a, std::string_view b);
std::string to_lower(std::string_view text);

/// One CSV field as Corsa writes it (RFC 4180): quoted with '"' only when it holds a comma, a
/// quote, a line break or leading/trailing blanks; quotes inside doubled.
std::string csv_field(std::string_view text);

/// `text` for quoting in a message: itself when at most `max_bytes` long, else its first bytes
/// (never ending inside a UTF-8 sequence) followed by "...". Keeps a 5 MB name or value in a
/// malformed input from flooding the terminal; every value a message echoes goes through it.
inline constexpr size_t kClipBytes = 200;
std::string clip(std::string_view text, size_t max_bytes = kClipBytes);

/// The name of `candidates` nearest to `word` when it is a likely misspelling of it: at most one
/// edit (insertion, deletion, substitution or swap of neighbours) for words of up to four
/// letters, two up to eight, three beyond; ties go to the first. Case is ignored.
std::optional<std::string> nearest_name(std::string_view word,
                                        std::span<const std::string> candidates);
/// " (did you mean 'NAME'?)" for the nearest candidate, or "" when none is near.
std::string did_you_mean(std::string_view word, std::span<const std::string> candidates);

}  // namespace corsa
