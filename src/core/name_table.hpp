#pragma once
//! One table per enumeration between its values and the names study files and output files
//! use, kept beside the enumeration: the reader (TomlTable::enumeration), the writers (HDF5
//! attributes) and the generated studies all look names up here, so a new value is one row.
#include <array>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace stengmc {

template <class Enum>
struct NamedValue {
  Enum value;
  std::string_view name;
};

template <class Enum, std::size_t N>
class NameTable {
 public:
  constexpr explicit NameTable(std::array<NamedValue<Enum>, N> rows) : rows_(rows) {}

  //! The name of `value`; a value without a row is a programming error (std::logic_error).
  [[nodiscard]] constexpr std::string_view name(Enum value) const {
    for (const auto& row : rows_)
      if (row.value == value) return row.name;
    throw std::logic_error("NameTable: a value without a name");
  }

  //! The value named `name`; readers check names against names() first, so an unknown name
  //! here is a programming error (std::logic_error).
  [[nodiscard]] constexpr Enum value(std::string_view name) const {
    for (const auto& row : rows_)
      if (row.name == name) return row.value;
    throw std::logic_error("NameTable: no value named " + std::string(name));
  }

  //! Every name, in the table's order (what an error message lists as allowed).
  [[nodiscard]] std::vector<std::string_view> names() const {
    std::vector<std::string_view> out;
    out.reserve(N);
    for (const auto& row : rows_) out.push_back(row.name);
    return out;
  }

 private:
  std::array<NamedValue<Enum>, N> rows_;
};

template <class Enum, std::size_t N>
NameTable(std::array<NamedValue<Enum>, N>) -> NameTable<Enum, N>;

}  // namespace stengmc
