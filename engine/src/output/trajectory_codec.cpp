#include "output/trajectory_codec.h"

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#define CORSA_CRC_PCLMUL 1
#if __has_include(<sys/platform/x86.h>)
// glibc's copy of the CPU's features, read by the dynamic loader at start-up. GCC's
// __builtin_cpu_supports would link libgcc's __cpu_indicator_init, a constructor that runs a
// dozen CPUID instructions in every process, each costing ~25 us under a hypervisor.
#include <sys/platform/x86.h>
#define CORSA_HAS_PCLMUL() (CPU_FEATURE_ACTIVE(PCLMULQDQ) && CPU_FEATURE_ACTIVE(SSE4_1))
#else
#define CORSA_HAS_PCLMUL() (__builtin_cpu_supports("pclmul") && __builtin_cpu_supports("sse4.1"))
#endif
#endif

namespace corsa::engine::detail::trajectory_codec {

namespace {

// Slicing by 8 (Intel's "slicing-by-8" tables): table[k][b] is the CRC of byte b followed by k
// zero bytes, so eight bytes cost eight look-ups and no dependency between them; the result is
// that of the byte-at-a-time loop.
using CrcTables = std::array<std::array<uint32_t, 256>, 8>;

constexpr CrcTables crc_tables() {
  CrcTables tables{};
  for (uint32_t i = 0; i < 256; ++i) {
    uint32_t c = i;
    for (int k = 0; k < 8; ++k) {
      c = (c & 1) != 0 ? 0xEDB88320u ^ (c >> 1) : c >> 1;
    }
    tables[0][i] = c;
  }
  for (uint32_t i = 0; i < 256; ++i) {
    for (size_t k = 1; k < 8; ++k) {
      const uint32_t c = tables[k - 1][i];
      tables[k][i] = tables[0][c & 0xff] ^ (c >> 8);
    }
  }
  return tables;
}

constexpr CrcTables kCrcTables = crc_tables();

uint32_t load_le32(const char* p) {
  return static_cast<uint32_t>(static_cast<uint8_t>(p[0])) |
         static_cast<uint32_t>(static_cast<uint8_t>(p[1])) << 8 |
         static_cast<uint32_t>(static_cast<uint8_t>(p[2])) << 16 |
         static_cast<uint32_t>(static_cast<uint8_t>(p[3])) << 24;
}

#ifdef CORSA_CRC_PCLMUL

__m128i crc_load16(const char* at) { return _mm_loadu_si128(reinterpret_cast<const __m128i*>(at)); }

// a * k (low halves) ^ a * k (high halves) ^ next: lane `a` moved on by the distance k stands
// for, and the bytes met there added.
__attribute__((target("sse4.1,pclmul"))) inline __m128i crc_fold(__m128i a, __m128i k,
                                                                 __m128i next) {
  return _mm_xor_si128(
      _mm_xor_si128(_mm_clmulepi64_si128(a, k, 0x00), _mm_clmulepi64_si128(a, k, 0x11)), next);
}

// The CRC state (inverted, as the loops below keep it) after `n` bytes at `p` (n >= 64, a
// multiple of 16), by carry-less multiplication: Intel's "Fast CRC Computation for Generic
// Polynomials Using PCLMULQDQ Instruction" (2009), its constants for the reflected IEEE
// polynomial (those of Linux's crc32-pclmul and zlib's crc32_simd). Four 16-byte lanes are
// folded 64 bytes ahead, then into one, which is folded 16 bytes at a time and reduced to 32
// bits (Barrett). A CRC is a function of the bytes: the result is the tables' to the bit, for
// an eighth of their instructions (the tables' loop was a tenth or more of the binary
// recorder's CPU time).
__attribute__((target("sse4.1,pclmul"))) uint32_t crc32_folded(const char* p, size_t n,
                                                               uint32_t crc) {
  const __m128i k1k2 = _mm_set_epi64x(0x01c6e41596, 0x0154442bd4);
  const __m128i k3k4 = _mm_set_epi64x(0x00ccaa009e, 0x01751997d0);
  const __m128i k5 = _mm_set_epi64x(0, 0x0163cd6124);
  const __m128i poly = _mm_set_epi64x(0x01f7011641, 0x01db710641);
  __m128i x1 = _mm_xor_si128(crc_load16(p), _mm_cvtsi32_si128(static_cast<int>(crc)));
  __m128i x2 = crc_load16(p + 16);
  __m128i x3 = crc_load16(p + 32);
  __m128i x4 = crc_load16(p + 48);
  p += 64;
  n -= 64;
  for (; n >= 64; p += 64, n -= 64) {
    x1 = crc_fold(x1, k1k2, crc_load16(p));
    x2 = crc_fold(x2, k1k2, crc_load16(p + 16));
    x3 = crc_fold(x3, k1k2, crc_load16(p + 32));
    x4 = crc_fold(x4, k1k2, crc_load16(p + 48));
  }
  x1 = crc_fold(x1, k3k4, x2);
  x1 = crc_fold(x1, k3k4, x3);
  x1 = crc_fold(x1, k3k4, x4);
  for (; n >= 16; p += 16, n -= 16) {
    x1 = crc_fold(x1, k3k4, crc_load16(p));
  }
  // 128 bits to 64, then Barrett's reduction to 32.
  const __m128i low32 = _mm_setr_epi32(~0, 0, ~0, 0);
  x1 = _mm_xor_si128(_mm_srli_si128(x1, 8), _mm_clmulepi64_si128(x1, k3k4, 0x10));
  x1 = _mm_xor_si128(_mm_srli_si128(x1, 4),
                     _mm_clmulepi64_si128(_mm_and_si128(x1, low32), k5, 0x00));
  __m128i reduced = _mm_clmulepi64_si128(_mm_and_si128(x1, low32), poly, 0x10);
  reduced = _mm_clmulepi64_si128(_mm_and_si128(reduced, low32), poly, 0x00);
  x1 = _mm_xor_si128(x1, reduced);
  return static_cast<uint32_t>(_mm_extract_epi32(x1, 1));
}

#endif

}  // namespace

uint32_t crc32(uint32_t crc, std::string_view data) {
  const auto& t = kCrcTables;
  crc = ~crc;
  const char* p = data.data();
  size_t n = data.size();
#ifdef CORSA_CRC_PCLMUL
  if (n >= 64 && CORSA_HAS_PCLMUL()) {
    const size_t whole = n & ~size_t{15};
    crc = crc32_folded(p, whole, crc);
    p += whole;
    n -= whole;
  }
#endif
  for (; n >= 8; p += 8, n -= 8) {
    const uint32_t low = load_le32(p) ^ crc;
    const uint32_t high = load_le32(p + 4);
    crc = t[7][low & 0xff] ^ t[6][(low >> 8) & 0xff] ^ t[5][(low >> 16) & 0xff] ^ t[4][low >> 24] ^
          t[3][high & 0xff] ^ t[2][(high >> 8) & 0xff] ^ t[1][(high >> 16) & 0xff] ^
          t[0][high >> 24];
  }
  for (; n > 0; ++p, --n) {
    crc = t[0][(crc ^ static_cast<uint8_t>(*p)) & 0xff] ^ (crc >> 8);
  }
  return ~crc;
}

}  // namespace corsa::engine::detail::trajectory_codec
