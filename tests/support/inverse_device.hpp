#pragma once
// The known-device study of the inverse tests, read from tests/support/known_device.toml
// (shared with io/test_netcdf_outputs.py): records of `duration` seconds, and the given
// [inverse] table's keys.
#include <string>

#include "support/support_files.hpp"

namespace stengmc::testing {

inline std::string known_device_study(const std::string& duration, const std::string& inverse) {
  return "duration_s = " + duration + "\n" + support_file_text("known_device.toml") + "[inverse]\n" + inverse;
}

//! The [inverse] keys of a bank of 50 records that takes seconds (20 us records).
inline std::string quick_prior() { return support_file_text("known_device_quick_prior.toml"); }

}  // namespace stengmc::testing
