#pragma once
//! Model 2's sliding propagator: long, exact-for-the-oscillator steps where friction is
//! nearly linear (model2_integrator.cpp decides where; this file is the step itself).
//!
//! Frozen at its linearisation at the step start, the scaled system u' = w,
//! w' = -u - 2 zeta w + phi(w) becomes z' = M z + (0, g(w)) with z = (u - b, w),
//! M = [[0, 1], [-1, -2 zeta_e]], 2 zeta_e = -J_ww, b = f_w + u + 2 zeta_e w and the
//! remainder g(w) = phi(w) - phi(w_n) - phi'(w_n) (w - w_n), small while sliding (the
//! friction's curvature over a velocity swing). The remainder along the step is replaced by
//! the polynomial P(s) = sum_{k=2}^{Q+1} c_k s^k (s = tau / h; g and g' vanish at s = 0)
//! through its values at the Q equispaced nodes s = 1/Q .. 1, and z' = M z + (0, P) is
//! solved exactly: z = exp(tau M) (z_0 - z_p(0)) + z_p(tau), where z_p is the polynomial
//! particular solution (coefficients by back substitution, a_j = M^-1 ((j+1) a_{j+1} - e2 d_j))
//! and exp(tau M) the oscillator's closed-form flow (oscillator_flow.hpp). The nodes are
//! first taken on the frozen oscillator, then on the corrected solution (one Picard
//! sweep, converging at the rate h |g'|, ~1e-4 per sweep; a second sweep where needed):
//! an exponential collocation method (Hochbruck & Ostermann, "Exponential integrators",
//! Acta Numerica 19 (2010) 209, Sec. 2.3; exponential Euler with the remainder frozen is
//! its one-node case). Its defect g(z(tau)) - P(tau), checked at the nodes (the Picard
//! error) and at the midpoints of the first and last node intervals (where equispaced
//! interpolation errs most), bounds the local error by h max|defect| (variation of
//! constants with |exp(sM)| <= e^{max(0, -zeta_e) s}), which the caller holds to its
//! tolerance; the dense output is the same exact solution, so it is as accurate inside
//! the step as at its end.
#include <algorithm>
#include <array>
#include <cmath>

#include "tribology/model2_scaled_system.hpp"

namespace stengmc {

//! Collocation nodes per step. Fewer nodes mean a lower order (the local error bound
//! scales as h^(nodes + 3)) but cheaper attempts; measured on one asperity-run (k = 25,
//! 50 us), integration time against the node count, v_b = 1 / 10 m/s at the default
//! tolerance: 6 nodes 86 / 125 us, 5 nodes 80 / 109 us, 4 nodes 79 / 108 us (8 nodes: slower
//! still than 6). Five keep the smaller steps' accuracy margin of four at the same cost.
inline constexpr int PROPAGATOR_NODES = 5;
//! Largest |z_p(0)| (in units of the length scale, ~ the motion's amplitude) a step may
//! have: the free oscillator and the polynomial then cancel by at most this factor, so
//! the dense output keeps all but ~1.5 of its digits.
inline constexpr double PROPAGATOR_CANCELLATION = 30.0;
//! Coefficients of the particular solution's displacement, tau^0 .. tau^(NODES + 1).
inline constexpr int PROPAGATOR_TERMS = PROPAGATOR_NODES + 2;
static_assert(PROPAGATOR_TERMS == MOTION_PIECE_TERMS, "MotionPiece stores the propagator's polynomial");

//! One attempted propagator step.
struct PropagatorStep {
  Vec2 y_end;            //!< scaled state at the step end
  double error = 0.0;    //!< weighted error norm (<= 1: acceptable), inf if not finite
  //! false where the remainder is so far from small that its polynomial response exceeds
  //! PROPAGATOR_CANCELLATION length scales: exp(tau M) (z_0 - z_p(0)) and z_p(tau) would
  //! cancel and cost digits (near a stick/slip transition). RODAS4 takes such a step.
  bool suitable = true;
  double zeta = 0.0;     //!< damping ratio of the frozen oscillator
  double centre = 0.0;   //!< its equilibrium b (scaled)
  std::array<double, PROPAGATOR_TERMS> particular{};  //!< u_p(tau) = sum_j particular[j] tau^j (scaled)
};

//! A step of scaled length h from y, where f and jac are the right-hand side and its
//! Jacobian at y; error measured as RODAS4's (weighted RMS with tolerance `tol`).
PropagatorStep propagator_step(const ScaledSystem& sys, const Vec2& y, const Vec2& f, const Mat2& jac, double h,
                               double tol);

//! The weighted RMS error norm the integrators share: sk = tol + tol max(|y0|, |y1|).
//! Inline: called once per RODAS4 step from another file, on the step's critical path.
inline double error_norm(const Vec2& err, const Vec2& y0, const Vec2& y1, double tol) {
  double sum = 0.0;
  for (int i = 0; i < 2; ++i) {
    const double sk = tol + tol * std::max(std::abs(y0[i]), std::abs(y1[i]));
    const double r = err[i] / sk;
    sum += r * r;
  }
  return std::sqrt(0.5 * sum);
}

}  // namespace stengmc
