#pragma once
//! Which parameters a fit of a record adjusts, within which bounds, and what the prior says
//! of each (docs/inverse.md, "the record model"): the prior decides. Each atom always has its
//! stiffness; its load when the prior spreads loads (load_cv), or one load factor shared by
//! every atom when only a tolerance makes the device's load uncertain; its onset when the
//! prior staggers them (onset_s). The device's damping c is fitted within the tolerance, the
//! record's amplitude (sigma and R) too, and its offset when the prior allows one: those two
//! enter the model linearly and are solved for at every step (variable projection, Golub &
//! Pereyra 1973; Kaufman 1975).
#include <cstddef>

#include "inverse/inverse_prior.hpp"
#include "inverse/known_device.hpp"
#include "inverse/load_prior.hpp"

namespace stengmc {

struct FitLayout {
  bool load_per_atom = false;  //!< each atom its own load
  bool load_shared = false;    //!< one load factor for every atom
  bool onset_free = false;     //!< each atom its own onset
  bool damping_free = false;   //!< the device's damping
  bool amplitude_free = false; //!< the record's voltage scale (linear)
  bool offset_free = false;    //!< the record's offset (linear)
  bool coloured_noise = false; //!< the noise spectrum is estimated (whitening)

  double nominal_load_n = 0.0;                    //!< the device's N [N]
  double min_log_load = 0.0, max_log_load = 0.0;  //!< bounds of ln(N_i / N) (or of the shared factor's log)
  double onset_min_s = 0.0, onset_max_s = 0.0;    //!< onset bounds [s]
  double nominal_damping_rate = 0.0;              //!< d = c / 2m of the device [1/s]
  double min_damping_rate = 0.0, max_damping_rate = 0.0;  //!< its bounds [1/s]
  double min_amplitude = 1.0, max_amplitude = 1.0;        //!< the voltage scale's bounds [-]

  //! Nonlinear parameters per atom: ln k, then ln N and t_on when free.
  [[nodiscard]] std::size_t per_atom() const { return 1 + (load_per_atom ? 1 : 0) + (onset_free ? 1 : 0); }
  //! Nonlinear parameters shared by every atom: the damping's log, the shared load factor's log.
  [[nodiscard]] std::size_t shared() const { return (damping_free ? 1 : 0) + (load_shared ? 1 : 0); }
};

//! The layout the prior asks for, on `device`. A tolerance tau allows the damping within
//! (1 +- tau) and the amplitude within (1 +- tau) (sigma; R is written out), the shared load
//! within the product of the mean load's and mu_s's (1 +- tau).
FitLayout fit_layout(const InversePrior& prior, const KnownDevice& device, const LoadPrior& loads);

}  // namespace stengmc
