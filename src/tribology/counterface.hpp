#pragma once
//! The counterface's excitation of Model 2 (docs/model.md §1.4): each asperity's friction
//! force F_i(v_r) (1 + eps_i(t)), eps_i an Ornstein-Uhlenbeck process, independent per
//! asperity, and how it is sampled on the integrator's grid.
#include <cstdint>

#include <boost/random/normal_distribution.hpp>

#include "core/random_stream.hpp"

namespace stengmc {

//! `[counterface]` of a study: the rough counterface's friction modulation.
struct CounterfaceParams {
  //! eps, rms of the relative friction modulation eps_i(t) [-]; 0: no modulation (today's model).
  double friction_modulation_rms = 0.0;
  //! lambda, correlation length of the counterface profile along the sliding direction [m]:
  //! <eps_i(t) eps_i(t + tau)> = eps^2 exp(-v_b |tau| / lambda).
  double correlation_length_m = 1e-6;

  //! True when the friction is modulated (eps > 0).
  [[nodiscard]] bool active() const { return friction_modulation_rms > 0.0; }
};

//! Largest friction_modulation_rms accepted: 1 + eps_i(t) < 0 (friction pushing the
//! asperity along the belt) then has probability Phi(-1/eps) < 3e-5.
inline constexpr double MAX_FRICTION_MODULATION_RMS = 0.25;

//! Which random stream drives an asperity's modulation: (seed, realisation, asperity index),
//! with StreamKind::counterface (MODEL.md §5).
struct CounterfaceStream {
  std::uint64_t seed = 0;
  std::uint64_t realisation = 0;
  std::uint64_t asperity = 0;
};

//! Correlation time tau_c = lambda / |v_b| of eps_i(t) [s]; infinite for v_b = 0.
double correlation_time_s(const CounterfaceParams& counterface, double belt_velocity_m_per_s);

//! Spacing of the grid eps_i is sampled on [s]: min(tau_c / 20, T_min / 200), T_min the
//! shortest undamped period the asperity reaches (2 pi sqrt(m / k_max)). Between the nodes
//! eps_i is interpolated linearly; that filters the sampled process by sinc^4(omega dt / 2)
//! and folds in its aliases, a relative error of at most ~(omega dt)^2 / 6 + dt^2 / (12 tau_c^2)
//! < 4e-4 on its spectrum at the line (docs/model.md §1.4).
double modulation_step_s(double correlation_time_s, double highest_angular_frequency_rad_per_s);

//! eps_i on the grid t_j = j dt (from the contact onset), drawn node by node with the exact
//! update of the Ornstein-Uhlenbeck process (Gillespie, Phys. Rev. E 54, 2084 (1996), Eq. 1.6):
//! eps_0 = eps xi_0 (the stationary law), eps_{j+1} = rho eps_j + eps sqrt(1 - rho^2) xi_{j+1},
//! rho = exp(-dt / tau_c), xi_j independent standard normals from the asperity's stream.
//! The nodes depend only on (stream, eps, tau_c, dt): bit-identical for any thread count.
class ModulationSequence {
 public:
  ModulationSequence(const CounterfaceStream& stream, double rms, double correlation_time_s, double step_s);

  //! The node index j of the current node and its value eps_j [-].
  [[nodiscard]] std::uint64_t index() const { return index_; }
  [[nodiscard]] double value() const { return value_; }
  //! The next node's value eps_{j+1} (drawn once, kept until advance()).
  [[nodiscard]] double next_value() const { return next_; }
  //! Grid spacing dt [s].
  [[nodiscard]] double step_s() const { return step_s_; }
  //! Moves to node j + 1.
  void advance();

 private:
  double draw();

  RandomEngine engine_;
  boost::random::normal_distribution<double> normal_;
  double rms_;
  double rho_;
  double innovation_;
  double step_s_;
  std::uint64_t index_ = 0;
  double value_ = 0.0;
  double next_ = 0.0;
};

}  // namespace stengmc
