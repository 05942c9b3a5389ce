#pragma once
//! Hermite interpolation through the ends of a step (knots): what Model 2's dense output
//! is made of between RODAS4 step ends, and how the streamed circuit reads a motion it
//! recorded densely.
#include <array>

#include "model/motion.hpp"
#include "model/motion_knot.hpp"

namespace stengmc {

//! The quintic Hermite of (x, x', x'') at knots a and b, at t [s] (extrapolates outside).
PhasePoint quintic_hermite(const MotionKnot& a, const MotionKnot& b, double t_s);

//! The cubic Hermite of (x, x') at knots a and b, at t [s] (extrapolates outside).
PhasePoint cubic_hermite(const MotionKnot& a, const MotionKnot& b, double t_s);

//! Its velocity as a polynomial in s = (t - t_a) / (t_b - t_a), as below (degree 2).
std::array<double, 5> cubic_hermite_velocity(const MotionKnot& a, const MotionKnot& b);

//! Its velocity as a quartic in s = (t - t_a) / (t_b - t_a): x'(s) = sum_n c[n] s^n [m/s].
std::array<double, 5> quintic_hermite_velocity(const MotionKnot& a, const MotionKnot& b);

}  // namespace stengmc
