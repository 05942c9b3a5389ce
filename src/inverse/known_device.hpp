#pragma once
//! The known device of an inversion: everything about the sensor but the number of sliding
//! asperities and their stiffnesses (docs/inverse.md). Every asperity shares the
//! device's mass, load and S-TENG element; the record starts with every asperity at rest
//! (x = x' = 0) at t = 0, as the forward model does.
#include <string>
#include <vector>

#include "circuit/circuit_solver.hpp"
#include "pipeline/study.hpp"
#include "model/asperity.hpp"
#include "tribology/model2.hpp"

namespace stengmc {

struct KnownDevice {
  Model2Params model;      //!< friction, belt velocity, damping (Model 2 only)
  Asperity asperity;       //!< m, N and the S-TENG element every asperity shares (its k is unused)
  CircuitParams circuit;   //!< R, C_L, solver substeps
  double duration_s = 0.0;       //!< record length the device study describes [s]
  double sample_rate_hz = 0.0;   //!< its sample rate [Hz]
  std::string study_file;  //!< where it was read from (messages)

  //! Damping rate d = c / 2m of every asperity's free oscillation [1/s].
  [[nodiscard]] double damping_rate_per_s() const { return model.damping_n_s_per_m / (2.0 * asperity.mass_kg); }
  //! Damped angular frequency sqrt(k/m - d^2) of stiffness k [rad/s] (0 when over-damped).
  [[nodiscard]] double angular_frequency(double stiffness_n_per_m) const;
  //! Stiffness whose damped angular frequency is omega [N/m] (inverse of angular_frequency).
  [[nodiscard]] double stiffness_for(double angular_frequency_rad_per_s) const;
  //! Voltage scale R sigma w v_b of one asperity moving with the belt [V].
  [[nodiscard]] double voltage_scale_v() const;
  //! Element capacitance eps0 w (l - x) / d0 at displacement x [F].
  [[nodiscard]] double element_capacitance_f(double displacement_m) const;
  //! Friction force while sliding fast, N (mu_k + (mu_s - mu_k) exp(-c_s v_b)) ~ mu_s N [N]:
  //! the force the oscillation is centred on.
  [[nodiscard]] double sliding_friction_n() const;
  //! The known parameters as "name = value" lines (provenance, bank identity).
  [[nodiscard]] std::string describe() const;
};

//! The known device of a study (the `--known` study of `stengmc invert`). The study must be
//! a Model 2 study whose asperities share every parameter but the stiffness, start at rest,
//! and state every known parameter explicitly (MODEL.md's defaults are not assumed: a
//! device parameter left out by mistake would silently bias every estimate).
//! @throws InputError naming the file and each missing or inconsistent key.
KnownDevice known_device_from_study(const Study& study);

//! The study keys that must be written out, as "table.key" (for messages and tests).
const std::vector<std::string>& required_device_keys();

}  // namespace stengmc
