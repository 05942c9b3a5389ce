#pragma once
//! One field of every item of a table, as a vector: how per-asperity and per-line tables
//! are written and passed on.
#include <iterator>
#include <type_traits>
#include <vector>

namespace stengmc {

template <class Range, class Field>
auto column(const Range& items, Field field) {
  std::vector<std::decay_t<decltype(field(*std::begin(items)))>> out;
  for (const auto& item : items) out.push_back(field(item));
  return out;
}

}  // namespace stengmc
