#include "inverse/sample_statistics.hpp"

#include <algorithm>
#include <cmath>

namespace stengmc {

double sample_median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

double sample_sd_log(const std::vector<double>& v) {
  if (v.size() < 2) return 0.0;
  double mean = 0.0, var = 0.0;
  for (double x : v) mean += std::log(x) / static_cast<double>(v.size());
  for (double x : v) var += (std::log(x) - mean) * (std::log(x) - mean) / static_cast<double>(v.size() - 1);
  return std::sqrt(var);
}

}  // namespace stengmc
