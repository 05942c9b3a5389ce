#pragma once
//! An independent solution of the whole chain for the tests: the coupled system of
//! MODEL.md §1 (Model 2, consistent friction) and §2 (parallel elements on R || C_L) for n
//! asperities, 2n + 2 equations in (x_i, x_i', V, Q), integrated at once by Boost.Odeint's
//! rosenbrock4 with its dense output. Everything is written out again from MODEL.md; no
//! stengmc code is used. Plain C++17 in its interface: its source is compiled as C++17,
//! because Boost 1.74's uBLAS (which rosenbrock4 needs) does not build as C++20.
#include <vector>

namespace stengmc::test {

struct ChainAsperity {
  double stiffness_n_per_m = 0.0;
  double mass_kg = 0.0;
  double normal_load_n = 0.0;
  double initial_displacement_m = 0.0;
  double initial_velocity_m_per_s = 0.0;
  double charge_density_c_per_m2 = 0.0;
  double effective_thickness_m = 0.0;
  double width_m = 0.0;
  double length_m = 0.0;
};

struct ChainParameters {
  double static_friction = 0.28;
  double kinetic_friction = 0.22;
  double belt_velocity_m_per_s = 1.0;
  double damping_n_s_per_m = 1e-7;
  double stribeck_decay_s_per_m = 1e-7;
  double atan_sharpness_s_per_m = 1e3;
  double load_resistance_ohm = 1e6;
  double load_capacitance_f = 0.0;
};

struct ChainSolution {
  std::vector<double> voltage_v;  //!< V at the requested times [V]
  std::vector<double> charge_c;   //!< Q = integral of V/R dt [C]
};

//! V and Q at `times_s` (increasing, times_s[0] = 0 where x_i, x_i' take their initial
//! values and V = Q = 0), rosenbrock4 at relative and absolute tolerance `tolerance` in
//! units us, um, m/s, mV, fC.
ChainSolution coupled_chain_reference(const std::vector<ChainAsperity>& asperities, const ChainParameters& params,
                                      const std::vector<double>& times_s, double tolerance);

}  // namespace stengmc::test
