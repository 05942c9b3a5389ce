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

//! Model 2's friction law (params.friction_law) at one normal load.
class StribeckFriction {
 public:
  //! The law of `params.friction_law` for normal load `normal_load_n` [N].
  StribeckFriction(const Model2Params& params, double normal_load_n)
      : parameters_{normal_load_n, params.friction.kinetic_coefficient, params.friction.static_coefficient,
                    params.stribeck_decay_s_per_m, params.atan_sharpness_s_per_m},
        law_(params.friction_law) {}

  //! F(v_r) [N] for relative velocity v_r [m/s].
  [[nodiscard]] double force(double v_r) const { return law_->force(parameters_, v_r); }

  //! F at `count` relative velocities [m/s] into force_n [N]: the same values as force().
  void forces(const double* v_r, double* force_n, std::size_t count) const {
    law_->forces(parameters_, v_r, force_n, count);
  }

  //! F(v_r) [N] and dF/dv_r [N s/m] together (they share the transcendental calls).
  void force_and_slope(double v_r, double& force_n, double& slope_n_s_per_m) const {
    const ForceAndSlope f = law_->force_and_slope(parameters_, v_r);
    force_n = f.force_n;
    slope_n_s_per_m = f.slope_n_s_per_m;
  }

 private:
  FrictionParameters parameters_;
  const FrictionLaw* law_;
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

//! The free oscillator's state at the start of an oscillator piece that begins at knot
//! `start`: (x_h, x_h' / w0) = (x - centre - x_p, x' / w0 - x_p' / w0) at tau = 0 [m].
inline void free_oscillator_start(const MotionKnot& start, const MotionPiece& piece, double w0, double& z, double& dz) {
  z = start.x_m - piece.centre_m - piece.particular_m[0];
  dz = start.v_m_per_s / w0 - piece.particular_m[1];
}

//! What integrate_model2 returns.
struct Model2Integration {
  std::vector<MotionKnot> knots;   //!< t = 0, then the end of every accepted step, up to t_end
  std::vector<MotionPiece> pieces; //!< one per step: pieces[i] joins knots[i] and knots[i + 1]
  double natural_frequency_rad_per_s = 0.0;  //!< w0 = sqrt(k/m), the oscillator pieces' time scale
  std::size_t accepted_steps = 0;  //!< accepted steps of either kind
  std::size_t oscillator_steps = 0;  //!< of those, steps of the sliding propagator
  std::size_t rejected_steps = 0;  //!< steps rejected by either error test (or non-finite)
};

//! The length scale Model 2's integrators measure displacement in [m]: the sticking
//! displacement mu N / k (mu the larger coefficient), or what the initial state and the belt
//! impose when friction is (nearly) absent (w0 = sqrt(k/m)); 1 um when all of them vanish.
double model2_length_scale(const Asperity& asperity, const Model2Params& params, double k, double w0);

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
