#pragma once
//! Physical constants, each with its unit and source.

namespace stengmc {

//! Vacuum permittivity [F/m], CODATA 2018 (the paper prints 8.8541878e-12).
inline constexpr double EPSILON_0 = 8.8541878128e-12;

//! pi, to double precision.
inline constexpr double PI = 3.14159265358979323846;

}  // namespace stengmc
