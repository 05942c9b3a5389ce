#include "spectral/local_noise_floor.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "spectral/peaks.hpp"

namespace stengmc {

std::vector<double> local_noise_floor(const AmplitudeSpectrum& spectrum, double width_hz) {
  const auto& a = spectrum.amplitude;
  const std::size_t n = a.size();
  if (n < 2) throw InputError("local noise floor: the spectrum has no bin above DC");
  const auto half = static_cast<std::size_t>(std::floor(0.5 * width_hz / spectrum.bin_width_hz));
  if (half == 0) return std::vector<double>(n, noise_floor(spectrum));
  const std::size_t stride = std::max<std::size_t>(1, half / 4);
  const double rayleigh = std::sqrt(std::log(2.0));
  std::vector<std::size_t> nodes;
  std::vector<double> values;
  std::vector<double> window;
  for (std::size_t centre = 1;; centre += stride) {
    centre = std::min(centre, n - 1);
    const std::size_t lo = centre > half ? centre - half : 1;
    const std::size_t hi = std::min(n - 1, centre + half);
    window.assign(a.begin() + static_cast<std::ptrdiff_t>(lo), a.begin() + static_cast<std::ptrdiff_t>(hi) + 1);
    const auto middle = window.begin() + static_cast<std::ptrdiff_t>(window.size() / 2);
    std::nth_element(window.begin(), middle, window.end());
    nodes.push_back(centre);
    values.push_back(*middle / rayleigh);
    if (centre == n - 1) break;
  }
  std::vector<double> floor(n);
  floor[0] = values.front();
  std::size_t j = 0;
  for (std::size_t k = 1; k < n; ++k) {
    while (j + 1 < nodes.size() && nodes[j + 1] < k) ++j;
    if (j + 1 >= nodes.size() || k <= nodes[j]) {
      floor[k] = values[j];
      continue;
    }
    const double f = static_cast<double>(k - nodes[j]) / static_cast<double>(nodes[j + 1] - nodes[j]);
    floor[k] = values[j] + f * (values[j + 1] - values[j]);
  }
  return floor;
}

}  // namespace stengmc
