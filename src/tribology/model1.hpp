#pragma once
//! Model 1: Coulomb stick-slip under an imposed sinusoid x0(t) = A sin(omega t + phi)
//! (MODEL.md §1; paper Eq. 1 with its sign typo corrected).
#include <cstddef>

#include "core/name_table.hpp"
#include "model/asperity.hpp"
#include "tribology/friction.hpp"
#include "tribology/time_grid.hpp"
#include "tribology/trajectory.hpp"

namespace stengmc {

//! How Model 1 is integrated.
enum class Model1Solver {
  exact,         //!< closed-form slip phases, transitions located to machine precision (default)
  euler_cromer,  //!< the paper's fixed-step scheme, velocity forced to zero at a sign change
};
//! `solver` in study and run files.
inline constexpr NameTable MODEL1_SOLVER_NAMES{std::array{NamedValue<Model1Solver>{Model1Solver::exact, "exact"},
                                                          NamedValue<Model1Solver>{Model1Solver::euler_cromer, "euler_cromer"}}};

//! Parameters of Model 1 shared by all asperities.
struct Model1Params {
  FrictionCoefficients friction;
  double drive_amplitude_m = 9e-6;                              //!< A [m]
  double drive_angular_frequency_rad_per_s = 2.0 * 3.14159265358979323846 * 1e4;  //!< omega [rad/s]
  Model1Solver solver = Model1Solver::exact;
  std::size_t euler_cromer_substeps = 1;  //!< euler_cromer steps per output step
};

//! Imposed displacement x0(t) = A sin(omega t + phi) [m].
double imposed_displacement(const Model1Params& params, const Asperity& asperity, double t_s);

//! True when the drive can ever break static friction: A > mu_s N / k (paper Eq. 1).
bool model1_can_slip(const Model1Params& params, const Asperity& asperity);

//! Throws InputError unless m, k > 0, N >= 0, mu_s >= mu_k >= 0, A >= 0, omega > 0, the grid
//! step > 0 and (for euler_cromer) substeps >= 1; both solvers call it first.
void validate_model1(const Asperity& asperity, const Model1Params& params, const TimeGrid& grid);

//! Solves one asperity with the configured solver.
Trajectory solve_model1(const Asperity& asperity, const Model1Params& params, const TimeGrid& grid);

//! Closed-form solver: slip phases are forced linear oscillators with constant friction.
Trajectory solve_model1_exact(const Asperity& asperity, const Model1Params& params, const TimeGrid& grid);

//! The paper's Euler-Cromer scheme with `params.euler_cromer_substeps` steps per output step.
Trajectory solve_model1_euler_cromer(const Asperity& asperity, const Model1Params& params,
                                     const TimeGrid& grid);

}  // namespace stengmc
