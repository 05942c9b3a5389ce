#pragma once
//! A configurable thing's settings as (key, value) pairs, listed by the thing itself beside
//! its reader (Cantera's getParameters habit): the run files record them as HDF5
//! attributes and the generated studies write them back as TOML, from the one list.
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <variant>

namespace stengmc {

class Hdf5Writer;

struct Setting {
  std::string_view key;                                  //!< the study file's key
  std::variant<double, std::int64_t, std::string> value;  //!< in the key's SI unit
};

//! Each setting as an attribute of `object`.
void write_settings(Hdf5Writer& file, const std::string& object, std::span<const Setting> settings);

//! `key = value` lines for a TOML table, numbers to 17 digits (they read back exactly).
std::string toml_lines(std::span<const Setting> settings);

}  // namespace stengmc
