#pragma once
//! The search for the stiffnesses of n sliding asperities, for every n near the best one
//! (docs/inverse.md, "search").
//!
//! Each atom has a fixed amplitude and phase (the known device fixes both for a given k), so
//! a record is fitted by choosing the k_i alone: greedy additions (the best-scoring
//! proposal, refined with exact atoms) each followed by a joint Levenberg–Marquardt fit of
//! every ln k_i (Levenberg 1944, Marquardt 1963; Nocedal & Wright, Numerical Optimization,
//! 2nd ed., §10.3). Two asperities too close to tell apart add up to twice an atom, which
//! no single atom explains: the count stays identifiable where frequency resolution is
//! lost, and the greedy step adds the second one. Along the greedy path only the new atom and
//! its neighbours (within 8 line widths) are refitted; the orders the posterior weighs (the
//! greedy count -1 .. +extra) are then refitted in full.
#include <Eigen/Dense>
#include <span>
#include <vector>

#include "inverse/line_proposals.hpp"
#include "inverse/record_model.hpp"

namespace stengmc {

//! The best fit found with a given number of atoms.
struct OrderFit {
  std::vector<double> stiffness_n_per_m;  //!< ascending [N/m]
  double residual_v2 = 0.0;               //!< sum of squared residuals [V^2]
  //! J^T J of the fit in ln k, same order [V^2]; empty for orders fitted only along the greedy
  //! path (far from the count the search settled on: their evidence is negligible)
  Eigen::MatrixXd normal_matrix;
  std::size_t iterations = 0;             //!< Levenberg–Marquardt iterations of the last refinement
};

struct LineSearchOptions {
  std::size_t max_iterations = 60;   //!< per Levenberg–Marquardt refinement
  //! The greedy path stops when the best addition would lower the squared residual by less
  //! than this fraction of its atom's energy (a true atom lowers it by about its energy,
  //! one that is not there raises it by as much).
  double stop_fraction = 0.25;
  std::size_t extra_orders = 2;      //!< orders fitted past the greedy stop (for the count's posterior)
  std::size_t candidates = 4;        //!< proposals refined with exact atoms at each step
};

class LineSearch {
 public:
  LineSearch(const RecordModel& model, LineProposals& proposals, std::span<const double> record,
             const LineSearchOptions& options = {});

  //! Levenberg–Marquardt fit of the ln k_i from `k` [N/m]: all of them, or only those
  //! `active` marks (the others stay where they are). With `normal_matrix`, the fit's J^T J
  //! over all atoms is computed at the end.
  OrderFit refine(std::vector<double> k, const std::vector<bool>& active = {}, bool normal_matrix = true);

  //! Fits for n = 0 (no atom) along the greedy path to its stop, then `extra_orders` more,
  //! and on to `min_count` at least (a prior's smallest count: the posterior weighs no order
  //! below it), never beyond `max_count`: index n of the result holds the fit with n atoms.
  std::vector<OrderFit> search(std::size_t max_count, std::size_t min_count = 0);

  //! The record minus the model of `k`.
  std::vector<double> residual(std::span<const double> k) const;

 private:
  //! Exact decrease of the squared residual if atom k were added to a fit with residual r.
  double exact_score(double k, std::span<const double> residual) const;
  LineCandidate best_addition(std::span<const double> residual);
  double residual_norm(std::span<const double> k, Eigen::MatrixXd* jacobian, std::vector<double>& r) const;
  //! Atoms within this many line widths of a new one are refitted with it on the greedy path.
  static constexpr double NEIGHBOURHOOD_WIDTHS = 8.0;

  const RecordModel* model_;
  LineProposals* proposals_;
  std::span<const double> record_;
  LineSearchOptions options_;
};

}  // namespace stengmc
