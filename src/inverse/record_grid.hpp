#pragma once
//! The sample times of a record: t_m = start_s + m step_s, m = 0 .. samples-1.
#include <cstddef>
#include <vector>

namespace stengmc {

struct RecordGrid {
  double start_s = 0.0;     //!< time of the first sample, counted from the start of sliding [s]
  double step_s = 0.0;      //!< sample interval [s]
  std::size_t samples = 0;  //!< number of samples

  [[nodiscard]] double at(std::size_t m) const { return start_s + static_cast<double>(m) * step_s; }
  [[nodiscard]] double sample_rate_hz() const { return 1.0 / step_s; }
  [[nodiscard]] double duration_s() const { return step_s * static_cast<double>(samples > 0 ? samples - 1 : 0); }
  [[nodiscard]] std::vector<double> times() const {
    std::vector<double> t(samples);
    for (std::size_t m = 0; m < samples; ++m) t[m] = at(m);
    return t;
  }
  //! Same grid to a billionth of a step (a bank is valid only for its grid).
  [[nodiscard]] bool same_as(const RecordGrid& other) const;
};

}  // namespace stengmc
