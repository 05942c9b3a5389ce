#pragma once
//! Model 2: mass on a moving belt with Stribeck friction (MODEL.md §1; paper Eq. 2).
#include <memory>
#include <span>
#include <vector>

#include "model/asperity.hpp"
#include "tribology/counterface.hpp"
#include "tribology/friction.hpp"
#include "tribology/friction_law.hpp"
#include "tribology/time_grid.hpp"
#include "tribology/trajectory.hpp"

namespace stengmc {

//! Parameters of Model 2 shared by all asperities.
struct Model2Params {
  FrictionCoefficients friction;
  double belt_velocity_m_per_s = 1.0;        //!< v_b [m/s]
  double damping_n_s_per_m = 1e-7;           //!< c, viscous damping [N s/m]
  double stribeck_decay_s_per_m = 1e-7;      //!< c_s, Stribeck decay constant [s/m]
  double atan_sharpness_s_per_m = 1e3;       //!< s, sharpness of the atan regularisation [s/m]
  //! F(v_r), by `friction_form` (friction_law.hpp; consistent unless the study says otherwise).
  const FrictionLaw* friction_law = &default_friction_law();
  //! Local error tolerance of the integrator (RODAS4 steps and sliding-propagator steps,
  //! model2_integrator.hpp), relative and (in units of the length scale
  //! max(mu N / k, |x0|, |x0'| / w0, v_b / w0)) absolute [-].
  //! The default 1e-8 guarantees, for the 8 Table-1 cases (k = 25..155 N/m, v_b = 1, 10 m/s,
  //! 50 us, both friction forms), a displacement on the output grid and on the dense output
  //! within 1e-6 of max|x| of a 100x tighter solution (measured worst case 4.3e-8, k = 155,
  //! v_b = 1, literal form; 3.1e-7 with RODAS4 alone). The global error scales ~linearly with it.
  double relative_tolerance = 1e-8;
  //! Take exact steps of the linearised motion where friction is nearly linear (sliding);
  //! false: RODAS4 alone, the method before issue 12. Not a study key: benchmarks and
  //! tests compare the two.
  bool sliding_propagator = true;
  //! The counterface's friction modulation (`[counterface]`, docs/model.md §1.4); none by default.
  CounterfaceParams counterface;
};

//! Friction force F(v_r) on the asperity [N] for relative velocity v_r = v_b - x' [m/s].
double model2_friction(const Model2Params& params, double normal_load_n, double relative_velocity_m_per_s);

//! Solves m x'' + c x' + k x = F(v_b - x') for one asperity with an error-controlled,
//! L-stable integrator; dense output between steps for the circuit.
//! Method: RODAS4 (Hairer & Wanner) on the nondimensional system, and where friction is
//! nearly linear exact steps of the linearised oscillator with a polynomial correction
//! (sliding_propagator.hpp), see model2_integrator.hpp. The samples and the
//! overtake/regrip events are taken from the dense output (tribology/model2_motion.hpp);
//! Event::asperity is left 0 for the caller to set.
//! @throws ModelError if the integrator fails (step size underflow, non-finite state); the
//!         message names k, v_b and the time. @throws InputError for k <= 0 or m <= 0.
Trajectory solve_model2(const Asperity& asperity, const Model2Params& params, const TimeGrid& grid);

//! One asperity's Model 2 motion over [0, t_end_s] before it is sampled.
struct Model2Solution {
  std::unique_ptr<Motion> motion;  //!< dense output (a DelayedMotion when the onset is > 0)
  std::vector<Event> events;       //!< overtakes and regrips, in time (Event::asperity 0)
  std::size_t accepted_steps = 0;
  std::size_t rejected_steps = 0;
};

//! Integrates from the asperity's contact onset (`onset_s`, clamped to t_end_s), at rest at
//! its initial displacement before it: the motion from the onset is the one from t = 0
//! shifted (the equation holds t only through the evolving contact below).
//! A contact that evolves (contact_evolves: counterface modulation, release, wear,
//! stiffness steps; docs/model.md §1.4) is integrated by integrate_evolving_contact, its
//! modulation drawn from `stream`; any other by integrate_model2, as before. Overtakes and
//! regrips after the release (no contact) are not events.
Model2Solution solve_model2_motion(const Asperity& asperity, const Model2Params& params, double t_end_s,
                                   const CounterfaceStream& stream = {});

//! Friction on the grid from the sampled velocities: F(v_b - x') (1 + eps(t)), 0 before the
//! onset and after the release (carried by nothing), into `friction_n` (resized).
void model2_friction_trace(const Asperity& asperity, const Model2Params& params, std::span<const double> times_s,
                           std::span<const double> velocities_m_per_s, std::vector<double>& friction_n,
                           const CounterfaceStream& stream = {});

//! Damped natural frequency f = sqrt(k/m) sqrt(1 - zeta^2) / 2 pi, zeta = c / (2 sqrt(k m)) [Hz].
double damped_natural_frequency_hz(double stiffness_n_per_m, double mass_kg, double damping_n_s_per_m);

}  // namespace stengmc
