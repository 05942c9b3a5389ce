#pragma once
//! The velocity envelope of a freely oscillating asperity after breakaway, from the
//! first-order averaged equation (Krylov–Bogoliubov averaging; Bogoliubov & Mitropolsky,
//! "Asymptotic Methods in the Theory of Non-Linear Oscillations", 1961, ch. 1; Nayfeh &
//! Mook, "Nonlinear Oscillations", 1979, §4.1).
//!
//! After breakaway an asperity of Model 2 (MODEL.md §1) oscillates around x_eq with
//! x' = A cos(theta). Averaging m x'' + c x' + k x = F(v_b - x') over one period gives
//!
//!   dA/ds = -(c / 2m) A + G(A) / m,   G(A) = (1 / 2 pi) integral_0^{2 pi} F(v_b - A cos theta) cos theta dtheta,
//!
//! and no change of frequency (the friction depends on cos theta only, so its sin theta
//! component vanishes). G < 0: where x' comes close to v_b the regularised friction
//! weakens, which damps the oscillation beyond c. Neither term depends on k, so A(s) is ONE
//! curve per device: every asperity's envelope is this curve, shifted in time. Measured
//! against the forward model (k = 40-120 N/m, v_b = 5, 10 m/s): a damped cosine on this
//! envelope with its time shift and phase fitted leaves 6e-4 to 1e-3 of the atom's L2 norm,
//! almost all within 3 us of breakaway (against 1-3 % for a damped cosine at rate c / 2m).
#include <vector>

#include "inverse/known_device.hpp"

namespace stengmc {

class FrictionEnvelope {
 public:
  //! A(s) for s in [0, span_s], A(0) = v_b, tabulated at `step_s` (linear interpolation
  //! between: A changes by ~1e-7 relative per 10 ns step after the first microsecond).
  FrictionEnvelope(const KnownDevice& device, double span_s, double step_s);

  //! A(s) [m/s]; s is clamped to the tabulated span.
  [[nodiscard]] double at(double s) const;
  //! dA/ds [m/s^2] (from the averaged equation itself, not by differencing).
  [[nodiscard]] double slope(double s) const;
  //! G(A) [N]: the averaged friction component in phase with the velocity (adaptive
  //! Gauss–Kronrod quadrature; the friction changes sharply near theta = 0 where A -> v_b).
  [[nodiscard]] double averaged_friction(double amplitude_m_per_s) const;

  [[nodiscard]] double span_s() const { return step_s_ * static_cast<double>(values_.size() - 1); }
  [[nodiscard]] double step_s() const { return step_s_; }
  //! The table itself (A and dA/ds at s = j step), for loops that walk it sample by sample.
  [[nodiscard]] const std::vector<double>& values() const { return values_; }
  [[nodiscard]] const std::vector<double>& slopes() const { return slopes_; }

 private:
  //! G(A) from its table (linear interpolation on 4096 amplitudes in [0, v_b]).
  [[nodiscard]] double tabulated_friction(double amplitude_m_per_s) const;

  KnownDevice device_;
  std::vector<double> friction_table_;  // G at A = v_b j / (size - 1)
  double step_s_ = 0.0;
  std::vector<double> values_;
  std::vector<double> slopes_;
};

}  // namespace stengmc
