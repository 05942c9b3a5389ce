#pragma once
//! The velocity envelopes of freely oscillating asperities after breakaway, for every load
//! and damping an inversion may meet (docs/inverse.md, "atoms"): the Krylov–Bogoliubov
//! averaged equation (Bogoliubov & Mitropolsky 1961, ch. 1; Nayfeh & Mook 1979, §4.1) in
//! units of v_b,
//!
//!   dA/ds = -d A + beta G(A),   A(0) = 1,   beta = N f_ref / (m v_b),
//!
//! with G the friction's share in phase with the velocity (friction_ratios.hpp). It holds
//! no k: an asperity's envelope depends on its load (beta) and the damping d = c/2m alone.
//! Tabulated as L = -ln A on the record's step for a grid of beta and d; between nodes L is
//! interpolated linearly in beta and in d, which is exact for the viscous part d s and for
//! the part linear in beta (all of G once A is below ~0.5), and second order in the rest.
#include <span>
#include <vector>

#include "inverse/friction_ratios.hpp"

namespace stengmc {

struct EnvelopeFamilyRange {
  double min_beta_per_s = 0.0, max_beta_per_s = 0.0;  //!< beta range [1/s]
  double min_damping_rate_per_s = 0.0, max_damping_rate_per_s = 0.0;  //!< d range [1/s]
  double span_s = 0.0;                                 //!< longest s needed [s]
  double step_s = 0.0;                                 //!< table step (the record's) [s]
};

class EnvelopeFamily {
 public:
  EnvelopeFamily(const FrictionRatios& ratios, const EnvelopeFamilyRange& range);

  //! A(s_m; beta, d) at s_m = first_s + m step for m < out.size() (1 before s = 0). With `d_dlnbeta`, `d_dd` and `d_ds` (each empty or out.size() long), the
  //! derivatives dA/d ln beta, dA/dd [s] and dA/ds [1/s].
  void evaluate(double beta_per_s, double damping_rate_per_s, double first_s, std::span<double> out,
                std::span<double> d_dlnbeta = {}, std::span<double> d_dd = {}, std::span<double> d_ds = {}) const;

  //! A at one s (slow path: tests and proposals).
  [[nodiscard]] double at(double beta_per_s, double damping_rate_per_s, double s) const;

  //! The s [s] at which the envelope has L = -ln A = `log_amplitude` (>= 0), and the slope
  //! dL/ds there [1/s]; with `ds_dlnbeta`, `ds_dd` also how that s moves with ln beta [s]
  //! and d [s^2] at fixed L.
  double time_at(double beta_per_s, double damping_rate_per_s, double log_amplitude, double* slope = nullptr,
                 double* ds_dlnbeta = nullptr, double* ds_dd = nullptr) const;

  [[nodiscard]] const EnvelopeFamilyRange& range() const { return range_; }

 private:
  //! The table of (beta node i, d node q): L at s = j step.
  [[nodiscard]] const double* row(std::size_t i, std::size_t q) const { return &tables_[(i * d_nodes_.size() + q) * samples_]; }
  //! L at s, and dL/dbeta [s] and dL/dd [s] there, for the bracket (i, wb) x (q, wd); beyond
  //! the table L is extrapolated linearly (G is linear in A there, so L is too).
  double log_amplitude_at(std::size_t i, double wb, std::size_t q, double wd, double s, double* dL_dbeta, double* dL_dd,
                          double* dL_ds) const;
  void bracket_beta(double beta, std::size_t& i, double& w) const;
  void bracket_d(double d, std::size_t& q, double& w) const;

  const FrictionRatios* ratios_;
  EnvelopeFamilyRange range_;
  std::vector<double> beta_nodes_, d_nodes_;
  std::size_t samples_ = 0;
  std::vector<double> tables_;
};

}  // namespace stengmc
