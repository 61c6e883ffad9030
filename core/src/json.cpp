#include "corsa/core/json.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "corsa/core/atomic_file.h"
#include "corsa/core/diagnostic.h"
#include "corsa/core/strings.h"

namespace corsa {
namespace {

/// The length of the well-formed UTF-8 sequence at the start of `text` (Unicode 15 §3.9, table
/// 3-7: no overlong forms, surrogates or code points above U+10FFFF), 0 when there is none.
size_t utf8_sequence_length(std::string_view text) {
  const auto byte = [&](size_t i) { return static_cast<unsigned char>(text[i]); };
  const unsigned char lead = byte(0);
  size_t length = 0;
  unsigned char low = 0x80;
  unsigned char high = 0xBF;
  if (lead < 0x80) {
    return 1;
  } else if (lead >= 0xC2 && lead <= 0xDF) {
    length = 2;
  } else if (lead >= 0xE0 && lead <= 0xEF) {
    length = 3;
    low = lead == 0xE0 ? 0xA0 : 0x80;
    high = lead == 0xED ? 0x9F : 0xBF;
  } else if (lead >= 0xF0 && lead <= 0xF4) {
    length = 4;
    low = lead == 0xF0 ? 0x90 : 0x80;
    high = lead == 0xF4 ? 0x8F : 0xBF;
  } else {
    return 0;
  }
  if (text.size() < length || byte(1) < low || byte(1) > high) return 0;
  for (size_t i = 2; i < length; ++i) {
    if (byte(i) < 0x80 || byte(i) > 0xBF) return 0;
  }
  return length;
}

// Appends a run of well-formed UTF-8 escaped by nlohmann-json (quotes, backslashes and control
// characters), without the quotes around it.
void write_escaped(std::string& out, std::string_view run) {
  if (run.empty()) return;
  const std::string quoted = Json(std::string(run)).dump();
  out.append(quoted, 1, quoted.size() - 2);
}

// JSON text is UTF-8 (RFC 8259 §8.1): each byte that starts no well-formed sequence (input files
// may hold any bytes) becomes \ufffd, the replacement character, so that a name read from a
// Latin-1 file still gives a valid file; the well-formed runs between are escaped by nlohmann-json.
void write_string(std::string& out, std::string_view text) {
  out += '"';
  size_t run_start = 0;
  for (size_t at = 0; at < text.size();) {
    const size_t length = utf8_sequence_length(text.substr(at));
    if (length == 0) {
      write_escaped(out, text.substr(run_start, at - run_start));
      out += "\\ufffd";
      run_start = ++at;
    } else {
      at += length;
    }
  }
  write_escaped(out, text.substr(run_start));
  out += '"';
}

void write_number(std::string& out, const Json& value) {
  if (value.is_number_unsigned()) {
    out += std::to_string(value.get<uint64_t>());
  } else if (value.is_number_integer()) {
    out += std::to_string(value.get<int64_t>());
  } else {
    const double number = value.get<double>();
    out += std::isfinite(number) ? format_double(number) : "null";
  }
}

// One value on one line; `spaced` puts a space after each colon and comma.
void write_line(std::string& out, const Json& value, bool spaced) {
  const char* comma = spaced ? ", " : ",";
  const char* colon = spaced ? ": " : ":";
  switch (value.type()) {
    case Json::value_t::object: {
      out += '{';
      bool first = true;
      for (auto it = value.begin(); it != value.end(); ++it) {
        out += first ? "" : comma;
        first = false;
        write_string(out, it.key());
        out += colon;
        write_line(out, it.value(), spaced);
      }
      out += '}';
      break;
    }
    case Json::value_t::array: {
      out += '[';
      bool first = true;
      for (const Json& element : value) {
        out += first ? "" : comma;
        first = false;
        write_line(out, element, spaced);
      }
      out += ']';
      break;
    }
    case Json::value_t::string:
      write_string(out, value.get_ref<const std::string&>());
      break;
    case Json::value_t::boolean:
      out += value.get<bool>() ? "true" : "false";
      break;
    case Json::value_t::number_integer:
    case Json::value_t::number_unsigned:
    case Json::value_t::number_float:
      write_number(out, value);
      break;
    default:  // null, discarded, binary (never built by Corsa)
      out += "null";
      break;
  }
}

bool is_array_of_objects(const Json& value) {
  return value.is_array() && !value.empty() &&
         std::all_of(value.begin(), value.end(), [](const Json& e) { return e.is_object(); });
}

}  // namespace

std::string json_line(const Json& value) {
  std::string out;
  write_line(out, value, true);
  return out;
}

std::string json_compact(const Json& value) {
  std::string out;
  write_line(out, value, false);
  return out;
}

std::string json_document(const Json& value) {
  if (!value.is_object() || value.empty()) {
    return json_line(value) + "\n";
  }
  std::string out = "{";
  bool first = true;
  for (auto it = value.begin(); it != value.end(); ++it) {
    out += first ? "\n  " : ",\n  ";
    first = false;
    write_string(out, it.key());
    out += ": ";
    if (is_array_of_objects(it.value())) {
      out += '[';
      bool first_element = true;
      for (const Json& element : it.value()) {
        out += first_element ? "\n    " : ",\n    ";
        first_element = false;
        write_line(out, element, true);
      }
      out += "\n  ]";
    } else {
      write_line(out, it.value(), true);
    }
  }
  return out + "\n}\n";
}

Json parse_json(std::string_view text, const std::string& file) {
  try {
    return Json::parse(text.begin(), text.end());
  } catch (const Json::parse_error& error) {
    // error.byte counts from 1; the line is that of the byte where reading stopped.
    const size_t end = std::min<size_t>(error.byte > 0 ? error.byte - 1 : 0, text.size());
    const int line = 1 + static_cast<int>(std::count(text.begin(), text.begin() + end, '\n'));
    // what(): "[json.exception.parse_error.101] parse error at line 1, column 2: <reason>".
    std::string reason = error.what();
    if (const size_t colon = reason.find(": "); colon != std::string::npos) {
      reason.erase(0, colon + 2);
    }
    throw InputError(make_error(file, line, "not valid JSON: " + reason));
  } catch (const Json::out_of_range& error) {
    // A number beyond the range of doubles (RFC 8259 §6 leaves the range to the reader):
    // "[json.exception.out_of_range.406] number overflow parsing '1e400'". Located at the line
    // of the first occurrence of that number.
    std::string reason = error.what();
    if (const size_t bracket = reason.find("] "); bracket != std::string::npos) {
      reason.erase(0, bracket + 2);
    }
    int line = 1;
    const size_t open = reason.find('\'');
    const size_t close = reason.rfind('\'');
    if (open != std::string::npos && close > open + 1) {
      const size_t at = text.find(reason.substr(open + 1, close - open - 1));
      if (at != std::string_view::npos) {
        line += static_cast<int>(std::count(text.begin(), text.begin() + at, '\n'));
      }
    }
    throw InputError(make_error(file, line, "not valid JSON: " + clip(reason)));
  }
}

Json read_json_file(const std::filesystem::path& file) {
  return parse_json(read_file(file), file.string());
}

}  // namespace corsa
