#pragma once
//! The circuit of MODEL.md §2 solved from the elements' sums on the output grid: each
//! asperity's motion is added to a few per-sample sums and can then be dropped, so memory
//! and the circuit's own work do not grow with the number of asperities (streaming).
//!
//! With U = C V (C = C_L + sum C_i, C_i = eps0 w_i (l_i - x_i) / d0_i), the circuit
//! equation (sum C_i + C_L) V' = sum sigma_i w_i x_i' + V sum eps0 w_i x_i' / d0_i - V/R
//! reads U' = S(t) - U / (R C(t)) (the conductance term is -C' V), and the delivered
//! charge is exactly Q = P(t) - P(t0) - U, with P = sum sigma_i w_i x_i (charge balance:
//! Q + C_L V = sum_i [Q_i(t) - Q_i(t0)], Q_i = sigma_i w_i x_i - C_i V). So Q needs no
//! quadrature of V and is as accurate as the displacements themselves; only U, a small
//! fast-relaxing quantity (R C ~ 1e-10 s), is integrated. Everything the circuit needs of
//! n motions is then S = P', P and K = sum eps0 w_i x_i / d0_i on the grid, which the
//! ElementSums accumulate: each interval's P and K are the quintic Hermite through their
//! values and slopes at both ends and at the midpoint (error ~ (w dt)^6 / 3e5 in x,
//! (w dt)^5 / 1e4 in x' for a motion of angular frequency w; 1e-9 at 2 MHz and 10 ns
//! samples, exact for the cubic splines and straight lines of sampled motions). An
//! element whose motion has a breakpoint (kink) inside an interval is evaluated exactly
//! there instead, and the steps split at the kink (ElementSums::add).
//!
//! U is stepped with 3-stage Radau IIA (order 5, L-stable, stiffly accurate; Hairer &
//! Wanner, Solving ODEs II, Sec. IV.5), `substeps` steps per output interval, as the
//! motion-node solver (circuit_solver.hpp), which evaluates every motion at every node.
#include <cstddef>
#include <memory>
#include <span>
#include <vector>

#include "circuit/circuit_solver.hpp"
#include "model/asperity.hpp"
#include "model/motion.hpp"

namespace stengmc {

class Progress;

//! Radau steps per substep in an interval holding fine structure (the belt's catch): with
//! it the four-asperity chain's V error at v_b = 10 m/s falls from 1.1e-6 (no refinement)
//! to 1.8e-7, below which 8 changes nothing (test_chain_reference).
inline constexpr std::size_t FINE_STRUCTURE_REFINEMENT = 4;
//! Points per sample interval at which an element with fine structure there is recorded.
inline constexpr std::size_t FINE_STRUCTURE_POINTS = 64;

class ElementSums {
 public:
  ElementSums() = default;
  //! Empty sums on `times_s` (strictly increasing).
  explicit ElementSums(std::span<const double> times_s) { reset(times_s); }

  //! Empties the sums and takes a new grid (buffers keep their capacity).
  void reset(std::span<const double> times_s);

  //! Adds one element driven by `motion`, whose samples on the grid (with midpoints) are
  //! `samples`. Where its motion has a breakpoint strictly inside an interval, it is
  //! evaluated exactly there and the interval's steps split at every such element's
  //! breakpoints: the sums keep the motion's excerpt over those intervals (Motion::excerpt,
  //! bit for bit the same there), or, for a motion without one, `motion` must outlive the
  //! solve; where it has fine structure (Motion::fine_structure), it is recorded densely
  //! over the interval now, and the interval takes FINE_STRUCTURE_REFINEMENT times as many steps.
  //! @return whether `motion` must outlive the solve (a breakpoint inside an interval and no excerpt)
  bool add(const StengElement& element, const MotionSamples& samples, const Motion& motion);

  [[nodiscard]] std::span<const double> times() const { return times_; }
  [[nodiscard]] std::size_t elements() const { return elements_; }

 private:
  friend struct SummedCircuitSolver;

  //! An element evaluated exactly over one interval.
  struct Exception {
    std::size_t interval = 0;
    //! The motion, evaluated exactly at every node (intervals with a kink of it), or none:
    //! then its fine structure is read from a table of FINE_STRUCTURE_POINTS + 1 equally
    //! spaced (x, x') over the interval, taken when it was added, by cubic Hermite
    //! interpolation (the motion itself need not outlive add()).
    const Motion* motion = nullptr;
    std::size_t table = 0;           // first of its (x, x') pairs in fine_tables_
    std::size_t kinks = 0;           // its breakpoints: element_kinks_[kinks]
    bool fine = false;               // it has fine structure here (Motion::fine_structure)
    double charge_per_m = 0.0;       // sigma w [C/m]
    double capacitance_per_m = 0.0;  // eps0 w / d0 [F/m]
    // Its samples at the interval's ends (right limit at the start, left at the end),
    // which the interval's Hermite data must not count.
    double x_start = 0.0, v_start = 0.0, x_end = 0.0, v_end = 0.0;
  };

  std::vector<double> times_;
  std::size_t elements_ = 0;
  double capacitance_at_zero_ = 0.0;  // sum eps0 w l / d0 [F]
  // Per sample: P, K and their slopes from the right and from the left.
  std::vector<double> p_, k_, dp_right_, dk_right_, dp_left_, dk_left_;
  // Per interval, at its midpoint: P, K, P', K'.
  std::vector<double> p_mid_, k_mid_, dp_mid_, dk_mid_;
  std::vector<Exception> exceptions_;  // in the order added
  std::vector<std::vector<double>> element_kinks_;  // breakpoints of the elements with exceptions
  std::vector<double> fine_tables_;  // (x, x') pairs of the fine-structure tables
  // Excerpts of the motions with kinks (Motion::excerpt), which their exceptions evaluate;
  // shared so that the sums stay copyable.
  std::vector<std::shared_ptr<const Motion>> excerpts_;
};

//! The solution on the grid's first `samples` times.
struct SummedCircuit {
  std::vector<double> voltage_v;       //!< V [V]
  std::vector<double> charge_c;        //!< Q, delivered to R [C]
  std::vector<double> dv_dt_v_per_s;   //!< V' from the left (at the first sample: from the right) [V/s]
};

//! Solves the circuit of MODEL.md §2 (V(t0) = 0, Q(t0) = 0) on the first `samples` grid
//! times of `sums`. `progress`, if given, is advanced by `samples` units in all.
//! @throws InputError for a non-positive R, negative C_L or zero substeps
//! @throws ModelError if sum C_i + C_L <= 0 at a node (some x reached l), or V or Q is not
//!         finite at an output time (as solve_circuit)
SummedCircuit solve_summed_circuit(const ElementSums& sums, std::size_t samples, const CircuitParams& params,
                                   Progress* progress = nullptr);

//! The same into `out`, whose buffers are reused.
void solve_summed_circuit(const ElementSums& sums, std::size_t samples, const CircuitParams& params, SummedCircuit& out,
                          Progress* progress = nullptr);

//! One element's current i = sigma w x' + (eps0 w x'/d0) V - C_i V' (x' from the left, as
//! V' is) and delivered charge Q_i(t) - Q_i(t0), Q_i = sigma w x - C_i V (exact), on the
//! circuit's samples, into `current_a` and `charge_c` (resized).
//! @throws ModelError if either is not finite (naming `element_number` and the time)
void element_traces(const StengElement& element, const MotionSamples& samples, const SummedCircuit& circuit,
                    std::span<const double> times_s, std::size_t element_number, std::vector<double>& current_a,
                    std::vector<double>& charge_c);

//! The whole of it for motions at hand (the `circuit` command, tests): each motion sampled,
//! summed, the circuit solved and every element's current and charge, as solve_circuit.
CircuitResult solve_circuit_streamed(std::span<const StengElement> elements, std::span<const Motion* const> motions,
                                     std::span<const double> times, const CircuitParams& params,
                                     Progress* progress = nullptr);

}  // namespace stengmc
