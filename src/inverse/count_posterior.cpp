#include "inverse/count_posterior.hpp"

#include <algorithm>
#include <cmath>

#include "core/constants.hpp"
#include "core/error.hpp"

namespace stengmc {

Eigen::VectorXd prior_curvatures(std::size_t atoms, const InversePrior& prior, const FitLayout& layout, const LoadPrior& loads) {
  const auto [low, high] = prior.support(1e-3);
  const double spread = std::max(0.05, std::log(high / low) / 6.0);
  const double load_sd = std::max(0.05, loads.sd_log());
  // A uniform prior has no curvature; its sd stands in, so H stays regular where the record
  // does not pin a parameter (the Laplace approximation is then as wide as the prior).
  const double onset_sd = std::max(1e-9, (layout.onset_max_s - layout.onset_min_s) / std::sqrt(12.0));
  const double damping_sd = std::max(1e-3, std::log(layout.max_damping_rate / layout.min_damping_rate) / std::sqrt(12.0));
  const std::size_t per_atom = layout.per_atom();
  Eigen::VectorXd c(static_cast<Eigen::Index>(atoms * per_atom + layout.shared()));
  Eigen::Index i = 0;
  for (std::size_t a = 0; a < atoms; ++a) {
    c(i++) = 1.0 / (spread * spread);
    if (layout.load_per_atom) c(i++) = 1.0 / (load_sd * load_sd);
    if (layout.onset_free) c(i++) = 1.0 / (onset_sd * onset_sd);
  }
  if (layout.damping_free) c(i++) = 1.0 / (damping_sd * damping_sd);
  if (layout.load_shared) c(i++) = 1.0 / (load_sd * load_sd);
  return c;
}

CountPosterior count_posterior(const std::vector<OrderFit>& fits, double sigma_v, const InversePrior& prior,
                               const LogStiffnessDensity& density, const FitLayout& layout, const LoadPrior& loads) {
  if (!(sigma_v > 0.0)) throw Error("count_posterior: the noise level must be > 0");
  CountPosterior out;
  const double s2 = sigma_v * sigma_v;
  const double onset_log_density = layout.onset_free ? -std::log(layout.onset_max_s - layout.onset_min_s) : 0.0;
  const double damping_log_density =
      layout.damping_free ? -std::log(std::log(layout.max_damping_rate / layout.min_damping_rate)) : 0.0;
  for (std::size_t n = 0; n < fits.size(); ++n) {
    if (n < prior.count_min || n > prior.count_max) continue;
    const OrderFit& fit = fits[n];
    const std::size_t parameters = n * layout.per_atom() + (n > 0 ? layout.shared() : 0);
    // The fit's MAP terms: its loads' prior is in its penalty (-2 ln p).
    double log_evidence = -fit.residual_v2 / (2.0 * s2) - 0.5 * fit.penalty + 0.5 * static_cast<double>(parameters) * std::log(2.0 * PI) +
                          std::lgamma(static_cast<double>(n) + 1.0);
    for (const AtomParameters& a : fit.state.atoms) log_evidence += density(a.stiffness_n_per_m) + onset_log_density;
    if (n > 0) log_evidence += damping_log_density + (layout.load_shared ? loads.log_density(std::log(fit.state.load_factor)) : 0.0);
    // Orders fitted only along the greedy path (no normal matrix) are far from the best: their
    // evidence, dominated by -RSS / 2 sigma^2, is negligible without the determinant too.
    if (n > 0 && fit.normal_matrix.rows() == static_cast<Eigen::Index>(parameters)) {
      Eigen::MatrixXd h = fit.normal_matrix / s2;
      h.diagonal() += prior_curvatures(n, prior, layout, loads);
      const Eigen::LLT<Eigen::MatrixXd> llt(h);
      double log_det = 0.0;
      for (Eigen::Index i = 0; i < h.rows(); ++i) log_det += 2.0 * std::log(llt.matrixL()(i, i));
      log_evidence -= 0.5 * log_det;
    }
    out.counts.push_back(n);
    out.log_evidence.push_back(log_evidence);
  }
  if (out.counts.empty()) return out;
  const double top = *std::max_element(out.log_evidence.begin(), out.log_evidence.end());
  double total = 0.0;
  for (double e : out.log_evidence) total += std::exp(e - top);
  for (std::size_t j = 0; j < out.counts.size(); ++j) {
    out.probability.push_back(std::exp(out.log_evidence[j] - top) / total);
    if (out.log_evidence[j] == top) out.best = out.counts[j];
  }
  return out;
}

}  // namespace stengmc
