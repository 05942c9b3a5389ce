#pragma once
//! Per-asperity normal loads of a given spread (MODEL.md §4.4, "load spread"): the
//! Greenwood–Williamson picture of a rough surface (Greenwood & Williamson, Proc. R. Soc.
//! Lond. A 295 (1966) 300) with Gaussian summit heights, of which the summits in contact
//! are those above the flat's separation, each loaded as a Hertz sphere,
//! N_i ∝ (z_i − d)^{3/2}. In units of the height's standard deviation, with Z standard
//! normal and δ the separation,
//!
//!   N_i = N̄ (Z_i − δ)^{3/2} / M_{3/2}(δ),   M_p(δ) = E[(Z − δ)^p | Z > δ],
//!
//! so the load law's mean is N̄ and its coefficient of variation is
//!
//!   CV(δ)² = M_3(δ) / M_{3/2}(δ)² − 1,
//!
//! which rises from 0 (δ → −∞: every summit pressed deep, loads alike) to
//! √(Γ(4)/Γ(5/2)² − 1) = 1.5477 (δ → ∞: the excess over δ becomes exponential). The
//! separation is solved for a target CV; the heights of the summits in contact are drawn
//! from the normal law conditioned on Z > δ.
#include <cstddef>

#include "core/random_stream.hpp"

namespace stengmc {

//! The largest CV a load spread accepts: close to the limit 1.548, the separation (and the
//! share of summits it leaves in contact, Q(δ)) runs beyond what a draw resolves.
inline constexpr double MAX_LOAD_CV = 1.4;

//! M_p(δ) = E[(Z − δ)^p | Z > δ] for standard normal Z, p > 0 (adaptive Gauss–Kronrod
//! quadrature, relative accuracy ~1e-13).
double excess_height_moment(double power, double separation);

//! CV(δ) of the loads N ∝ (Z − δ)^{3/2} given Z > δ [-].
double load_cv_at_separation(double separation);

//! The separation δ whose load law has coefficient of variation `cv` in (0, MAX_LOAD_CV]
//! (TOMS 748 to 1e-14 in δ).
double separation_for_load_cv(double cv);

//! One summit in contact: its standardised height and its load.
struct LoadedSummit {
  double height_score = 0.0;  //!< Z_i, the height in standard deviations from the mean [-]
  double load_n = 0.0;        //!< N_i [N]
};

//! The load law of one surface: mean load N̄ and CV; draws summits in contact.
class LoadSpread {
 public:
  //! @param mean_load_n N̄ > 0 [N]; @param cv in [0, MAX_LOAD_CV] (0: every load N̄,
  //! heights unconditioned)
  LoadSpread(double mean_load_n, double cv);

  //! One summit in contact: Z from N(0, 1) conditioned on Z > δ by inverse-CDF sampling
  //! (one uniform draw from `engine`), its load from Z. With cv = 0, Z ~ N(0, 1) and N = N̄.
  [[nodiscard]] LoadedSummit draw(RandomEngine& engine) const;
  //! The p-quantile of the load law, 0 < p < 1 [N].
  [[nodiscard]] double load_quantile(double p) const;

  [[nodiscard]] double mean_load_n() const { return mean_load_n_; }
  [[nodiscard]] double cv() const { return cv_; }
  //! δ (-inf when cv = 0) [-].
  [[nodiscard]] double separation() const { return separation_; }

 private:
  double mean_load_n_ = 0.0;
  double cv_ = 0.0;
  double separation_ = 0.0;
  double load_per_excess_ = 0.0;  // N̄ / M_{3/2}(δ)
};

}  // namespace stengmc
