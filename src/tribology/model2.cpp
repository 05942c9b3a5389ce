#include "tribology/model2.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <sstream>

#include "core/constants.hpp"
#include "core/error.hpp"
#include "model/delayed_motion.hpp"
#include "tribology/evolving_contact.hpp"
#include "tribology/model2_motion.hpp"
#include "tribology/model2_integrator.hpp"

namespace stengmc {

double model2_friction(const Model2Params& params, double normal_load_n, double relative_velocity_m_per_s) {
  return StribeckFriction(params, normal_load_n).force(relative_velocity_m_per_s);
}

double damped_natural_frequency_hz(double stiffness_n_per_m, double mass_kg, double damping_n_s_per_m) {
  const double zeta = damping_n_s_per_m / (2.0 * std::sqrt(stiffness_n_per_m * mass_kg));
  // Critically or over-damped: no oscillation, hence no spectral line.
  if (!(zeta < 1.0)) return 0.0;
  return std::sqrt(stiffness_n_per_m / mass_kg) * std::sqrt(1.0 - zeta * zeta) / (2.0 * PI);
}

Model2Solution solve_model2_motion(const Asperity& asperity, const Model2Params& params, double t_end_s,
                                   const CounterfaceStream& stream) {
  const double onset = std::clamp(asperity.onset_s, 0.0, std::max(t_end_s, 0.0));
  const bool evolves = contact_evolves(asperity, params);
  Model2Integration integration;
  if (evolves) {
    integrate_evolving_contact(asperity, params, t_end_s - onset, stream, integration);
  } else {
    integrate_model2(asperity, params, t_end_s - onset, integration);
  }
  Model2Solution out;
  out.accepted_steps = integration.accepted_steps;
  out.rejected_steps = integration.rejected_steps;
  auto motion = std::make_unique<Model2Motion>(std::move(integration));
  out.events = motion->relative_velocity_events(params.belt_velocity_m_per_s);
  if (evolves && std::isfinite(asperity.release_s))
    std::erase_if(out.events, [&](const Event& e) { return e.time_s >= asperity.release_s - onset; });
  if (onset > 0.0) {
    for (Event& e : out.events) e.time_s += onset;
    out.motion = std::make_unique<DelayedMotion>(std::move(motion), onset, asperity.initial_displacement_m);
  } else {
    out.motion = std::move(motion);
  }
  return out;
}

void model2_friction_trace(const Asperity& asperity, const Model2Params& params, std::span<const double> times_s,
                           std::span<const double> velocities_m_per_s, std::vector<double>& friction_n,
                           const CounterfaceStream& stream) {
  const StribeckFriction friction(params, asperity.normal_load_n);
  friction_n.resize(velocities_m_per_s.size());
  // v_r first, then F in place, in one batch (the law's formula inlined in its loop).
  for (std::size_t j = 0; j < friction_n.size(); ++j) friction_n[j] = params.belt_velocity_m_per_s - velocities_m_per_s[j];
  friction.forces(friction_n.data(), friction_n.data(), friction_n.size());
  if (asperity.onset_s > 0.0)
    for (std::size_t j = 0; j < friction_n.size() && times_s[j] < asperity.onset_s; ++j) friction_n[j] = 0.0;
  if (params.counterface.active()) {
    std::vector<double> factor;
    modulation_factors(asperity, params, stream, times_s.first(friction_n.size()), factor);
    for (std::size_t j = 0; j < friction_n.size(); ++j) friction_n[j] *= factor[j];
  }
  if (std::isfinite(asperity.release_s))
    for (std::size_t j = 0; j < friction_n.size(); ++j)
      if (times_s[j] > asperity.release_s) friction_n[j] = 0.0;
}

Trajectory solve_model2(const Asperity& asperity, const Model2Params& params, const TimeGrid& grid) {
  if (grid.count > 0 && !(grid.step_s > 0.0)) {
    std::ostringstream msg;
    msg << "Model 2 output grid step " << grid.step_s << " s must be positive";
    throw InputError(msg.str());
  }
  const double t_end = grid.count > 0 ? grid.at(grid.count - 1) : 0.0;
  Model2Solution solution = solve_model2_motion(asperity, params, t_end);

  Trajectory out;
  out.solver_steps = solution.accepted_steps;
  out.rejected_steps = solution.rejected_steps;
  // Samples come from the dense output rather than from steps forced onto the grid: the
  // steps are typically longer than the 10 ns output step, and forcing them down would
  // multiply the step count with no gain (the dense output is as accurate as the steps).
  MotionSamples samples;
  const std::vector<double> times = grid.times();
  solution.motion->sample(times, false, samples);
  out.x_m = std::move(samples.x_m);
  out.v_m_per_s = std::move(samples.v_m_per_s);
  model2_friction_trace(asperity, params, times, out.v_m_per_s, out.friction_n);
  out.events = std::move(solution.events);
  out.motion = std::move(solution.motion);
  return out;
}

}  // namespace stengmc
