#pragma once
//! The least-squares fit of a record's parameters for a given number of atoms
//! (docs/inverse.md, "the search"): Levenberg–Marquardt (Levenberg 1944, Marquardt 1963;
//! Nocedal & Wright, "Numerical Optimization", 2nd ed., §10.3) on the nonlinear parameters
//! the layout frees (each atom's ln k, ln N, t_on; the device's ln d and shared load factor),
//! within their bounds, with the linear ones (amplitude, offset) solved at every step and
//! projected out of the Jacobian (variable projection: Golub & Pereyra 1973, in Kaufman's
//! 1975 form). Residuals and Jacobians go through the noise's whitening filter, so the
//! fit is the maximum of the likelihood under the estimated noise spectrum; the prior's
//! density of each atom's load is added (a maximum a posteriori fit), which keeps the load
//! of an atom the record barely constrains where the prior puts it.
#include <Eigen/Dense>
#include <span>
#include <vector>

#include "inverse/fit_layout.hpp"
#include "inverse/load_prior.hpp"
#include "inverse/noise_whitening.hpp"
#include "inverse/record_model.hpp"

namespace stengmc {

//! The best fit found with a given number of atoms.
struct OrderFit {
  FitState state;                 //!< atoms ascending in k
  double residual_v2 = 0.0;       //!< |W (y - a M - b)|^2 [V^2]
  double penalty = 0.0;           //!< -2 ln p of the loads' prior (MAP term) [-]
  //! J^T J of the whitened, projected Jacobian over every free nonlinear parameter (atoms in
  //! order of k, each ln k, ln N, t_on as freed; then ln d, ln load factor) [V^2 per unit];
  //! empty for fits made only along the greedy path
  Eigen::MatrixXd normal_matrix;
  std::size_t iterations = 0;
};

class RecordFit {
 public:
  RecordFit(const RecordModel& model, const FitLayout& layout, const LoadPrior& loads, std::span<const double> record);

  //! Noise whitening (identity by default) and the noise level the prior's terms are weighed
  //! against [V].
  void set_noise(const Whitener& whitener, double sigma_v);

  //! Levenberg–Marquardt from `start`: the atoms `active` marks (all when empty) move, the
  //! others stay; the device's shared parameters move when `shared`. With `normal_matrix`, the
  //! fit's J^T J over all its free parameters is computed at the end.
  OrderFit refine(FitState start, const std::vector<bool>& active = {}, bool shared = false, bool normal_matrix = true,
                  std::size_t max_iterations = 60);

  //! The raw (unwhitened) record minus the model of `state`, the linear parameters solved first
  //! (they are written back into `state`).
  std::vector<double> residual(FitState& state) const;
  //! |W (y - a M - b)|^2 with the linear parameters solved [V^2]; `state`'s are updated.
  double whitened_rss(FitState& state) const;

  //! -2 ln p of the prior's load density for an atom's load (0 for a fixed load).
  [[nodiscard]] double load_penalty(double load_n) const;

  [[nodiscard]] const RecordModel& model() const { return *model_; }
  [[nodiscard]] const FitLayout& layout() const { return layout_; }
  [[nodiscard]] const Whitener& whitener() const { return whitener_; }
  [[nodiscard]] double sigma_v() const { return sigma_v_; }
  [[nodiscard]] std::span<const double> record() const { return record_; }

 private:
  //! Solves the linear parameters of `state` for the unit-amplitude model `unit` (raw) and
  //! returns the whitened residual into `r`; `wunit` receives W M.
  double solve_linear(FitState& state, std::span<const double> unit, std::vector<double>& r, std::vector<double>& wunit) const;

  //! Scratch of refine, kept between refits (a record's search makes hundreds): the atoms'
  //! evaluations and the Jacobian (up to M x p doubles) were allocated, and their pages
  //! faulted in, anew by each.
  struct Workspace {
    AtomSums frozen, sums;
    std::vector<AtomValues> values;
    std::vector<double> unit, wunit, residual;
    std::vector<double> jacobian;  // M x p, column-major
  };
  Workspace work_;
  const RecordModel* model_;
  FitLayout layout_;
  const LoadPrior* loads_;
  std::span<const double> record_;
  std::vector<double> whitened_record_;
  std::vector<double> whitened_ones_;
  Whitener whitener_;
  double sigma_v_ = 1.0;
};

//! Sorts the atoms of `state` by stiffness.
void sort_atoms(FitState& state);

}  // namespace stengmc
