#include "inverse/nested_search.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace stengmc {

std::vector<InversePrior> nested_priors(const InversePrior& prior) {
  const bool loads = prior.load_cv[1] > 0.0, onsets = prior.onset_s[1] > prior.onset_s[0];
  std::vector<InversePrior> out;
  if (!loads && !onsets) return out;
  InversePrior ideal = prior;
  ideal.load_cv = {0.0, 0.0};
  ideal.onset_s = {prior.onset_s[0], prior.onset_s[0]};
  out.push_back(ideal);
  if (loads && onsets) {
    InversePrior loads_alone = prior;
    loads_alone.onset_s = ideal.onset_s;
    out.push_back(loads_alone);
    InversePrior onsets_alone = prior;
    onsets_alone.load_cv = ideal.load_cv;
    out.push_back(onsets_alone);
  }
  return out;
}

struct NestedSearch::Level {
  LoadPrior loads;
  FitLayout layout;
  LineProposals proposals;
  Level(const RecordModel& model, const InversePrior& prior, const KnownDevice& device)
      : loads(prior), layout(fit_layout(prior, device, loads)), proposals(model, layout, loads) {}
};

NestedSearch::NestedSearch(const RecordModel& model, const InversePrior& prior, const KnownDevice& device,
                           const LineSearchOptions& options)
    : model_(&model), options_(options) {
  for (const InversePrior& nested : nested_priors(prior)) levels_.push_back(std::make_unique<Level>(model, nested, device));
}

NestedSearch::~NestedSearch() = default;

void NestedSearch::set_step_onsets(const std::vector<double>& asperity_onsets_s) {
  step_asperities_s_ = asperity_onsets_s;
  std::vector<double> onsets = asperity_onsets_s;
  onsets.erase(std::unique(onsets.begin(), onsets.end()), onsets.end());
  for (const std::unique_ptr<Level>& level : levels_) level->proposals.set_step_onsets(onsets);
}

NestedFits NestedSearch::search(std::span<const double> voltage, double sigma_v, const FitLayout& layout,
                               std::size_t max_count, std::size_t min_count, const WhitenedLevel& whitened_level) {
  NestedFits out;
  const double s2 = sigma_v * sigma_v;
  const auto samples = static_cast<double>(voltage.size());
  const double fits_chi2 = fitting_chi2(voltage.size());
  // A nested fit's atoms carry their loads (N x the shared factor, record_fit.cpp); a layout of
  // per-atom loads has no shared factor.
  auto lifted = [&](const FitState& state) {
    FitState s = state;
    if (!layout.load_shared) s.load_factor = 1.0;
    return s;
  };
  // Judged against the noise the estimator will assume: white, or (coloured) the spectrum of
  // each order's residual (noise_judge.hpp), by the searches' re-seating and by this stop alike.
  const NoiseJudge judge = layout.coloured_noise && whitened_level ? NoiseJudge(whitened_level) : NoiseJudge();
  for (const std::unique_ptr<Level>& level : levels_) {
    RecordFit fit(*model_, level->layout, level->loads, voltage);
    fit.set_noise(Whitener(), sigma_v);
    LineSearch search(fit, level->proposals, options_, judge);
    FitState start;
    start.damping_rate_per_s = level->layout.nominal_damping_rate;
    std::vector<OrderFit> fits = search.search(start, max_count, min_count);
    if (level->layout.onset_free && !step_asperities_s_.empty() && step_asperities_s_.size() < max_count) {
      // A start from the onset steps; it replaces its order's fit where better.
      keep_better_start(fits, search.place_at_steps(start, step_asperities_s_), sigma_v);
    }
    // Only the orders refitted in full (they have their normal matrix), and of those the ones
    // within reach of the best (as LineSearch::refit judges hopeless): the others carry little
    // posterior weight, and a broadened refit of each would cost its time for nothing.
    double best = INFINITY;
    std::size_t best_order = 0;
    for (std::size_t n = 0; n < fits.size(); ++n)
      if (const double chi2 = fits[n].residual_v2 / s2 + fits[n].penalty; chi2 < best) best = chi2, best_order = n;
    for (const OrderFit& f : fits)
      if (!f.state.atoms.empty() && f.normal_matrix.size() > 0 && f.residual_v2 / s2 + f.penalty <= best + HOPELESS_CHI2_GAP)
        out.starts.push_back(lifted(f.state));
    const NoiseJudge::Judgement judged = judge.judge(fit, fits[best_order]);
    if (std::getenv("STENGMC_DEBUG_SEARCH"))
      std::fprintf(stderr, "nested level: best order %zu, chi2 / M %.4f (fits below %.4f), worst segment %zu-%zu p %.3g of %zu\n",
                   best_order, judged.chi2 / samples, fits_chi2 / samples, judged.worst.first_sample,
                   judged.worst.last_sample, judged.worst.p_value, judged.worst.segments);
    if (judged.fits) {
      for (const OrderFit& f : fits) out.fitted_orders.push_back(lifted(f.state));
      break;
    }
  }
  return out;
}

}  // namespace stengmc
