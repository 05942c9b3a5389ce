#pragma once
//! Shard i of n of an ensemble: the realisations r with r mod n = i (ensemble/shard.hpp).
#include <cstdint>
#include <string>
#include <string_view>

namespace stengmc {

struct ShardSpec {
  std::uint64_t index = 0;  //!< i, 0 <= i < count
  std::uint64_t count = 1;  //!< n >= 1
  [[nodiscard]] bool contains(std::uint64_t realisation) const { return realisation % count == index; }
  [[nodiscard]] std::string text() const { return std::to_string(index) + "/" + std::to_string(count); }
};

//! Parses "i/n" (whole numbers, 0 <= i < n); InputError saying what was expected otherwise.
ShardSpec parse_shard_spec(std::string_view text);

}  // namespace stengmc
