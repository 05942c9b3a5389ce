#include "inverse/noise_judge.hpp"

#include <numeric>
#include <vector>

namespace stengmc {

NoiseJudge::Judgement NoiseJudge::judge(RecordFit& fit, const OrderFit& order) const {
  const double s = fit.sigma_v();
  if (order.residual_v2 == judged_rss_v2_ && s == judged_sigma_v_ && order.state.atoms.size() == judged_atoms_) return judged_;
  const std::size_t m = fit.record().size();
  FitState state = order.state;
  Judgement out;
  // Ten segments of at least ten samples each, else one (the chi^2 alone): a record too short
  // to cut is judged as before.
  const auto segments = [&](std::size_t first) { return m >= first + 10 * RESIDUAL_SEGMENTS ? RESIDUAL_SEGMENTS : 1; };
  if (!level_) {
    out.chi2 = order.residual_v2 / (s * s);
    if (out.chi2 <= fitting_chi2(m)) out.worst = worst_residual_segment(fit.residual(state), s, 0, segments(0));
  } else {
    std::vector<double> residual = fit.residual(state);
    const Whitener whitener = whitener_of(fit_noise_spectrum(residual), m);
    const double level_v = level_(whitener);
    const Whitener previous = fit.whitener();
    fit.set_noise(whitener, level_v);
    out.chi2 = fit.whitened_rss(state) / (level_v * level_v);
    fit.set_noise(previous, s);
    if (out.chi2 <= fitting_chi2(m)) {
      const double mean = std::accumulate(residual.begin(), residual.end(), 0.0) / static_cast<double>(m);
      for (double& v : residual) v -= mean;
      whitener.apply(residual, residual);
      // The filter's first taps see the record's start, not its past: left out.
      const std::size_t first = whitener.coefficients().size();
      out.worst = worst_residual_segment(residual, level_v, first, segments(first));
    }
  }
  out.fits = out.worst.segments > 0 && out.worst.p_value >= bonferroni_p_bound(FITS_SIGMAS, out.worst.segments);
  judged_rss_v2_ = order.residual_v2, judged_sigma_v_ = s, judged_atoms_ = order.state.atoms.size(), judged_ = out;
  return out;
}

}  // namespace stengmc
