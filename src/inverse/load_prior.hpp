#pragma once
//! What the prior says of one sliding asperity's load (docs/inverse.md, "the prior"): the
//! marginal law of rho = N_i / N, N the device's normal_load_n, over the prior's load spread
//! (a Greenwood–Williamson law whose CV is uniform on load_cv, MODEL.md §4.4) and its
//! tolerance (the mean load and mu_s each within +-tau: the friction an atom feels is
//! mu_s N_i, so both scale it alike). Tabulated as a density of ln rho from a fixed-seed
//! Monte Carlo sample (2e5 draws, a Gaussian kernel of width 0.05 in ln rho): smooth, and
//! the same in every run.
#include <utility>
#include <vector>

#include "inverse/inverse_prior.hpp"

namespace stengmc {

class LoadPrior {
 public:
  explicit LoadPrior(const InversePrior& prior);

  //! True when the prior gives every asperity the device's own load.
  [[nodiscard]] bool fixed() const { return fixed_; }
  //! ln p(ln rho) (density per unit ln rho); steeply falling beyond the table.
  [[nodiscard]] double log_density(double log_ratio) const;
  //! [rho_low, rho_high]: the 1e-4 and 1 - 1e-4 quantiles of rho [-].
  [[nodiscard]] std::pair<double, double> support() const { return support_; }
  //! Mean and standard deviation of ln rho [-].
  [[nodiscard]] double mean_log() const { return mean_log_; }
  [[nodiscard]] double sd_log() const { return sd_log_; }

 private:
  bool fixed_ = true;
  std::pair<double, double> support_{1.0, 1.0};
  double mean_log_ = 0.0, sd_log_ = 0.0;
  double first_ = 0.0, step_ = 1.0;  // the table's grid in ln rho
  std::vector<double> log_density_;
};

}  // namespace stengmc
