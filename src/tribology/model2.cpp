#include "tribology/model2.hpp"

#include <array>
#include <cmath>
#include <memory>
#include <sstream>

#include "core/constants.hpp"
#include "core/error.hpp"
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

Trajectory solve_model2(const Asperity& asperity, const Model2Params& params, const TimeGrid& grid) {
  if (grid.count > 0 && !(grid.step_s > 0.0)) {
    std::ostringstream msg;
    msg << "Model 2 output grid step " << grid.step_s << " s must be positive";
    throw InputError(msg.str());
  }
  const double t_end = grid.count > 0 ? grid.at(grid.count - 1) : 0.0;
  Model2Integration integration = integrate_model2(asperity, params, t_end);

  Trajectory out;
  out.solver_steps = integration.accepted_steps;
  out.rejected_steps = integration.rejected_steps;
  auto motion = std::make_unique<Model2Motion>(std::move(integration));

  // Samples come from the dense output rather than from steps forced onto the grid: the
  // steps are typically longer than the 10 ns output step, and forcing them down would
  // multiply the step count with no gain (the dense output is as accurate as the steps).
  MotionSamples samples;
  motion->sample(grid.times(), false, samples);
  out.x_m = std::move(samples.x_m);
  out.v_m_per_s = std::move(samples.v_m_per_s);
  const StribeckFriction friction(params, asperity.normal_load_n);
  out.friction_n.resize(grid.count);
  // v_r first, then F in place, in one batch (the law's formula inlined in its loop).
  for (std::size_t j = 0; j < grid.count; ++j) out.friction_n[j] = params.belt_velocity_m_per_s - out.v_m_per_s[j];
  friction.forces(out.friction_n.data(), out.friction_n.data(), grid.count);

  out.events = motion->relative_velocity_events(params.belt_velocity_m_per_s);
  out.motion = std::move(motion);
  return out;
}

}  // namespace stengmc
