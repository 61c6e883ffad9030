#pragma once

// CP949 (Unified Hangul Code, the superset of EUC-KR that Korean DBF files use) to UTF-8,
// through glibc iconv. One decoder per import: it owns its iconv descriptor.

#include <string>
#include <string_view>

namespace corsa::ngii::detail {

class Cp949Decoder {
 public:
  Cp949Decoder();
  Cp949Decoder(const Cp949Decoder&) = delete;
  Cp949Decoder& operator=(const Cp949Decoder&) = delete;
  ~Cp949Decoder();

  /// UTF-8 text of `bytes`. ASCII passes through unchanged; a byte sequence that is not valid
  /// CP949 becomes U+FFFD and sets `*invalid` (when given) to true.
  std::string decode(std::string_view bytes, bool* invalid = nullptr);

 private:
  void* descriptor_;  // iconv_t
};

}  // namespace corsa::ngii::detail
