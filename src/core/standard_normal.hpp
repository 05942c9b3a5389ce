#pragma once
//! The standard normal cdf and density, safe at +-infinity (copulas, the normal and
//! lognormal families' moments, residual tests' tails, tracking's detection odds).
#include <cmath>

namespace stengmc {

inline double phi_cdf(double z) { return 0.5 * std::erfc(-z / std::sqrt(2.0)); }
inline double phi_pdf(double z) { return std::isinf(z) ? 0.0 : std::exp(-0.5 * z * z) / std::sqrt(2.0 * M_PI); }

}  // namespace stengmc
