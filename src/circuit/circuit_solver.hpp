#pragma once
//! The S-TENG elements in parallel on a load R (|| C_L), MODEL.md §2.
#include <cstddef>
#include <span>
#include <vector>

#include "model/asperity.hpp"
#include "model/motion.hpp"

namespace stengmc {

class Progress;

//! The load the elements feed, and how finely the solver steps.
struct CircuitParams {
  double load_resistance_ohm = 1e6;  //!< R [Ohm] (paper: 1 MOhm)
  double load_capacitance_f = 0.0;   //!< C_L in parallel with R [F]; 0 for none
  std::size_t substeps = 4;          //!< Radau IIA steps per output interval (and per breakpoint piece)
};

//! The circuit's response on the output times.
struct CircuitResult {
  std::vector<double> voltage_v;  //!< V, terminal voltage across the load [V]
  std::vector<double> charge_c;   //!< Q = integral of V/R dt, charge delivered to R [C]
  std::vector<std::vector<double>> current_a;  //!< i_i = dQ_i/dt per element, [element][sample] [A]
  //! integral of i_i dt from the first time, [element][sample] [C]; Q_i(t) - Q_i(t0) with
  //! Q_i = sigma_i w_i x_i - C_i V, and sum_i = Q + C_L V
  std::vector<std::vector<double>> element_charge_c;
  //! A netlist's probes ([circuit] probes), in the study's order, on the same samples [V or A]
  std::vector<std::vector<double>> probes;
};

//! Solves (sum C_i + C_L) dV/dt = sum sigma_i w_i x_i' + V sum(eps0 w_i x_i'/d0_i) - V/R
//! with V(0) = 0 and Q(0) = 0 on the given output times.
//!
//! V is linear in itself and stiff (R sum C_i ~ 1e-11 s against microsecond mechanics),
//! so each step is a 3-stage Radau IIA step (order 5, L-stable; Hairer & Wanner, Solving
//! ODEs II, §IV.5), which for a linear scalar equation is one 3x3 linear solve. Steps never
//! cross a motion breakpoint: each piece between breakpoints and output times is split
//! into `substeps` steps whose last node is the piece's end exactly (left limit there).
//! Q and every element charge ride along with the same stage quadrature, so
//! sum_i element_charge_c[i] = Q + C_L V up to rounding, and element_charge_c[i] matches
//! the change of Q_i = sigma_i w_i x_i - C_i V to the quadrature's accuracy (exact where
//! x_i is piecewise linear, up to rounding).
//!
//! Every x_i(t) must stay below l_i on [times.front(), times.back()]; the caller
//! checks the domain first (see domain_check.hpp).
//! @param elements  the S-TENG element of each asperity
//! @param motions   x_i(t), x_i'(t) of each asperity, same order
//! @param times     strictly increasing output times [s]; times[0] is the initial time
//! @param progress  if given, advanced by times.size() units in all (in batches); the
//!                  solver prints nothing itself
//! @throws InputError  for a non-positive R, negative C_L, zero substeps or unordered times
//! @throws ModelError  if sum C_i + C_L <= 0 at a node (some x reached l), or V, Q, a
//!                     current or an element charge is not finite at an output time
CircuitResult solve_circuit(std::span<const StengElement> elements, std::span<const Motion* const> motions,
                            std::span<const double> times, const CircuitParams& params,
                            Progress* progress = nullptr);

}  // namespace stengmc
