#include "inverse/record_grid.hpp"

#include <cmath>

namespace stengmc {

bool RecordGrid::same_as(const RecordGrid& other) const {
  return samples == other.samples && std::abs(step_s - other.step_s) <= 1e-9 * step_s &&
         std::abs(start_s - other.start_s) <= 1e-9 * step_s;
}

}  // namespace stengmc
