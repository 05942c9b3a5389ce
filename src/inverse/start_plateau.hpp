#pragma once
//! How many asperities are in contact when the record starts, read off its first microsecond
//! (docs/tracking.md, n(t)). The known device starts every asperity at rest when the belt
//! starts (t = 0). The belt's friction F brings each one to the belt's velocity within
//! m v_b / F (18-36 ns with Table 1 values), and it stays stuck, x' = v_b, until its spring
//! holds F, at t_b = (F - c v_b) / (k v_b) (0.18-3 us for k = 20-160 N/m). Meanwhile the
//! voltage is the plateau V = n R sigma w v_b (C_L = 0: V = R sum sigma w x'), an integer
//! multiple of one stuck asperity's voltage. Afterwards no asperity in contact moves faster
//! than the belt (the `consistent` friction law: it never overtakes it), so the plateau is the
//! record's early maximum: n is the largest short mean of its first microsecond over
//! R sigma w v_b, rounded.
#include <cstddef>
#include <optional>
#include <span>

#include "inverse/known_device.hpp"
#include "inverse/record_grid.hpp"

namespace stengmc {

//! The number of asperities stuck to the belt at the record's start, or nothing when the record
//! does not start with the belt (its first sample after t = 0 by more than the ramp, or not at
//! rest) or shows no plateau of at least one asperity.
std::optional<std::size_t> asperities_at_start(const KnownDevice& device, const RecordGrid& grid, std::span<const double> voltage_v);

}  // namespace stengmc
