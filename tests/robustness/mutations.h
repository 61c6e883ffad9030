#pragma once

// Deterministic ways to break a good input file: truncation, byte flips, attribute values replaced
// or deleted. Seeds are fixed, so every run of the tests sees the same broken files; std::mt19937's
// output sequence is fixed by the C++ standard (its distributions are not, so none is used).

#include <cstdint>
#include <random>
#include <regex>
#include <string>
#include <vector>

namespace corsa::test {

/// A named broken variant of an input text.
struct Mutant {
  std::string name;
  std::string text;
};

/// `text` cut after each fraction of its length (0 gives an empty file).
inline std::vector<Mutant> truncations(const std::string& text,
                                       const std::vector<double>& fractions) {
  std::vector<Mutant> out;
  for (const double fraction : fractions) {
    const auto size = static_cast<size_t>(fraction * static_cast<double>(text.size()));
    out.push_back({"truncated at byte " + std::to_string(size), text.substr(0, size)});
  }
  return out;
}

/// `count` variants with 1 to 8 random bytes overwritten by random values.
inline std::vector<Mutant> byte_flips(const std::string& text, uint32_t seed, int count) {
  std::mt19937 engine(seed);
  std::vector<Mutant> out;
  for (int i = 0; i < count; ++i) {
    Mutant mutant{"flips seed " + std::to_string(seed) + " #" + std::to_string(i), text};
    const uint32_t flips = 1 + engine() % 8;
    for (uint32_t k = 0; k < flips; ++k) {
      const size_t at = engine() % text.size();
      mutant.text[at] = static_cast<char>(engine() % 256);
      mutant.name += " @" + std::to_string(at);
    }
    out.push_back(std::move(mutant));
  }
  return out;
}

/// Position of the value of the first `attribute="..."` inside the first `<element ` tag.
struct AttributeSpot {
  size_t value_begin = std::string::npos;
  size_t value_end = std::string::npos;
  size_t attribute_begin = std::string::npos;  ///< at the space before the name
};

inline AttributeSpot find_attribute(const std::string& text, const std::string& element,
                                    const std::string& attribute) {
  AttributeSpot spot;
  const size_t tag = text.find("<" + element + " ");
  if (tag == std::string::npos) {
    return spot;
  }
  const size_t tag_end = text.find('>', tag);
  const std::regex pattern("\\s" + attribute + "\\s*=\\s*\"([^\"]*)\"");
  std::smatch match;
  const std::string tag_text = text.substr(tag, tag_end - tag);
  if (!std::regex_search(tag_text, match, pattern)) {
    return spot;
  }
  spot.attribute_begin = tag + static_cast<size_t>(match.position(0));
  spot.value_begin = tag + static_cast<size_t>(match.position(1));
  spot.value_end = spot.value_begin + static_cast<size_t>(match.length(1));
  return spot;
}

/// `text` with the value of `element`'s first `attribute` replaced by `value`.
inline std::string with_attribute(const std::string& text, const std::string& element,
                                  const std::string& attribute, const std::string& value) {
  const AttributeSpot spot = find_attribute(text, element, attribute);
  if (spot.value_begin == std::string::npos) {
    return {};
  }
  return text.substr(0, spot.value_begin) + value + text.substr(spot.value_end);
}

/// `text` without `element`'s first `attribute` (name, '=' and value).
inline std::string without_attribute(const std::string& text, const std::string& element,
                                     const std::string& attribute) {
  const AttributeSpot spot = find_attribute(text, element, attribute);
  if (spot.value_begin == std::string::npos) {
    return {};
  }
  return text.substr(0, spot.attribute_begin) + text.substr(spot.value_end + 1);
}

/// Values no numeric attribute should accept silently (or, for the large ones, run away with).
inline const std::vector<std::string>& bad_numbers() {
  static const std::vector<std::string> values{
      "nan",   "NaN",    "inf",  "-inf", "abc",  "",    "1e999",
      "1e308", "-1e308", "1e20", "-1",   "0x10", "1 2", "99999999999999999999999"};
  return values;
}

}  // namespace corsa::test
