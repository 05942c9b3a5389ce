#pragma once
#include <cmath>
#include <cstddef>
#include <span>
#include <vector>

namespace stengmc {

//! The uniform output grid t_j = j / sample_rate, j = 0 .. count-1, covering [0, duration].
struct TimeGrid {
  double step_s = 0.0;     //!< 1 / sample_rate [s]
  std::size_t count = 0;   //!< number of samples, endpoints included

  //! Grid of `duration_s` at `sample_rate_hz`, both ends included.
  static TimeGrid covering(double duration_s, double sample_rate_hz) {
    return {1.0 / sample_rate_hz,
            static_cast<std::size_t>(std::llround(duration_s * sample_rate_hz)) + 1};
  }

  //! Time of sample j [s].
  [[nodiscard]] double at(std::size_t j) const { return static_cast<double>(j) * step_s; }

  //! All sample times [s].
  [[nodiscard]] std::vector<double> times() const {
    std::vector<double> t(count);
    for (std::size_t j = 0; j < count; ++j) t[j] = at(j);
    return t;
  }
};

//! Whether every spacing of `times_s` is `step_s` to within 1e-9 of it (false for any NaN).
//! Every spacing is checked, four at a time where the processor has AVX.
bool evenly_spaced(std::span<const double> times_s, double step_s);

}  // namespace stengmc
