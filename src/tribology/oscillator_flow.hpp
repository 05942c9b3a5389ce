#pragma once
//! The exact flow of the damped linear oscillator z'' + 2 zeta z' + z = 0 (scaled time,
//! unit natural frequency): the motion Model 2 follows while its friction is frozen at
//! its linearisation (model2_integrator.cpp), in closed form.
#include <cmath>

namespace stengmc {

//! exp(tau M) for M = [[0, 1], [-1, -2 zeta]], acting on (z, z'):
//! exp(tau M) = e^{-zeta tau} [C I + S (M + zeta I)] with C = cos(w tau), S = sin(w tau) / w,
//! w = sqrt(1 - zeta^2) (Cayley-Hamilton: M + zeta I squares to (zeta^2 - 1) I), and the
//! hyperbolic counterparts for zeta > 1, written with the two decay rates so nothing
//! overflows however stiff the over-damped oscillator is.
struct OscillatorFlow {
  double m00 = 1.0, m01 = 0.0, m10 = 0.0, m11 = 1.0;

  //! The flow over scaled time `tau` >= 0 for damping ratio `zeta` (any sign).
  static OscillatorFlow over(double zeta, double tau) {
    double decay_cos = 0.0;  // e^{-zeta tau} C
    double decay_sin = 0.0;  // e^{-zeta tau} S
    if (zeta < 1.0) {
      const double w = std::sqrt((1.0 - zeta) * (1.0 + zeta));
      const double e = std::exp(-zeta * tau);
      decay_cos = e * std::cos(w * tau);
      decay_sin = e * (w > 0.0 ? std::sin(w * tau) / w : tau);
    } else {
      const double mu = std::sqrt((zeta - 1.0) * (zeta + 1.0));
      if (mu * tau < 20.0) {
        const double e = std::exp(-zeta * tau);
        decay_cos = e * std::cosh(mu * tau);
        decay_sin = e * (mu > 0.0 ? std::sinh(mu * tau) / mu : tau);
      } else {
        const double slow = std::exp(-tau / (zeta + mu));  // rate 1 / (zeta + mu) = zeta - mu, without cancellation
        const double fast = std::exp(-(zeta + mu) * tau);
        decay_cos = 0.5 * (slow + fast);
        decay_sin = 0.5 * (slow - fast) / mu;
      }
    }
    return {decay_cos + zeta * decay_sin, decay_sin, -decay_sin, decay_cos - zeta * decay_sin};
  }

  //! The flow over twice the time: this one applied twice (4 multiply-adds per entry,
  //! instead of another exponential and sine).
  [[nodiscard]] OscillatorFlow doubled() const {
    return {m00 * m00 + m01 * m10, m00 * m01 + m01 * m11, m10 * m00 + m11 * m10, m10 * m01 + m11 * m11};
  }

  //! (z, z') advanced by the flow, in place.
  void apply(double& z, double& dz) const {
    const double z1 = m00 * z + m01 * dz;
    dz = m10 * z + m11 * dz;
    z = z1;
  }
};

}  // namespace stengmc
