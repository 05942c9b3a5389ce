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

//! One sliding asperity that departs from the device's own: its stiffness, normal load and
//! contact onset (everything else is the device's).
struct SimulatedAsperity {
  double stiffness_n_per_m = 0.0;  //!< k [N/m]
  double normal_load_n = 0.0;      //!< N [N]
  double onset_s = 0.0;            //!< t_on [s]
};

//! The clean voltage of the device with `asperities` on `grid` (grid.start_s must be 0) [V].
//! @throws ModelError when an asperity reaches l.
std::vector<double> simulate_record(const KnownDevice& device, std::span<const SimulatedAsperity> asperities,
                                    const RecordGrid& grid);

}  // namespace stengmc
