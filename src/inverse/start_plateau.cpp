#include "inverse/start_plateau.hpp"

#include <algorithm>
#include <cmath>

namespace stengmc {

std::optional<std::size_t> asperities_at_start(const KnownDevice& device, const RecordGrid& grid, std::span<const double> v) {
  const double unit = device.voltage_scale_v();  // one asperity stuck to the belt: R sigma w v_b
  const double ramp_s = device.asperity.mass_kg * device.model.belt_velocity_m_per_s / device.sliding_friction_n();
  if (!(unit > 0.0) || std::abs(grid.start_s) > ramp_s || v.empty() || std::abs(v.front()) > 0.5 * unit) return std::nullopt;
  // Short means of 8 samples (80 ns at 100 MHz): the noise's sigma / sqrt(8) against one
  // asperity's step, and short enough to lie inside the plateau of the stiffest asperity (t_b
  // = 0.18 us at k = 160 N/m, v_b = 10 m/s). From twice the ramp on (the friction accelerates
  // each asperity at F/m until it moves with the belt) over the first microsecond.
  const auto first = static_cast<std::size_t>(std::ceil(2.0 * ramp_s / grid.step_s));
  const auto last = std::min(v.size(), static_cast<std::size_t>(1e-6 / grid.step_s));
  constexpr std::size_t SPAN = 8;
  if (last < first + SPAN) return std::nullopt;
  double best = -1.0;
  double sum = 0.0;
  for (std::size_t i = first; i < last; ++i) {
    sum += v[i];
    if (i >= first + SPAN) sum -= v[i - SPAN];
    if (i + 1 >= first + SPAN) best = std::max(best, sum / static_cast<double>(SPAN));
  }
  const double n = std::round(best / unit);
  if (!(n >= 1.0)) return std::nullopt;
  return static_cast<std::size_t>(n);
}

}  // namespace stengmc
