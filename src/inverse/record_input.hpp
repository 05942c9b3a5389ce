#pragma once
//! What an inversion demands of a record before it looks at it (docs/inverse.md,
//! rejected inputs): enough samples, finite values, times that increase on a uniform grid.
#include <span>
#include <string>

#include "inverse/record_grid.hpp"

namespace stengmc {

//! Fewest samples a record may have: below this the noise band and the line fit have too
//! little to work on (and a 1/T resolution of more than 1/64 of the sample rate).
inline constexpr std::size_t MIN_RECORD_SAMPLES = 64;

//! The record's grid, checked: >= 64 samples; every time and voltage finite; times strictly
//! increasing (a repeated time is named), uniform to 1e-6 of the step; the first time >= 0
//! (t = 0 is when the belt starts: the known device's asperities start at rest then).
//! @throws InputError naming `source` and the offending sample.
RecordGrid checked_record_grid(std::span<const double> times_s, std::span<const double> voltage_v, const std::string& source);

//! A record whose voltage is the same at every sample (all zero: an empty channel, the wrong
//! column) holds no line to fit, and its noise level is 0: refused once the device and grid
//! are checked, before anything is computed.
//! @throws InputError naming `source` and the value.
void check_record_varies(std::span<const double> voltage_v, const std::string& source);

}  // namespace stengmc
