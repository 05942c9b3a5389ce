#include "inverse/noise_judge.hpp"

namespace stengmc {

double NoiseJudge::chi2(RecordFit& fit, const OrderFit& order) const {
  const double s = fit.sigma_v();
  if (!level_) return order.residual_v2 / (s * s);
  if (order.residual_v2 == judged_rss_v2_ && s == judged_sigma_v_ && order.state.atoms.size() == judged_atoms_) return judged_chi2_;
  FitState state = order.state;
  const Whitener whitener = whitener_of(fit_noise_spectrum(fit.residual(state)), fit.record().size());
  const double noise_v = level_(whitener);
  const Whitener previous = fit.whitener();
  fit.set_noise(whitener, noise_v);
  const double chi2 = fit.whitened_rss(state) / (noise_v * noise_v);
  fit.set_noise(previous, s);
  judged_rss_v2_ = order.residual_v2, judged_sigma_v_ = s, judged_chi2_ = chi2, judged_atoms_ = order.state.atoms.size();
  return chi2;
}

}  // namespace stengmc
