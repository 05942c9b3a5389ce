// Model 1 pieces shared by both solvers: the drive, the paper's slip condition, input checks
// and the solver dispatch (MODEL.md §1).
#include <cmath>
#include <sstream>
#include <string>

#include "core/error.hpp"
#include "tribology/model1.hpp"

namespace stengmc {

namespace {

// Formats "name = value must be <what>" so that a rejected parameter names itself.
[[noreturn]] void reject(const char* name, double value, const char* expected) {
  std::ostringstream message;
  message.precision(17);
  message << "Model 1: " << name << " = " << value << " must be " << expected;
  throw InputError(message.str());
}

}  // namespace

double imposed_displacement(const Model1Params& params, const Asperity& asperity, double t_s) {
  return params.drive_amplitude_m *
         std::sin(params.drive_angular_frequency_rad_per_s * t_s + asperity.drive_phase_rad);
}

bool model1_can_slip(const Model1Params& params, const Asperity& asperity) {
  // The spring force k (x0 - x) of an asperity stuck at x = 0 peaks at k A; static friction
  // holds it while that stays <= mu_s N (paper, discussion of Eq. 1).
  return params.drive_amplitude_m >
         params.friction.static_coefficient * asperity.normal_load_n / asperity.stiffness_n_per_m;
}

void validate_model1(const Asperity& asperity, const Model1Params& params, const TimeGrid& grid) {
  // Written as !(x > 0) so that NaN is rejected too.
  if (!(asperity.mass_kg > 0.0) || !std::isfinite(asperity.mass_kg))
    reject("mass_kg", asperity.mass_kg, "finite and > 0");
  if (!(asperity.stiffness_n_per_m > 0.0) || !std::isfinite(asperity.stiffness_n_per_m))
    reject("stiffness_n_per_m", asperity.stiffness_n_per_m, "finite and > 0");
  if (!(asperity.normal_load_n >= 0.0) || !std::isfinite(asperity.normal_load_n))
    reject("normal_load_n", asperity.normal_load_n, "finite and >= 0");
  const double mu_k = params.friction.kinetic_coefficient;
  const double mu_s = params.friction.static_coefficient;
  if (!(mu_k >= 0.0) || !std::isfinite(mu_k)) reject("mu_k", mu_k, "finite and >= 0");
  if (!(mu_s >= mu_k) || !std::isfinite(mu_s)) reject("mu_s", mu_s, "finite and >= mu_k");
  if (!(params.drive_amplitude_m >= 0.0) || !std::isfinite(params.drive_amplitude_m))
    reject("drive_amplitude_m", params.drive_amplitude_m, "finite and >= 0");
  if (!(params.drive_angular_frequency_rad_per_s > 0.0) ||
      !std::isfinite(params.drive_angular_frequency_rad_per_s))
    reject("drive_angular_frequency_rad_per_s", params.drive_angular_frequency_rad_per_s,
           "finite and > 0");
  if (!(std::abs(asperity.drive_phase_rad) <= MAX_DRIVE_PHASE_RAD))
    reject("drive_phase_rad", asperity.drive_phase_rad, "within +-1e6 rad");
  if (!std::isfinite(asperity.initial_displacement_m))
    reject("initial_displacement_m", asperity.initial_displacement_m, "finite");
  if (!std::isfinite(asperity.initial_velocity_m_per_s))
    reject("initial_velocity_m_per_s", asperity.initial_velocity_m_per_s, "finite");
  if (asperity.onset_s != 0.0) reject("onset_s", asperity.onset_s, "0 (a contact onset is a Model 2 key)");
  if (!(grid.step_s > 0.0) || !std::isfinite(grid.step_s))
    reject("output time step [s]", grid.step_s, "finite and > 0");
  if (params.solver == Model1Solver::euler_cromer && params.euler_cromer_substeps < 1)
    reject("euler_cromer_substeps", static_cast<double>(params.euler_cromer_substeps), ">= 1");
}

Trajectory solve_model1(const Asperity& asperity, const Model1Params& params, const TimeGrid& grid) {
  switch (params.solver) {
    case Model1Solver::exact: return solve_model1_exact(asperity, params, grid);
    case Model1Solver::euler_cromer: return solve_model1_euler_cromer(asperity, params, grid);
  }
  throw InputError("Model 1: unknown solver");
}

}  // namespace stengmc
