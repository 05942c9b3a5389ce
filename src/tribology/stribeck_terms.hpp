#pragma once
//! The pieces the Stribeck friction laws of MODEL.md §1 are made of, at one v_r, with fast
//! forms of exp and atan for the ranges the solver lives in (they were a quarter and a
//! fifth of its time with std::exp and std::atan).
#include <cmath>

#include "core/processor_features.hpp"
#include "tribology/friction_law.hpp"

namespace stengmc::stribeck {

inline constexpr double TWO_OVER_PI = 0.63661977236758134308;
inline constexpr double HALF_PI = 1.57079632679489661923;

// exp(-z) for z >= 0. With Table-2 c_s = 1e-7 s/m, z = c_s |v_r| stays below 1e-5, where
// the degree-5 Taylor polynomial is exact to rounding (remainder z^6/720 < 1.4e-21 for
// z < 1e-3) and ~3x cheaper than std::exp.
inline double decay_series(double z) {
  return 1.0 - z * (1.0 - z * (0.5 - z * (1.0 / 6.0 - z * (1.0 / 24.0 - z * (1.0 / 120.0)))));
}
inline double decay(double z) {
  if (z < 1e-3) return decay_series(z);
  return std::exp(-z);
}

// atan(z). Sliding keeps |s v_r| in the hundreds to thousands, where
// atan(z) = pi/2 - atan(1/z) and atan(1/z) is its odd Taylor series to y^9 (remainder
// y^11 / 11 < 1.3e-21 for |1/z| <= 1/64, below rounding): one division and five
// multiply-adds. arctan_far is that series alone, for |z| >= 64 only (no branch, so a loop
// of them vectorises); copysign is the sign the branch chose, as z is neither 0 nor NaN there.
inline double arctan_far(double z) {
  const double y = 1.0 / std::abs(z);
  const double y2 = y * y;
  const double r = HALF_PI - y * (1.0 - y2 * (1.0 / 3.0 - y2 * (1.0 / 5.0 - y2 * (1.0 / 7.0 - y2 * (1.0 / 9.0)))));
  return std::copysign(r, z);
}
inline double arctan(double z) {
  if (!(std::abs(z) >= 64.0)) return std::atan(z);  // also NaN
  return arctan_far(z);
}

//! Whether v_r lies where both fast forms hold (decay_series, arctan_far).
inline bool in_series_range(const FrictionParameters& p, double v_r) {
  return std::abs(p.atan_sharpness_s_per_m * v_r) >= 64.0 && p.stribeck_decay_s_per_m * std::abs(v_r) < 1e-3;
}

//! (mu_s - mu_k) exp(-c_s |v_r|): the static excess, decaying with sliding speed.
inline double excess(const FrictionParameters& p, double v_r) {
  return (p.static_coefficient - p.kinetic_coefficient) * decay(p.stribeck_decay_s_per_m * std::abs(v_r));
}

//! (2/pi) atan(s v_r): the regularised sign of v_r.
inline double regularised_sign(const FrictionParameters& p, double v_r) {
  return TWO_OVER_PI * arctan(p.atan_sharpness_s_per_m * v_r);
}

//! excess() and regularised_sign() by their series alone: where in_series_range holds,
//! the same values, without a branch.
inline double excess_series(const FrictionParameters& p, double v_r) {
  return (p.static_coefficient - p.kinetic_coefficient) * decay_series(p.stribeck_decay_s_per_m * std::abs(v_r));
}
inline double regularised_sign_far(const FrictionParameters& p, double v_r) {
  return TWO_OVER_PI * arctan_far(p.atan_sharpness_s_per_m * v_r);
}

//! The two pieces every law combines, by the series alone (`Series`: the caller knows v_r
//! is in their range) or by the general forms.
struct ExcessAndSign {
  double excess;
  double sign;
};
template <bool Series>
inline ExcessAndSign excess_and_sign(const FrictionParameters& p, double v_r) {
  if constexpr (Series) return {excess_series(p, v_r), regularised_sign_far(p, v_r)};
  else return {excess(p, v_r), regularised_sign(p, v_r)};
}

//! The branch-free loop of forces_by: `SeriesForce` at each v_r, inlined (so compiled for
//! whatever target the caller is compiled for).
template <double (*SeriesForce)(const FrictionParameters&, double)>
[[gnu::always_inline]] inline void series_forces(const FrictionParameters& p, const double* v_r, double* force_n,
                                                 std::size_t count) {
  const FrictionParameters local = p;  // not reloaded after every store (it cannot alias force_n)
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC ivdep  // force_n may be v_r itself, element for element, never shifted
#endif
  for (std::size_t i = 0; i < count; ++i) force_n[i] = SeriesForce(local, v_r[i]);
}

template <double (*SeriesForce)(const FrictionParameters&, double)>
void series_forces_baseline(const FrictionParameters& p, const double* v_r, double* force_n, std::size_t count) {
  series_forces<SeriesForce>(p, v_r, force_n, count);
}

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define STENGMC_SERIES_FORCES_AVX2 1
//! The same loop in AVX registers (four lanes). AVX2 alone, not FMA: lane by lane the same
//! operations as the baseline's SSE2 pairs, so the same bits.
template <double (*SeriesForce)(const FrictionParameters&, double)>
[[gnu::target("avx2")]] void series_forces_avx2(const FrictionParameters& p, const double* v_r, double* force_n,
                                                std::size_t count) {
  series_forces<SeriesForce>(p, v_r, force_n, count);
}
#endif

//! FrictionLaw::forces for a law whose force() is `Force`, `SeriesForce` being the same
//! formula through excess_series and regularised_sign_far: where every v_r of the batch
//! lies in their range (sliding, where the sliding propagator works), a branch-free loop
//! the compiler turns into SIMD (SSE2 pairs, or four AVX2 lanes where the processor has
//! them; no FMA either way: the same values), else force by force.
template <double (*Force)(const FrictionParameters&, double), double (*SeriesForce)(const FrictionParameters&, double)>
void forces_by(const FrictionParameters& p, const double* v_r, double* force_n, std::size_t count) {
  bool series = true;
  for (std::size_t i = 0; i < count; ++i) series &= in_series_range(p, v_r[i]);
  if (series) {
#ifdef STENGMC_SERIES_FORCES_AVX2
    if (processor_has_avx2()) {
      series_forces_avx2<SeriesForce>(p, v_r, force_n, count);
      return;
    }
#endif
    series_forces_baseline<SeriesForce>(p, v_r, force_n, count);
  } else {
    for (std::size_t i = 0; i < count; ++i) force_n[i] = Force(p, v_r[i]);
  }
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
