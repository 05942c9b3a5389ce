#pragma once
//! The stiffness law of the sliding asperities, fitted by maximum likelihood to identified
//! stiffnesses (one record's, or several records' pooled), three families compared by AIC
//! (Akaike 1974; Burnham & Anderson, "Model Selection and Multimodel Inference", 2002, §2.2:
//! Delta AIC > 2 is some evidence against a model, > 10 essentially none for it).
#include <array>
#include <span>
#include <string>
#include <vector>

#include "inverse/inverse_prior.hpp"

namespace stengmc {

struct LawFit {
  StiffnessFamily family = StiffnessFamily::lognormal;
  //! lognormal: median [N/m], sigma_log [-]; gamma, weibull: shape [-], scale [N/m]
  std::array<double, 2> parameters{};
  //! 90 % Wald intervals from the observed information, in ln of each parameter (so they
  //! stay positive): [low, high] per parameter
  std::array<std::array<double, 2>, 2> interval{};
  double log_likelihood = 0.0;
  double aic = 0.0;         //!< 2 x 2 - 2 ln L
  double median = 0.0;      //!< the fitted law's median [N/m]
  double sd_log = 0.0;      //!< the fitted law's sd of ln k [-]
  bool fitted = false;      //!< false: fewer than 3 distinct stiffnesses, or no spread (has_spread)
};

//! Narrowest population a law is fitted to: sd of ln k [-]. Stiffnesses that agree to
//! 0.01 % are one stiffness found several times (asperities of equal k give lines that
//! merge to ~1e-9): every family then tends to a point mass, the three are alike to AIC,
//! and their shapes run to 1e4 (Weibull) and 1e8 (gamma) and beyond. The prior's sd of
//! ln k is 0.1-0.6, so a sliding population this narrow is "one stiffness", not a law.
inline constexpr double MIN_LAW_SD_LOG = 1e-4;

//! True when the stiffnesses spread enough for a law: sd of ln k >= MIN_LAW_SD_LOG.
bool has_spread(std::span<const double> stiffness_n_per_m);

//! Maximum-likelihood fit of one family: lognormal in closed form (mean and 1/n variance of
//! ln k); gamma by Newton on ln a - psi(a) = ln mean(k) - mean(ln k) (Minka 2002, "Estimating
//! a gamma distribution", starting point and iteration); Weibull by the profile equation
//! sum k^c ln k / sum k^c - 1/c = mean(ln k), solved by TOMS 748 (Alefeld, Potra & Shi 1995)
//! in a bracket found from the data. Not fitted (`fitted` false): fewer than 3 distinct
//! stiffnesses, or a spread below MIN_LAW_SD_LOG.
LawFit fit_stiffness_law(std::span<const double> stiffness_n_per_m, StiffnessFamily family);

//! All three families, best (smallest AIC) first.
std::vector<LawFit> compare_stiffness_laws(std::span<const double> stiffness_n_per_m);

}  // namespace stengmc
