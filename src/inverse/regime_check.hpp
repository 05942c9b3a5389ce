#pragma once
//! Whether a record tracked as unexcited looks excited (docs/tracking.md, windows): a free
//! ringing's envelope only decays (e^{-gamma t}), while a driven line's, a random narrow-band
//! process, grows across a window about as often as it falls. When many of the clear ESPRIT
//! lines grow, the counterface drives the asperities: the `--known` device's `[counterface]
//! friction_modulation_rms` should not be 0. Measured: a single driven asperity tracked as
//! unexcited 0.45, four excited validation records (7-30 asperities) 0.36-0.40; free ringings
//! alone 0, ten crowded unexcited validation records (9-26 asperities, where close lines beat)
//! 0-0.23.
#include "inverse/tracking.hpp"

namespace stengmc {

//! The share of the clear lines (detected, z >= 10) whose fitted envelope grows across their
//! window (damping < 0) [-]; `count` receives how many clear lines there were.
double growing_line_share(const TrackingResult& result, std::size_t* count = nullptr);

//! True when `result` was tracked as unexcited and at least 20 clear lines were heard, 0.3 or
//! more of them growing (between the measured 0.23 and 0.36 above).
bool looks_excited(const TrackingResult& result);

}  // namespace stengmc
