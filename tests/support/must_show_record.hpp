#pragma once
// Issue 23's must-show record, shared by the tests that invert it: 100 us at 100 MHz of the
// known device, a prior of loads spread by a CV of 0.2-0.6 and onsets within 20 us; four
// asperities whose loads lie 0.6-1.5 x the device's and whose onsets are 0-12.5 us, their
// lines 0.87-2.25 MHz apart by ~25 line widths.
#include <optional>
#include <vector>

#include "inverse/simulated_record.hpp"
#include "pipeline/study.hpp"
#include "support/inverse_device.hpp"

namespace stengmc::testing {

inline Study unequal_loads_and_onsets_study() {
  return parse_study(known_device_study("100e-6", "count = [0, 8]\nload_cv = [0.2, 0.6]\nonset_s = [0, 20e-6]\n"), "unequal.toml",
                     std::nullopt);
}

//! The four asperities, ascending in k, for a device whose load is `device_load_n` [N].
inline std::vector<SimulatedAsperity> four_unequal_loads_and_onsets(double device_load_n) {
  const double n0 = device_load_n;
  return {{30.0, 0.6 * n0, 3.1e-6}, {60.0, 1.5 * n0, 0.0}, {110.0, 0.8 * n0, 12.5e-6}, {200.0, 1.2 * n0, 7.3e-6}};
}

}  // namespace stengmc::testing
