#include "inverse/count_posterior.hpp"

#include <algorithm>
#include <cmath>

#include "core/constants.hpp"
#include "core/error.hpp"

namespace stengmc {

CountPosterior count_posterior(const std::vector<OrderFit>& fits, double sigma_v, const InversePrior& prior,
                               const LogStiffnessDensity& density) {
  if (!(sigma_v > 0.0)) throw Error("count_posterior: the noise level must be > 0");
  CountPosterior out;
  // The prior's spread of ln k: the widest sigma_log of its laws, or that of a gamma / Weibull.
  const auto [low, high] = prior.support(1e-3);
  const double spread = std::max(0.05, std::log(high / low) / 6.0);
  const double s2 = sigma_v * sigma_v;
  for (std::size_t n = 0; n < fits.size(); ++n) {
    // Orders fitted only along the greedy path (no normal matrix) are far from the best: their
    // evidence, dominated by -RSS / 2 sigma^2, is negligible without the determinant too.
    if (n < prior.count_min || n > prior.count_max) continue;
    const OrderFit& fit = fits[n];
    double log_evidence = -fit.residual_v2 / (2.0 * s2) + 0.5 * static_cast<double>(n) * std::log(2.0 * PI) +
                          std::lgamma(static_cast<double>(n) + 1.0);
    for (double k : fit.stiffness_n_per_m) log_evidence += density(k);
    if (n > 0 && fit.normal_matrix.rows() == static_cast<Eigen::Index>(n)) {
      Eigen::MatrixXd h = fit.normal_matrix / s2;
      h.diagonal().array() += 1.0 / (spread * spread);
      // ln det by Cholesky (H is symmetric positive definite).
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
