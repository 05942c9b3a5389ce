#pragma once
//! The S-TENG element formulas hold for x < l only (MODEL.md §2, validity).
#include <optional>
#include <span>

#include "model/motion.hpp"

namespace stengmc {

//! First time [s] at which the dense output x(t) of `motion` reaches `length_m` [m] on
//! [times_s.front(), times_s.back()], or nothing; located to adjacent doubles.
//!
//! Each sample interval [t_j, t_j+1] is examined in turn:
//! - x_j+1 >= l (the sample itself): x − l is bisected on the interval;
//! - otherwise an interior maximum is detected from the one-sided velocities,
//!   x'(t_j, right) >= 0 >= x'(t_j+1, left), not both zero; the sign change of x' is
//!   bisected, and as soon as x >= l at an evaluated point, x − l is bisected between
//!   t_j and that point. A peak between samples (a spline overshooting l between samples
//!   that are all < l, a Model 2 oscillation sampled near its Nyquist rate) is found.
//!   Stick phases (x' exactly 0 over a stretch) at either end are walked through.
//!
//! A motion whose displacement_bound() is below l has nothing to find (after the samples'
//! NaN check). Otherwise the cost is two motion evaluations per sample interval, plus a
//! short bisection at each interior maximum. The peak bisection stops early once the bracket is <= 1/64 of the
//! interval, x' is nonzero at both its ends and max(x) + width · max|x'| at its ends is
//! below l, i.e. it assumes |x'| does not grow towards the peak on at least one side
//! within such a bracket (true near any maximum the sampling resolves). Otherwise the
//! bisection runs to adjacent doubles (~50 evaluations).
//!
//! Blind spots, inherent in looking at x' only at the samples (all need motion content
//! above half the sample rate, where the sampling does not resolve the motion anyway):
//! - two interior extrema with x' of the same sign at both ends (up over l, down, up
//!   again; or a max and a min), so no sign change is seen;
//! - x' exactly 0 at both ends with an interior maximum that is not a stick plateau.
//!   (A Model 1 slip between two sticks inside one interval is monotone: its maximum
//!   is the end sample, which is checked.)
//!
//! @param times_s strictly increasing sample times [s]
//! @param x_m     x at those times [m], the values `motion` passes through
//! @throws ModelError when a displacement (a sample, or the dense output at a point
//!         evaluated) or a velocity evaluated is NaN or Inf; the message gives the time.
//!         All samples are checked, also those after an exit.
std::optional<double> first_domain_exit(const Motion& motion, std::span<const double> times_s,
                                        std::span<const double> x_m, double length_m);

//! The same with the motion's samples at `times_s` (Motion::sample): the velocities at
//! the samples are read from them instead of evaluated, so only the bisections evaluate
//! the motion. Identical results when the samples are the motion's own.
std::optional<double> first_domain_exit(const Motion& motion, std::span<const double> times_s,
                                        const MotionSamples& samples, double length_m);

}  // namespace stengmc
