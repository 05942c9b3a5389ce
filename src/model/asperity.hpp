#pragma once
//! One asperity in contact: its mechanics and its S-TENG element (MODEL.md §1, §2).
#include <limits>
#include <vector>

namespace stengmc {

//! The sliding-TENG element an asperity carries (paper Eqs. 3-5, Table 2).
struct StengElement {
  double charge_density_c_per_m2 = 80e-6;  //!< sigma, tribo-charge surface density [C/m^2]
  double effective_thickness_m = 50e-6;    //!< d0 = d1/eps_r1 + d2/eps_r2 [m]
  double width_m = 10e-6;                  //!< w, dielectric width [m]
  double length_m = 10e-6;                 //!< l, dielectric length; the element needs x < l [m]
};

//! A step change of an asperity's stiffness (docs/model.md §1.4): from `time_s` on, k is
//! multiplied by `factor`.
struct StiffnessStep {
  double time_s = 0.0;   //!< when [s]
  double factor = 1.0;   //!< k after / k before [-], > 0
};

//! Mechanical parameters of one asperity and its element (paper Tables 1, 2).
struct Asperity {
  double stiffness_n_per_m = 75.0;           //!< k, shear stiffness [N/m]
  double mass_kg = 1e-12;                    //!< m [kg]
  double normal_load_n = 1e-3;               //!< N, normal load carried [N]
  double height_m = 110e-6;                  //!< h, asperity height = dielectric thickness d1 [m]
  double drive_phase_rad = 0.0;              //!< phi, Model 1 drive phase [rad]
  double initial_displacement_m = 0.0;       //!< x(0) [m]
  double initial_velocity_m_per_s = 0.0;     //!< x'(0) [m/s]
  //! Model 2: when it comes into contact [s]; before, at rest at x(0) and carried by nothing
  //! (its element stays in the circuit).
  double onset_s = 0.0;
  //! Model 2: when it leaves contact [s] (> onset_s): no load, no friction after it, it rings
  //! freely towards rest (its element stays in the circuit); infinity: never.
  double release_s = std::numeric_limits<double>::infinity();
  //! Model 2: w, wear of the stiffness per millisecond in contact [1/ms]:
  //! k(t) = k0 (1 - w (t - onset) / 1 ms) until the release, frozen after it.
  double wear_rate_per_ms = 0.0;
  //! Model 2: step changes of k, in time (docs/model.md §1.4); none by default.
  std::vector<StiffnessStep> stiffness_steps;
  StengElement element;                      //!< its S-TENG element
};

//! Largest |drive phase| [rad]: omega t + phi is a double, and a phase of 1e15 rad keeps no
//! digits of omega t (the fuzz tests found the exact solver looping on one).
inline constexpr double MAX_DRIVE_PHASE_RAD = 1e6;

}  // namespace stengmc
