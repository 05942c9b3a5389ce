#pragma once
//! The known device's friction law in the units the atoms use (docs/inverse.md, "atoms"):
//! per unit load and relative to f_ref = F(v_b)/N, the force an asperity feels while it
//! oscillates about its mean displacement, so that everything below depends on the device's
//! law, belt velocity and regularisation, and on nothing an asperity varies (k, N, c).
//!
//!  - phi(u) = F(v_b (1 - u)) / (N f_ref): the friction at velocity x' = u v_b;
//!  - G(A) = (1/pi) integral_0^pi phi(A cos t) cos t dt: the friction's share in phase with a
//!    velocity A v_b cos t, the Krylov–Bogoliubov average that damps the envelope beyond c
//!    (friction_envelope.hpp): dA/dt = -d A + beta G(A), beta = N f_ref / (m v_b);
//!  - the creep while the belt carries the asperity: the relative velocity v_r on the
//!    rising branch of F at which the friction supplies a share y of N f_ref.
#include <vector>

#include "inverse/known_device.hpp"

namespace stengmc {

class FrictionRatios {
 public:
  explicit FrictionRatios(const KnownDevice& device);

  //! f_ref = F(v_b) / N [-].
  [[nodiscard]] double reference() const { return reference_; }
  //! G(A) for A in [0, 1] (clamped), from a table on 4096 amplitudes [-].
  [[nodiscard]] double averaged(double amplitude) const;
  //! G(A) by adaptive Gauss–Kronrod quadrature (what the table holds) [-].
  [[nodiscard]] double averaged_by_quadrature(double amplitude) const;
  //! The relative velocity v_r >= 0 at which F(v_r) = y N f_ref on the rising branch of F
  //! (y clamped to [0, the branch's top]), by a table in y [m/s].
  [[nodiscard]] double creep_velocity(double share) const;
  //! q0 = -lim_{A -> 0} G(A) / A: the friction's small-amplitude damping, beta q0 [1/s] added to
  //! d; it also lowers the oscillation's frequency as viscous damping does [-].
  [[nodiscard]] double linear_damping() const { return linear_damping_; }
  //! The largest share the rising branch reaches, F_max / (N f_ref) [-].
  [[nodiscard]] double largest_share() const { return largest_share_; }

 private:
  KnownDevice device_;
  double reference_ = 0.0;
  std::vector<double> averaged_;      // G at A = j / (size - 1)
  double largest_share_ = 1.0;
  double linear_damping_ = 0.0;
  std::vector<double> creep_;         // v_r at y = largest_share j / (size - 1)
};

}  // namespace stengmc
