#pragma once
//! The posterior of the number of sliding asperities from the fits of every order
//! (docs/inverse.md, "count"). This is the raw (uncalibrated) posterior; a calibration bank
//! recalibrates it on simulations (calibration_maps.hpp).
//!
//! With the noise whitened (innovation variance sigma^2), the evidence of n atoms is
//! approximated by Laplace's method about the best (maximum a posteriori) fit (MacKay,
//! "Information Theory, Inference, and Learning Algorithms", 2003, §27-28):
//!
//!   ln p(y | n) ~ -RSS_n / 2 sigma^2 + sum_i ln p(theta_i) + (P_n / 2) ln 2 pi - (1/2) ln det H_n + ln n!
//!
//! theta_i an atom's free parameters (ln k, and ln N and t_on when the prior frees them) with
//! the prior's densities (ln k's marginal, the loads' law, onsets uniform), P_n their number
//! (and the device's shared ones), H_n = J^T J / sigma^2 + the prior's curvatures (which keep
//! H regular where two atoms coincide), n! for the atoms' exchangeable labels.
//! P(n) ~ p(y | n) p(n), p(n) uniform on the prior's count range.
#include <vector>

#include "inverse/fit_layout.hpp"
#include "inverse/inverse_prior.hpp"
#include "inverse/load_prior.hpp"
#include "inverse/record_fit.hpp"

namespace stengmc {

struct CountPosterior {
  std::vector<std::size_t> counts;      //!< the orders that were fitted and allowed by the prior
  std::vector<double> log_evidence;     //!< ln p(y | n) + ln p(n), up to a common constant
  std::vector<double> probability;      //!< normalised
  std::size_t best = 0;                 //!< the most probable count
};

//! The prior's curvatures of an order's parameters, in the normal matrix's order (record_fit.hpp).
Eigen::VectorXd prior_curvatures(std::size_t atoms, const InversePrior& prior, const FitLayout& layout, const LoadPrior& loads);

//! @param fits fits indexed by their number of atoms (LineSearch::search)
//! @param sigma_v the (whitened) noise's standard deviation [V]
CountPosterior count_posterior(const std::vector<OrderFit>& fits, double sigma_v, const InversePrior& prior,
                               const LogStiffnessDensity& density, const FitLayout& layout, const LoadPrior& loads);

}  // namespace stengmc
