#pragma once
//! Model 2 in the integrators' scaled variables (internal to the tribology solvers).
#include <array>
#include <cmath>
#include <cstddef>

#include <Eigen/Core>

#include "model/asperity.hpp"
#include "tribology/model2.hpp"
#include "tribology/model2_integrator.hpp"

namespace stengmc {

using Vec2 = Eigen::Vector2d;
using Mat2 = Eigen::Matrix2d;

// Model 2 in scaled variables tau = w0 t, u = x / L, w = x' / (w0 L), with w0 = sqrt(k/m):
//   u' = w,  w' = -u - 2 zeta w + F(v_b - w0 L w) / (k L).
// With L ~ mu_s N / k both components are O(1) in every Table-1 case (x up to ~1.2 L,
// velocity swings ~ L w0), so one relative + absolute tolerance fits both.
class ScaledSystem {
 public:
  ScaledSystem(const Asperity& asperity, const Model2Params& params, double length_scale_m)
      : friction_(params, asperity.normal_load_n),
        belt_velocity_(params.belt_velocity_m_per_s),
        velocity_scale_(std::sqrt(asperity.stiffness_n_per_m / asperity.mass_kg) * length_scale_m),
        force_scale_(1.0 / (asperity.stiffness_n_per_m * length_scale_m)),
        two_zeta_(params.damping_n_s_per_m / std::sqrt(asperity.stiffness_n_per_m * asperity.mass_kg)),
        max_friction_n_(std::abs(asperity.normal_load_n) *
                        std::max(std::abs(params.friction.static_coefficient), std::abs(params.friction.kinetic_coefficient))) {}

  //! The friction term F(v_b - w0 L w) / (k L) of the acceleration.
  [[nodiscard]] double friction_term(double w) const {
    return force_scale_ * friction_.force(belt_velocity_ - velocity_scale_ * w);
  }

  //! friction_term at `count` scaled velocities w into `out` (the same values).
  template <std::size_t N>
  void friction_terms(const std::array<double, N>& w, std::array<double, N>& out) const {
    std::array<double, N> v_r;
    for (std::size_t i = 0; i < N; ++i) v_r[i] = belt_velocity_ - velocity_scale_ * w[i];
    friction_.forces(v_r.data(), out.data(), N);
    for (std::size_t i = 0; i < N; ++i) out[i] *= force_scale_;
  }

  //! The largest |friction_term| any v_r gives, N max(mu_s, mu_k) / (k L): both forms of
  //! F stay within N max(mu_s, mu_k) (atan < pi/2, exp(-c_s |v_r|) <= 1).
  [[nodiscard]] double friction_term_bound() const { return force_scale_ * max_friction_n_; }

  //! 2 zeta, the viscous damping in scaled units.
  [[nodiscard]] double two_zeta() const { return two_zeta_; }

  [[nodiscard]] Vec2 rhs(const Vec2& y) const {
    const double force = friction_.force(belt_velocity_ - velocity_scale_ * y[1]);
    return {y[1], -y[0] - two_zeta_ * y[1] + force_scale_ * force};
  }

  //! Right-hand side and its Jacobian at y.
  void rhs_and_jacobian(const Vec2& y, Vec2& f, Mat2& jac) const {
    double force = 0.0;
    double slope = 0.0;
    friction_.force_and_slope(belt_velocity_ - velocity_scale_ * y[1], force, slope);
    f = {y[1], -y[0] - two_zeta_ * y[1] + force_scale_ * force};
    jac << 0.0, 1.0, -1.0, -two_zeta_ - force_scale_ * slope * velocity_scale_;
  }

 private:
  StribeckFriction friction_;
  double belt_velocity_;
  double velocity_scale_;
  double force_scale_;
  double two_zeta_;
  double max_friction_n_;
};

}  // namespace stengmc
