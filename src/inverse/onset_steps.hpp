#pragma once
//! Contact onsets read off a record as the steps they make (docs/inverse.md, "onset steps").
//!
//! An asperity that comes into contact at t_on is picked up by the belt's friction F within
//! the ramp m v_b / F (36 ns with the shipped devices at 10 m/s, 3.6 ns at 1 m/s) and stays
//! stuck, x' = v_b, until its spring holds F; so U = R sigma w v_b sum u_i steps up by exactly
//! one unit R sigma w v_b at every onset, whatever the asperity's stiffness or load. The other
//! asperities move smoothly over a few samples (a breakaway is a kink, an oscillation a slope of
//! at most omega A). So after the shared load's nonlinearity V = U / (1 - gamma U) is undone
//! (MODEL.md §2, inverse/record_model.hpp), the least-squares height h of one onset's ramp
//! beside a cubic over +-W samples, a linear filter of the record, peaks at each onset at one
//! unit per asperity; a step is a local maximum of h of at least STEP_MIN_UNITS and
//! STEP_MIN_SIGMAS of its error from white noise. Onsets in the record's first 2W samples (t = 0
//! above all, where every asperity then in contact ramps up at once) are not read: the start
//! plateau counts those (inverse/start_plateau.hpp).
#include <cstddef>
#include <span>
#include <vector>

#include "inverse/known_device.hpp"
#include "inverse/record_grid.hpp"

namespace stengmc {

//! One onset step.
struct OnsetStep {
  double onset_s = 0.0;  //!< where the ramp starts [s]
  double units = 0.0;    //!< its height over R sigma w v_b (1 per asperity; two at once ~2) [-]
};

//! The smallest height read as a step [units of R sigma w v_b]: above it a unit step, below it
//! what the cubic leaves of the others' motion (0.5-0.6 on records without onsets).
inline constexpr double STEP_MIN_UNITS = 0.7;
//! A step's height in standard errors of h from the white noise, at least.
inline constexpr double STEP_MIN_SIGMAS = 5.0;
//! The filter's half window at most [samples]; shorter where the stiffest line would turn by
//! more than 0.6 of a period across the window.
inline constexpr std::size_t STEP_MAX_HALF_WINDOW = 8;

//! The onset steps of `voltage_v` (the record on `grid`) for the known device, white noise of
//! sd `noise_sigma_v`, and the stiffest line the record is likely to hold `stiffest_n_per_m`
//! (the prior's 0.99 quantile), in time order. Empty where the record cannot show them: a ramp
//! longer than the window's half less two samples,
//! a load whose low pass (R C_L) is slower than the ramp, or a window too short to hold a
//! ramp beside the cubic.
std::vector<OnsetStep> onset_steps(const KnownDevice& device, double stiffest_n_per_m, double noise_sigma_v,
                                   const RecordGrid& grid, std::span<const double> voltage_v);

}  // namespace stengmc
