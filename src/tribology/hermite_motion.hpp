#pragma once
//! Dense output of an ODE solver: quintic Hermite interpolation of x through (x, x', x'')
//! at both ends of each accepted step.
#include <array>
#include <cstddef>
#include <vector>

#include "tribology/model2_integrator.hpp"
#include "tribology/motion.hpp"

namespace stengmc {

//! Piecewise quintic Hermite motion: on each step x(t) is the quintic matching x, x', x''
//! at both ends, so x is C^2 and x' is C^1 across knots. Its error is O(h^6 x^(6)) in x
//! and O(h^5) in x', below the integrator's own local error for the steps it takes.
class HermiteMotion final : public Motion {
 public:
  //! Takes knots with strictly increasing times (at least one).
  //! @throws ModelError if the knots are empty or not increasing.
  explicit HermiteMotion(std::vector<MotionKnot> knots);

  //! State at t [s], t within [first knot, last knot] (1e-9 relative slack at the ends).
  //! @throws ModelError for t outside that range.
  [[nodiscard]] PhasePoint at(double t_s, Side side = Side::right) const override;

  //! Empty: x is C^2 everywhere (the stiff transitions are resolved by the step sizes).
  [[nodiscard]] const std::vector<double>& breakpoints() const override { return breakpoints_; }

  //! Number of knots (accepted steps + 1).
  [[nodiscard]] std::size_t knot_count() const { return knots_.size(); }

  //! Knot i.
  [[nodiscard]] const MotionKnot& knot(std::size_t i) const { return knots_[i]; }

  //! State at t [s] on the interval [knot(i), knot(i+1)] (no search; t may lie outside
  //! the interval, which extrapolates the local quintic).
  [[nodiscard]] PhasePoint on_interval(std::size_t i, double t_s) const;

  //! Velocity on interval i as a quartic in s = (t - t_i) / (t_{i+1} - t_i), s in [0, 1]:
  //! x'(s) = sum_n c[n] s^n [m/s]. Cheap to evaluate and to bound (event search).
  [[nodiscard]] std::array<double, 5> velocity_polynomial(std::size_t i) const;

  //! Index i of the interval [knot(i), knot(i+1)] holding t (clamped to the first/last).
  [[nodiscard]] std::size_t interval_of(double t_s) const;

 private:
  std::vector<MotionKnot> knots_;
  std::vector<double> breakpoints_;
};

}  // namespace stengmc
