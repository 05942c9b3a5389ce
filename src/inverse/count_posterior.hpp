#pragma once
//! The posterior of the number of sliding asperities from the fits of every order (README:
//! inverse estimation, "count"). This is the raw (uncalibrated) posterior; a calibration bank
//! recalibrates it on simulations (calibration_maps.hpp).
//!
//! With white noise of known sigma, the evidence of n atoms is approximated by Laplace's
//! method about the best fit (MacKay, "Information Theory, Inference, and Learning
//! Algorithms", 2003, §27-28):
//!
//!   ln p(y | n) ~ -RSS_n / 2 sigma^2 + sum_i ln p(ln k_i) + (n/2) ln 2 pi - (1/2) ln det H_n + ln n!
//!
//! with H_n = J^T J / sigma^2 + I / s^2 the curvature in ln k (the prior's spread s of ln k
//! keeps H regular where two atoms coincide) and n! for the atoms' exchangeable labels.
//! P(n) ~ p(y | n) p(n), p(n) uniform on the prior's count range.
#include <vector>

#include "inverse/inverse_prior.hpp"
#include "inverse/line_search.hpp"

namespace stengmc {

struct CountPosterior {
  std::vector<std::size_t> counts;      //!< the orders that were fitted and allowed by the prior
  std::vector<double> log_evidence;     //!< ln p(y | n) + ln p(n), up to a common constant
  std::vector<double> probability;      //!< normalised
  std::size_t best = 0;                 //!< the most probable count
};

//! @param fits fits indexed by their number of atoms (LineSearch::search)
//! @param sigma_v the noise's standard deviation [V]
CountPosterior count_posterior(const std::vector<OrderFit>& fits, double sigma_v, const InversePrior& prior,
                               const LogStiffnessDensity& density);

}  // namespace stengmc
