#pragma once
//! The one place the inversion calls the forward model: the voltage a single asperity of the
//! known device produces on its own (docs/inverse.md, "atoms"). Everything the
//! estimator knows about the physics comes through here, so a faster forward path (issue 12)
//! replaces this one function.
#include <span>
#include <vector>

#include "inverse/known_device.hpp"
#include "tribology/time_grid.hpp"

namespace stengmc {

//! One asperity's motion and voltage on given times.
struct ForwardAtom {
  std::vector<double> voltage_v;        //!< V(t) of the device with this asperity alone [V]
  std::vector<double> slope_v_per_s;    //!< dV/dt from the circuit equation at each sample [V/s]
  std::vector<double> displacement_m;   //!< x(t) [m]
};

//! Runs one asperity of stiffness k through the tribology (Model 2, RODAS4) and the circuit
//! (Radau IIA, one element on R || C_L), from rest at t = 0, sampled at `times_s`
//! (increasing, times_s[0] >= 0; the circuit starts at t = 0 whatever the first time).
//! @throws ModelError when the asperity reaches its element's length l (the element
//!         formulas diverge there) or the solvers fail.
ForwardAtom simulate_forward_atom(const KnownDevice& device, double stiffness_n_per_m, std::span<const double> times_s);

}  // namespace stengmc

namespace stengmc {

//! True when an asperity of stiffness k stays below its element's length l on `grid` (the
//! tribology alone; the solvers' own failures throw ModelError).
bool stays_below_length(const KnownDevice& device, double stiffness_n_per_m, const TimeGrid& grid);

//! The smallest stiffness whose asperity stays below its element's length l for `duration_s`
//! (softer ones are dragged further before breakaway, x_b ~ mu_s N / k): bisection in ln k on
//! the tribology to 0.1 %, returned 2 % above the boundary [N/m]. 0 when even
//! `lowest_n_per_m` stays valid; infinity when even `highest_n_per_m` does not.
double smallest_valid_stiffness(const KnownDevice& device, double duration_s, double step_s, double lowest_n_per_m,
                                double highest_n_per_m);

}  // namespace stengmc
