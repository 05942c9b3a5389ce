#include "tribology/domain_check.hpp"

#include <cmath>

namespace stengmc {

std::optional<double> first_domain_exit(const Motion& motion, std::span<const double> times_s,
                                        std::span<const double> x_m, double length_m) {
  for (std::size_t j = 0; j < x_m.size(); ++j) {
    if (x_m[j] < length_m) continue;
    if (j == 0) return times_s[0];
    double lo = times_s[j - 1];
    double hi = times_s[j];
    // Bisection: x(lo) < l <= x(hi); 200 halvings reach adjacent doubles long before.
    for (int iteration = 0; iteration < 200 && std::nextafter(lo, hi) < hi; ++iteration) {
      const double mid = 0.5 * (lo + hi);
      (motion.at(mid).x_m < length_m ? lo : hi) = mid;
    }
    return hi;
  }
  return std::nullopt;
}

}  // namespace stengmc
