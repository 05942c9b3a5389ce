#pragma once
//! The pieces the Stribeck friction laws of MODEL.md §1 are made of, at one v_r, with fast
//! forms of exp and atan for the ranges the solver lives in (they were a quarter and a
//! fifth of its time with std::exp and std::atan).
#include <cmath>

#include "tribology/friction_law.hpp"

namespace stengmc::stribeck {

inline constexpr double TWO_OVER_PI = 0.63661977236758134308;
inline constexpr double HALF_PI = 1.57079632679489661923;

// exp(-z) for z >= 0. With Table-2 c_s = 1e-7 s/m, z = c_s |v_r| stays below 1e-5, where
// the degree-5 Taylor polynomial is exact to rounding (remainder z^6/720 < 1.4e-21 for
// z < 1e-3) and ~3x cheaper than std::exp.
inline double decay(double z) {
  if (z < 1e-3) return 1.0 - z * (1.0 - z * (0.5 - z * (1.0 / 6.0 - z * (1.0 / 24.0 - z * (1.0 / 120.0)))));
  return std::exp(-z);
}

// atan(z). Sliding keeps |s v_r| in the hundreds to thousands, where
// atan(z) = pi/2 - atan(1/z) and atan(1/z) is its odd Taylor series to y^9 (remainder
// y^11 / 11 < 1.3e-21 for |1/z| <= 1/64, below rounding): one division and five
// multiply-adds.
inline double arctan(double z) {
  const double a = std::abs(z);
  if (!(a >= 64.0)) return std::atan(z);  // also NaN
  const double y = 1.0 / a;
  const double y2 = y * y;
  const double r = HALF_PI - y * (1.0 - y2 * (1.0 / 3.0 - y2 * (1.0 / 5.0 - y2 * (1.0 / 7.0 - y2 * (1.0 / 9.0)))));
  return z < 0.0 ? -r : r;
}

//! (mu_s - mu_k) exp(-c_s |v_r|): the static excess, decaying with sliding speed.
inline double excess(const FrictionParameters& p, double v_r) {
  return (p.static_coefficient - p.kinetic_coefficient) * decay(p.stribeck_decay_s_per_m * std::abs(v_r));
}

//! (2/pi) atan(s v_r): the regularised sign of v_r.
inline double regularised_sign(const FrictionParameters& p, double v_r) {
  return TWO_OVER_PI * arctan(p.atan_sharpness_s_per_m * v_r);
}

//! Every piece with its slope.
struct Terms {
  double excess;             //!< (mu_s - mu_k) exp(-c_s |v_r|)
  double sign;               //!< (2/pi) atan(s v_r)
  double sign_slope;         //!< d sign / dv_r [s/m]
  double excess_slope_sign;  //!< d excess / dv_r times sign [s/m]
};

inline Terms terms(const FrictionParameters& p, double v_r) {
  const double e = excess(p, v_r);
  const double sv = p.atan_sharpness_s_per_m * v_r;
  const double sign = TWO_OVER_PI * arctan(sv);
  // d/dv exp(-c_s|v|) = -c_s sign(v) exp(-c_s|v|); sign(v) * atan(s v) = |atan(s v)|, so
  // F stays C^1 at v_r = 0 and the Jacobian is exact on both sides.
  return {e, sign, TWO_OVER_PI * p.atan_sharpness_s_per_m / (1.0 + sv * sv), -p.stribeck_decay_s_per_m * e * std::abs(sign)};
}

}  // namespace stengmc::stribeck
