#pragma once
//! A record of the known device simulated end to end (tribology of every asperity, then the
//! shared circuit): what tests and the development harness invert. Calibration banks go
//! through the ensemble runner instead (same forward model, journalled and parallel).
#include <span>
#include <vector>

#include "inverse/known_device.hpp"
#include "inverse/record_grid.hpp"

namespace stengmc {

//! The clean voltage of the device with asperities of stiffnesses `k` [N/m] on `grid`
//! (grid.start_s must be 0) [V].
//! @throws ModelError when an asperity reaches l.
std::vector<double> simulate_record(const KnownDevice& device, std::span<const double> k, const RecordGrid& grid);

}  // namespace stengmc
