#pragma once
//! The voltage of n sliding asperities of the known device, from their atoms (README:
//! inverse estimation, "the record model").
//!
//! The elements share the load (MODEL.md §2): with u_i = R sigma w x_i', tau = R (sum C_i + C_L)
//! and gamma = eps0 / (sigma d0), V obeys V (1 - gamma sum u_i) = sum u_i - tau V'. Each atom
//! V_i (one asperity alone, from AtomTable) already holds its own element's share of both
//! couplings, so to first order in tau and gamma
//!
//!   V = sum V_i - R C_sum (sum V_i)' + R (sum C_i V_i)' + gamma ((sum V_i)^2 - sum V_i^2),
//!
//! with C_i = eps0 w (l - x_i) / d0 at the asperity's displacement (carried by the belt until
//! it reaches its mean displacement F / k_i, then that mean) and C_sum = sum C_i (C_L
//! cancels: every atom already carries it). The neglected terms are of
//! order (omega tau)^2 ~ 2e-4 at n = 16, 2 MHz. Time derivatives are the atoms' own (the
//! circuit equation's right-hand side at each sample): a difference quotient fails at the
//! belt's pick-up, a corner within one sample.
#include <Eigen/Dense>
#include <span>
#include <vector>

#include "inverse/atom_table.hpp"

namespace stengmc {

//! The sums over atoms the coupling terms need (sum V_i, sum V_i^2, sum V_i', sum C_i V_i',
//! sum C_i), so a fit can keep the atoms it does not move summed once.
struct AtomSums {
  std::vector<double> value, squares, slope, weighted_slope, capacitance;
  //! Zeros for `samples` samples.
  void reset(std::size_t samples);
};

class RecordModel {
 public:
  explicit RecordModel(const AtomTable& atoms);

  //! Adds atom k [N/m] to `sums`; with `d_dlnk` (one value per sample) also its dV/d ln k.
  //! Not thread-safe (scratch buffers): one model per thread.
  void add(double k, AtomSums& sums, std::span<double> d_dlnk = {}) const;
  //! The model voltage of the atoms in `sums`, coupling included [V].
  void voltage(const AtomSums& sums, std::span<double> out) const;

  //! The model voltage for stiffnesses `k` [N/m] on the table's grid, into `voltage` [V].
  //! With `jacobian` (samples x n), also dV/d ln k_i, column i: the atoms' own derivatives
  //! (the coupling terms' share, ~1e-2 of it, is left out: it moves the optimum by nothing,
  //! only the convergence rate).
  void evaluate(std::span<const double> k, std::span<double> voltage, Eigen::MatrixXd* jacobian = nullptr) const;

  [[nodiscard]] const AtomTable& atoms() const { return *atoms_; }
  [[nodiscard]] std::size_t samples() const { return atoms_->grid().samples; }

 private:
  mutable std::vector<double> atom_, slope_;  // scratch of add()
  const AtomTable* atoms_;
  double gamma_per_v_ = 0.0;   // eps0 / (sigma d0)
};

}  // namespace stengmc
