#include "inverse/residual_segments.hpp"

#include <algorithm>
#include <cmath>

#include <boost/math/special_functions/gamma.hpp>

#include "core/error.hpp"
#include "core/standard_normal.hpp"

namespace stengmc {

WorstSegment worst_residual_segment(std::span<const double> residual, double level_v, std::size_t first, std::size_t segments) {
  if (!(level_v > 0.0) || !std::isfinite(level_v)) throw Error("worst_residual_segment: the noise level must be > 0 and finite");
  if (segments == 0 || first >= residual.size() || residual.size() - first < segments)
    throw Error("worst_residual_segment: fewer samples than segments");
  const std::size_t length = (residual.size() - first) / segments;
  WorstSegment worst;
  worst.segments = segments;
  for (std::size_t s = 0; s < segments; ++s) {
    const std::size_t begin = first + s * length, end = s + 1 == segments ? residual.size() : begin + length;
    double sum = 0.0;
    for (std::size_t t = begin; t < end; ++t) sum += residual[t] * residual[t];
    const double p = boost::math::gamma_q(0.5 * static_cast<double>(end - begin), 0.5 * sum / (level_v * level_v));
    if (p < worst.p_value) worst.p_value = p, worst.first_sample = begin, worst.last_sample = end - 1;
  }
  return worst;
}

double bonferroni_p_bound(double sigmas, std::size_t tests) {
  // One-sided normal tail Phi(-z), shared among the tests.
  return phi_cdf(-sigmas) / static_cast<double>(std::max<std::size_t>(tests, 1));
}

}  // namespace stengmc
