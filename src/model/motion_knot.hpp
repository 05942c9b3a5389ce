#pragma once
//! A point of a motion with its first two derivatives: an integrator's step end, and what
//! Hermite interpolation (hermite.hpp) joins.

namespace stengmc {

//! One accepted integrator step end: the data a quintic Hermite interpolant needs.
struct MotionKnot {
  double t_s = 0.0;                //!< time [s]
  double x_m = 0.0;                //!< displacement [m]
  double v_m_per_s = 0.0;          //!< velocity [m/s]
  double a_m_per_s2 = 0.0;         //!< acceleration from the ODE at (x, v) [m/s^2]
};

}  // namespace stengmc
