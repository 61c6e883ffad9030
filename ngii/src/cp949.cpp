#include "cp949.h"

#include <iconv.h>

#include <cerrno>
#include <cstdint>
#include <stdexcept>

namespace corsa::ngii::detail {
namespace {

bool is_ascii(std::string_view bytes) {
  for (const char c : bytes) {
    if (static_cast<unsigned char>(c) >= 0x80) {
      return false;
    }
  }
  return true;
}

constexpr std::string_view kReplacement = "\xEF\xBF\xBD";  // U+FFFD in UTF-8

}  // namespace

Cp949Decoder::Cp949Decoder() : descriptor_(iconv_open("UTF-8", "CP949")) {
  if (descriptor_ == reinterpret_cast<void*>(static_cast<intptr_t>(-1))) {
    // glibc always ships CP949 (gconv UHC); without it the platform is broken, not the input.
    throw std::runtime_error("iconv has no CP949 converter on this system");
  }
}

Cp949Decoder::~Cp949Decoder() { iconv_close(static_cast<iconv_t>(descriptor_)); }

std::string Cp949Decoder::decode(std::string_view bytes, bool* invalid) {
  if (is_ascii(bytes)) {
    return std::string(bytes);
  }
  auto cd = static_cast<iconv_t>(descriptor_);
  iconv(cd, nullptr, nullptr, nullptr, nullptr);  // reset the shift state
  std::string out;
  // A CP949 character is at most 2 bytes and becomes at most 3 UTF-8 bytes.
  std::string buffer(bytes.size() * 2 + 4, '\0');
  char* in = const_cast<char*>(bytes.data());
  size_t in_left = bytes.size();
  while (in_left > 0) {
    char* dst = buffer.data();
    size_t dst_left = buffer.size();
    const size_t result = iconv(cd, &in, &in_left, &dst, &dst_left);
    out.append(buffer.data(), static_cast<size_t>(dst - buffer.data()));
    if (result == static_cast<size_t>(-1)) {
      if (errno == E2BIG) {
        continue;
      }
      // EILSEQ (invalid byte) or EINVAL (truncated final character): replace one byte.
      out += kReplacement;
      ++in;
      --in_left;
      if (invalid != nullptr) {
        *invalid = true;
      }
    }
  }
  return out;
}

}  // namespace corsa::ngii::detail
