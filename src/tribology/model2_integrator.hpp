#pragma once
//! The error-controlled, L-stable integrator behind Model 2 (MODEL.md §1): RODAS4 on the
//! nondimensional 2x2 system, returning the accepted steps as Hermite knots.
#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

#include "model/asperity.hpp"
#include "model/motion_knot.hpp"
#include "tribology/model2.hpp"

namespace stengmc {

//! The friction law F(v_r) of Model 2 with its slope, for one normal load.
class StribeckFriction {
 public:
  //! Law of `params.friction_form` for normal load `normal_load_n` [N].
  StribeckFriction(const Model2Params& params, double normal_load_n)
      : load_n_(normal_load_n),
        mu_k_(params.friction.kinetic_coefficient),
        mu_delta_(params.friction.static_coefficient - params.friction.kinetic_coefficient),
        decay_s_per_m_(params.stribeck_decay_s_per_m),
        sharpness_s_per_m_(params.atan_sharpness_s_per_m),
        literal_(params.friction_form == FrictionForm::literal) {}

  //! F(v_r) [N] for relative velocity v_r [m/s].
  [[nodiscard]] double force(double v_r) const {
    const double stribeck = mu_delta_ * decay(decay_s_per_m_ * std::abs(v_r));
    const double regularised_sign = TWO_OVER_PI * arctan(sharpness_s_per_m_ * v_r);
    return literal_ ? load_n_ * (mu_k_ + stribeck * regularised_sign)
                    : load_n_ * (mu_k_ + stribeck) * regularised_sign;
  }

  //! F(v_r) [N] and dF/dv_r [N s/m] together (they share the transcendental calls).
  void force_and_slope(double v_r, double& force_n, double& slope_n_s_per_m) const {
    const double stribeck = mu_delta_ * decay(decay_s_per_m_ * std::abs(v_r));
    const double sv = sharpness_s_per_m_ * v_r;
    const double regularised_sign = TWO_OVER_PI * arctan(sv);
    const double sign_slope = TWO_OVER_PI * sharpness_s_per_m_ / (1.0 + sv * sv);
    // d/dv exp(-c_s|v|) = -c_s sign(v) exp(-c_s|v|); sign(v) * atan(s v) = |atan(s v)|, so
    // F stays C^1 at v_r = 0 and the Jacobian below is exact on both sides.
    const double stribeck_slope_times_sign = -decay_s_per_m_ * stribeck * std::abs(regularised_sign);
    if (literal_) {
      force_n = load_n_ * (mu_k_ + stribeck * regularised_sign);
      slope_n_s_per_m = load_n_ * (stribeck * sign_slope + stribeck_slope_times_sign);
    } else {
      force_n = load_n_ * (mu_k_ + stribeck) * regularised_sign;
      slope_n_s_per_m = load_n_ * ((mu_k_ + stribeck) * sign_slope + stribeck_slope_times_sign);
    }
  }

 private:
  // exp(-z) for z >= 0. With Table-2 c_s = 1e-7 s/m, z = c_s |v_r| stays below 1e-5, where
  // the degree-5 Taylor polynomial is exact to rounding (remainder z^6/720 < 1.4e-21 for
  // z < 1e-3) and ~3x cheaper than std::exp, which was a quarter of the solver's time.
  static double decay(double z) {
    if (z < 1e-3) return 1.0 - z * (1.0 - z * (0.5 - z * (1.0 / 6.0 - z * (1.0 / 24.0 - z * (1.0 / 120.0)))));
    return std::exp(-z);
  }
  // atan(z). Sliding keeps |s v_r| in the hundreds to thousands, where
  // atan(z) = pi/2 - atan(1/z) and atan(1/z) is its odd Taylor series to y^9 (remainder
  // y^11 / 11 < 1.3e-21 for |1/z| <= 1/64, below rounding): one division and five
  // multiply-adds where std::atan was a fifth of the solver's time.
  static double arctan(double z) {
    const double a = std::abs(z);
    if (!(a >= 64.0)) return std::atan(z);  // also NaN
    const double y = 1.0 / a;
    const double y2 = y * y;
    const double r = HALF_PI - y * (1.0 - y2 * (1.0 / 3.0 - y2 * (1.0 / 5.0 - y2 * (1.0 / 7.0 - y2 * (1.0 / 9.0)))));
    return z < 0.0 ? -r : r;
  }
  static constexpr double TWO_OVER_PI = 0.63661977236758134308;
  static constexpr double HALF_PI = 1.57079632679489661923;
  double load_n_;
  double mu_k_;
  double mu_delta_;
  double decay_s_per_m_;
  double sharpness_s_per_m_;
  bool literal_;
};

//! Terms of a sliding-propagator piece's polynomial (sliding_propagator.hpp).
inline constexpr int MOTION_PIECE_TERMS = 7;

//! How the motion continues from one knot to the next.
enum class PieceKind : unsigned char {
  //! A RODAS4 step: the quintic Hermite through (x, x', x'') at both knots.
  quintic,
  //! A RODAS4 step while sticking (the linearised system over-damped): the cubic Hermite
  //! through (x, x') only. There x'' from the ODE at a knot is the stiff slope
  //! (~1e4 w0) times the knot's tiny distance from the slow manifold: noise that a
  //! quintic would spread over the step, while x itself is nearly straight.
  cubic,
  //! A step of the sliding propagator, x(t) = centre + x_h(t) + x_p(t) with x_h the free
  //! damped oscillator x_h'' + 2 zeta w0 x_h' + w0^2 x_h = 0 and
  //! x_p(t) = sum_j particular_m[j] tau^j, tau = w0 (t - t_knot), the response to the
  //! friction's curvature (sliding_propagator.hpp).
  oscillator,
};

struct MotionPiece {
  PieceKind kind = PieceKind::quintic;
  double zeta = 0.0;      //!< damping ratio of that oscillator [-]
  double centre_m = 0.0;  //!< its equilibrium displacement [m]
  std::array<double, MOTION_PIECE_TERMS> particular_m{};  //!< x_p's coefficients [m]
};

//! What integrate_model2 returns.
struct Model2Integration {
  std::vector<MotionKnot> knots;   //!< t = 0, then the end of every accepted step, up to t_end
  std::vector<MotionPiece> pieces; //!< one per step: pieces[i] joins knots[i] and knots[i + 1]
  double natural_frequency_rad_per_s = 0.0;  //!< w0 = sqrt(k/m), the oscillator pieces' time scale
  std::size_t accepted_steps = 0;  //!< accepted steps of either kind
  std::size_t oscillator_steps = 0;  //!< of those, steps of the sliding propagator
  std::size_t rejected_steps = 0;  //!< steps rejected by either error test (or non-finite)
};

//! Integrates one asperity of Model 2 from its initial state to `t_end_s` [s] with local
//! error control at `params.relative_tolerance` (absolute tolerance the same, in units of
//! the length scale described in model2_integrator.cpp): RODAS4 steps, and where friction
//! is nearly linear (sliding, and wherever the frozen oscillator is under-damped) exact
//! steps of the linearised motion whose neglected remainder is estimated and held to the
//! same tolerance (model2_integrator.cpp).
//! @throws ModelError on step size underflow or a step budget exhausted, naming k, v_b, t.
//! @throws InputError for non-positive mass or stiffness, or a non-positive tolerance.
Model2Integration integrate_model2(const Asperity& asperity, const Model2Params& params, double t_end_s);

//! The same into `out`, whose buffers are reused (emptied first, capacity kept).
void integrate_model2(const Asperity& asperity, const Model2Params& params, double t_end_s, Model2Integration& out);

}  // namespace stengmc
