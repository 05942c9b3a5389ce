#include "core/checksum.hpp"

#include <bit>
#include <cstdio>

namespace stengmc {

std::uint64_t fnv1a64(std::string_view bytes, std::uint64_t basis) {
  std::uint64_t hash = basis;
  for (const char c : bytes) {
    hash ^= static_cast<unsigned char>(c);
    hash *= 0x100000001b3ULL;
  }
  return hash;
}

std::uint64_t fnv1a64_of_values(std::span<const double> values) {
  std::uint64_t hash = fnv1a64({});
  for (const double v : values) {
    const auto bits = std::bit_cast<std::uint64_t>(v);
    char bytes[8];
    for (int i = 0; i < 8; ++i) bytes[i] = static_cast<char>(bits >> (8 * i));
    hash = fnv1a64(std::string_view(bytes, sizeof bytes), hash);
  }
  return hash;
}

std::string checksum_text(std::uint64_t value) {
  char text[20];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(value));
  return text;
}

}  // namespace stengmc
