#include "inverse/record_estimator.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <numeric>

#include "core/constants.hpp"
#include "core/error.hpp"
#include "inverse/onset_steps.hpp"
#include "inverse/sample_statistics.hpp"
#include "inverse/se_inflation.hpp"
#include "spectral/amplitude_spectrum.hpp"

namespace stengmc {

namespace {

// The noise band starts this far above the prior's highest plausible line (its 1 - 1e-4
// quantile): a line's Lorentzian skirt, d / pi wide, is far below the noise there.
constexpr double NOISE_BAND_MARGIN = 1.25;

double mean_square(std::span<const double> v) {
  double s = 0.0;
  for (double x : v) s += x * x;
  return v.empty() ? 0.0 : s / static_cast<double>(v.size());
}

}  // namespace

RecordEstimator::RecordEstimator(const AtomLibrary& atoms, const InversePrior& prior, const LineSearchOptions& options)
    : atoms_(&atoms),
      prior_(prior),
      loads_(prior),
      layout_(fit_layout(prior, atoms.device(), loads_)),
      density_(prior),
      model_(atoms),
      proposals_(model_, layout_, loads_),
      options_(options),
      nested_(model_, prior_, atoms.device(), options),
      noise_(atoms.grid().samples, atoms.grid().sample_rate_hz(),
             NOISE_BAND_MARGIN * atoms.device().angular_frequency(prior.support().second) / (2.0 * PI)) {
  const auto [low, high] = prior.support();
  support_low_ = low;
  support_high_ = high;
  band_low_hz_ = atoms.device().angular_frequency(low) / (2.0 * PI);
  band_high_hz_ = atoms.device().angular_frequency(high) / (2.0 * PI);
}

ResidualChecks RecordEstimator::residual_checks(const RecordFit& fit, FitState state) const {
  ResidualChecks c;
  std::vector<double> r = fit.residual(state);
  fit.whitener().apply(r, r);
  const double s2 = fit.sigma_v() * fit.sigma_v();
  const std::size_t m = r.size();
  c.misfit = mean_square(r) / s2;
  // Over time: the span where the asperities break away, and the record's last third.
  const RecordGrid& grid = atoms_->grid();
  double last_breakaway = grid.start_s;
  for (const AtomParameters& a : state.atoms)
    last_breakaway = std::max(last_breakaway, atoms_->model().breakaway_time(a, state.damping_rate_per_s));
  const auto early_end = std::min(m, static_cast<std::size_t>(std::ceil((last_breakaway + 2e-6 - grid.start_s) / grid.step_s)));
  c.early = mean_square(std::span<const double>(r.data(), std::max<std::size_t>(early_end, 1))) / s2;
  c.late = mean_square(std::span<const double>(r.data() + 2 * m / 3, m - 2 * m / 3)) / s2;
  // Over frequency: the (whitened) residual's Hann periodogram, white at sigma^2 when the model fits.
  SpectrumAnalyzer analyzer(m, WindowKind::hann);
  const AmplitudeSpectrum s = analyzer.analyse(r, grid.sample_rate_hz());
  const std::vector<double>& w = analyzer.window();
  const double sum = std::accumulate(w.begin(), w.end(), 0.0), squares = std::inner_product(w.begin(), w.end(), w.begin(), 0.0);
  const double to_power = sum * sum / (4.0 * squares);
  double line = 0.0, low = 0.0;
  std::size_t n_line = 0, n_low = 0;
  for (std::size_t k = 1; k < s.frequency_hz.size(); ++k) {
    const double p = s.amplitude[k] * s.amplitude[k] * to_power;
    if (s.frequency_hz[k] >= band_low_hz_ && s.frequency_hz[k] <= band_high_hz_) line += p, ++n_line;
    else if (s.frequency_hz[k] < band_low_hz_) low += p, ++n_low;
  }
  if (n_line) c.line_band = line / static_cast<double>(n_line) / s2;
  if (n_low) c.low_band = low / static_cast<double>(n_low) / s2;
  return c;
}

RecordEstimate RecordEstimator::estimate(std::span<const double> voltage, const FitState* reference) {
  // CPU time of this thread: wall time would count whatever else the machine runs.
  timespec cpu_start{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &cpu_start);
  const std::size_t samples = atoms_->grid().samples;
  if (voltage.size() != samples) throw Error("RecordEstimator: the record has another length than the atoms' grid");
  RecordEstimate out;
  out.noise = noise_.estimate(voltage);

  // The record's power without its mean (an offset is no signal) sets the model's floor.
  const double mean = std::accumulate(voltage.begin(), voltage.end(), 0.0) / static_cast<double>(samples);
  double power = 0.0;
  for (double v : voltage) power += (v - mean) * (v - mean) / static_cast<double>(samples);
  const double floor_v = MIN_RELATIVE_NOISE * atoms_->device().voltage_scale_v();
  auto with_floor = [&](double sigma2, double signal_power) {
    return std::sqrt(std::max(sigma2 + MODEL_RELATIVE_ACCURACY * MODEL_RELATIVE_ACCURACY * signal_power, floor_v * floor_v));
  };
  // White noise first: the band above the lines, else the variance itself.
  const double white2 = out.noise.bins > 0 ? out.noise.sigma_v * out.noise.sigma_v : power;
  double sigma = with_floor(white2, power);

  // The noise level a whitener leaves: its innovation, with the model's floor on the whitened
  // record's power above it.
  auto whitened_level = [&](const Whitener& whitener) {
    std::vector<double> whitened(voltage.begin(), voltage.end());
    for (double& v : whitened) v -= mean;
    whitener.apply(whitened, whitened);
    const double innovation2 = whitener.innovation_sigma_v() * whitener.innovation_sigma_v();
    return with_floor(innovation2, std::max(0.0, mean_square(whitened) - innovation2));
  };
  // Contact onsets the record shows as steps (inverse/onset_steps.hpp), where the prior frees
  // onsets: the nested models' proposals try each placement at them too, and the start from
  // the steps places one atom at each. The broadened model's greedy additions and re-seats do
  // not: where a nested model does not fit the record to its noise, neither does the broadened
  // one as a rule (v_b = 1 m/s, docs/inverse.md), and there more placements are more ways to
  // patch its misfit with atoms the evidence rewards (all departures at once, 40 records: the
  // count's RMSE 5.3 with them, 4.1 without; staggered onsets at 10 m/s: 71 of 99 exact either way).
  std::vector<double> step_asperities;  // each step's onset once per asperity it carries
  if (layout_.onset_free) {
    const std::vector<OnsetStep> steps = onset_steps(atoms_->device(), prior_.support(0.01).second, sigma, atoms_->grid(), voltage);
    for (const OnsetStep& step : steps)
      for (long i = 0; i < std::max(1L, std::lround(step.units)); ++i) step_asperities.push_back(step.onset_s);
    if (std::getenv("STENGMC_DEBUG_SEARCH")) {
      std::fprintf(stderr, "onset steps: %zu at", steps.size());
      for (const OnsetStep& step : steps) std::fprintf(stderr, " %.3f", step.onset_s * 1e6);
      std::fprintf(stderr, " us\n");
    }
  }
  out.onset_steps = step_asperities.size();
  nested_.set_step_onsets(step_asperities);
  RecordFit fit(model_, layout_, loads_, voltage);
  fit.set_noise(Whitener(), sigma);
  // Under a prior of coloured noise the search judges its fits whitened (noise_judge.hpp).
  LineSearch search(fit, proposals_, options_, layout_.coloured_noise ? NoiseJudge(whitened_level) : NoiseJudge());
  FitState start;
  start.damping_rate_per_s = layout_.nominal_damping_rate;
  // The nested models first (inverse/nested_search.hpp). Where one fits the record to its
  // noise its orders are the fits, evaluated in the broadened model; else the broadened search.
  // Either way each nested order refitted in full is a start, polished in the broadened model,
  // that replaces its order's fit where it reaches a better optimum.
  NestedFits nested;
  if (nested_.applies())
    nested = nested_.search(voltage, sigma, layout_, prior_.count_max + 1, prior_.count_min, whitened_level);
  std::vector<OrderFit> fits;
  if (nested.fitted_orders.empty()) fits = search.search(start, prior_.count_max + 1, prior_.count_min);
  for (FitState& s : nested.fitted_orders) fits.push_back(fit.refine(std::move(s), {}, true, false, 0));
  for (FitState& s : nested.starts)
    if (s.atoms.size() <= fits.size()) keep_better_start(fits, search.polish(std::move(s)), sigma);
  // A start from the onset steps, one atom at each, where the record shows them
  // (LineSearch::place_at_steps), unless a nested model already fits the record to its noise:
  // its own onset-free level had that start, and its fits are the answer.
  if (nested.fitted_orders.empty() && !step_asperities.empty() && step_asperities.size() <= prior_.count_max)
    keep_better_start(fits, search.place_at_steps(start, step_asperities), sigma);

  if (layout_.coloured_noise) {
    // The noise's spectrum from the residual of the count the white model prefers, then every
    // order in the whitened space it gives (those near the count refitted).
    const CountPosterior white = count_posterior(fits, sigma, prior_, density_, layout_, loads_);
    FitState chosen = fits[white.best].state;
    const std::vector<double> r = fit.residual(chosen);
    out.spectrum = fit_noise_spectrum(r);
    const Whitener whitener = whitener_of(out.spectrum, samples);
    sigma = whitened_level(whitener);
    fit.set_noise(whitener, sigma);
    const std::size_t first = std::max(white.best > 0 ? white.best - 1 : 0, static_cast<std::size_t>(prior_.count_min));
    for (std::size_t n = 0; n < first && n < fits.size(); ++n) fits[n].residual_v2 = fit.whitened_rss(fits[n].state);
    search.refit(fits, first);
  }
  // Every order the posterior weighs needs its Laplace determinant: without it an order's
  // evidence keeps its parameters' prior densities (an onset's, per second, is ~1e5 for a
  // range of 10 us) with nothing to balance them, and the greedy path's orders, fitted without
  // one, won on pure noise. J^T J at the greedy fit (no further iterations) is enough: those
  // orders are not the best, so only the size of their Occam factor matters.
  for (std::size_t n = std::max<std::size_t>(1, prior_.count_min); n < fits.size() && n <= prior_.count_max; ++n) {
    const std::size_t parameters = n * layout_.per_atom() + layout_.shared();
    if (fits[n].normal_matrix.rows() != static_cast<Eigen::Index>(parameters))
      fits[n] = fit.refine(fits[n].state, {}, true, true, 0);
  }
  // Backward elimination: the greedy path can leave an atom of the right k with the wrong load
  // or onset (a local minimum no local fit leaves) and then add weak atoms that patch its
  // misfit, each of which the evidence rewards. With the others in place the patch's atoms are
  // the weakest: from the best order down, its weakest atom is removed and the rest refitted
  // in full from there; that fit replaces the order below when it fits better, and the descent
  // goes on from it, until one does not. On a record whose count is right, one refit that
  // changes nothing.
  {
    const double sigma2 = sigma * sigma;
    const std::vector<double> zeros(samples, 0.0);
    for (std::size_t n = count_posterior(fits, sigma, prior_, density_, layout_, loads_).best; n > 0 && n - 1 >= prior_.count_min;
         --n) {
      const FitState& state = fits[n].state;
      std::size_t weakest = 0;
      double weakest_energy = INFINITY;
      for (std::size_t i = 0; i < state.atoms.size(); ++i) {
        const double energy = proposals_.score(state.atoms[i], zeros, state.amplitude, state.damping_rate_per_s).energy_v2;
        if (energy < weakest_energy) weakest_energy = energy, weakest = i;
      }
      FitState without_weakest = state;
      without_weakest.atoms.erase(without_weakest.atoms.begin() + static_cast<std::ptrdiff_t>(weakest));
      OrderFit pruned = fit.refine(without_weakest, {}, true, true, options_.max_iterations);
      const OrderFit& below = fits[n - 1];
      if (!(pruned.residual_v2 / sigma2 + pruned.penalty < below.residual_v2 / sigma2 + below.penalty)) break;
      fits[n - 1] = std::move(pruned);
    }
  }
  for (const OrderFit& f : fits) out.fit_residual_v2.push_back(f.residual_v2);
  out.sigma_v = sigma;
  out.posterior = count_posterior(fits, sigma, prior_, density_, layout_, loads_);
  if (out.posterior.counts.empty()) throw Error("RecordEstimator: no fit within the prior's count range (the search stopped early)");
  out.count = out.posterior.best;
  double reference_seconds = 0.0;  // not the estimate's: taken out of its CPU time
  if (reference) {
    timespec reference_start{}, reference_end{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &reference_start);
    // Far more steps than the search allows: from the truth the refinement has no local
    // minimum to escape, but the shared parameters it frees (damping, load factor; amplitude
    // and offset solved) can take a long walk to a device's own values.
    constexpr std::size_t REFERENCE_ITERATIONS = 300;
    const double scale = sigma * sigma * static_cast<double>(samples);
    const std::size_t n = reference->atoms.size();
    const OrderFit unrefined = fit.refine(*reference, {}, true, false, 0);
    const OrderFit refined = fit.refine(*reference, {}, true, false, REFERENCE_ITERATIONS);
    ReferenceFit& r = out.reference.emplace();
    r.start_misfit = unrefined.residual_v2 / scale;
    r.misfit = refined.residual_v2 / scale;
    r.penalty = refined.penalty;
    r.iterations = refined.iterations;
    if (n < fits.size()) r.found_misfit = fits[n].residual_v2 / scale, r.found_penalty = fits[n].penalty;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &reference_end);
    reference_seconds = static_cast<double>(reference_end.tv_sec - reference_start.tv_sec) +
                        1e-9 * static_cast<double>(reference_end.tv_nsec - reference_start.tv_nsec);
  }
  const std::size_t parameters = out.count * layout_.per_atom() + (out.count > 0 ? layout_.shared() : 0);
  const OrderFit best = fits[out.count].normal_matrix.rows() == static_cast<Eigen::Index>(parameters) || out.count == 0
                            ? fits[out.count]
                            : fit.refine(fits[out.count].state, {}, true, true, options_.max_iterations);
  out.state = best.state;
  out.residual_sigma_v = std::sqrt(best.residual_v2 / static_cast<double>(samples - std::min(samples - 1, parameters)));
  if (out.count + 1 < fits.size() && out.count == prior_.count_max) {
    const double gain = best.residual_v2 - fits[out.count + 1].residual_v2;
    const LineCandidate extra = proposals_.score(fits[out.count + 1].state.atoms.back(), std::vector<double>(samples, 0.0),
                                                 best.state.amplitude, best.state.damping_rate_per_s);
    out.more_than_prior_allows = gain > 0.5 * extra.energy_v2;
  }

  // Lines and their standard errors: H^-1 with H as in the evidence (J^T J / sigma^2 plus the
  // prior's curvatures, so a coincident pair gets a wide but finite error).
  Eigen::MatrixXd covariance, curvature;
  if (out.count > 0) {
    curvature = best.normal_matrix / (sigma * sigma);
    curvature.diagonal() += prior_curvatures(out.count, prior_, layout_, loads_);
    covariance = curvature.inverse();
    // Said here, not by a writer refusing a NaN later.
    if (!covariance.allFinite())
      throw ModelError("the fit of " + std::to_string(out.count) + " atoms to the record is not finite (its parameters or "
                       "their errors): the record does not determine them; the known device is likely outside the "
                       "regime the atoms model (a belt-carried stick, then a free oscillation)");
  }
  const KnownDevice& device = atoms_->device();
  const AtomModel& model = atoms_->model();
  const std::size_t per_atom = layout_.per_atom();
  const double d = best.state.damping_rate_per_s;
  std::vector<double> k_values;
  for (std::size_t i = 0; i < out.count; ++i) {
    const AtomParameters& a = best.state.atoms[i];
    EstimatedLine line;
    const auto base = static_cast<Eigen::Index>(i * per_atom);
    line.stiffness_n_per_m = a.stiffness_n_per_m;
    line.log_stiffness_se = std::sqrt(std::max(0.0, covariance(base, base)));
    line.se_inflation = se_inflation(curvature, base, per_atom, layout_.shared(), covariance(base, base));
    line.frequency_hz = model.tail_angular_frequency(a, d) / (2.0 * PI);
    line.amplitude_v = best.state.amplitude * model_.volts_per_unit() * std::min(1.0, model.carried_phase(a));
    line.load_n = a.load_n;
    Eigen::Index next = base + 1;
    if (layout_.load_per_atom) line.log_load_se = std::sqrt(std::max(0.0, covariance(next, next))), ++next;
    else if (layout_.load_shared) {
      const auto shared = static_cast<Eigen::Index>(out.count * per_atom + (layout_.damping_free ? 1 : 0));
      line.log_load_se = std::sqrt(std::max(0.0, covariance(shared, shared)));
    }
    line.onset_s = a.onset_s;
    if (layout_.onset_free) line.onset_se_s = std::sqrt(std::max(0.0, covariance(next, next)));
    line.breakaway_s = model.breakaway_time(a, d);
    if (line.stiffness_n_per_m < support_low_ || line.stiffness_n_per_m > support_high_) ++out.lines_outside_prior;
    out.lines.push_back(line);
    k_values.push_back(a.stiffness_n_per_m);
  }
  for (std::size_t i = 0; i < out.lines.size(); ++i) {
    double nearest = INFINITY;
    if (i > 0) nearest = std::min(nearest, out.lines[i].frequency_hz - out.lines[i - 1].frequency_hz);
    if (i + 1 < out.lines.size()) nearest = std::min(nearest, out.lines[i + 1].frequency_hz - out.lines[i].frequency_hz);
    out.lines[i].nearest_separation_hz = std::isfinite(nearest) ? nearest : 0.0;
  }
  (void)device;

  // The realised population.
  out.median_stiffness_n_per_m = sample_median(k_values);
  out.sd_log_stiffness = sample_sd_log(k_values);

  // Checks for the verdict: what the residual says, and how strong the record was.
  out.checks = residual_checks(fit, best.state);
  {
    FitState state = best.state;
    const std::vector<double> r = fit.residual(state);
    out.in_band_power_ratio = layout_.coloured_noise ? out.checks.line_band : noise_.band_power_ratio(r, band_low_hz_, band_high_hz_);
  }
  std::vector<double> model_v(samples);
  model_.voltage(best.state, model_v);
  double model_mean = 0.0, model_var = 0.0;
  for (double v : model_v) model_mean += v / static_cast<double>(samples);
  for (double v : model_v) model_var += (v - model_mean) * (v - model_mean) / static_cast<double>(samples);
  const double noise_var = layout_.coloured_noise ? out.spectrum.variance(samples) : white2;
  out.signal_to_noise_db = noise_var > 0.0 && model_var > 0.0 ? 10.0 * std::log10(model_var / noise_var) : 0.0;
  timespec cpu_end{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &cpu_end);
  out.seconds = static_cast<double>(cpu_end.tv_sec - cpu_start.tv_sec) + 1e-9 * static_cast<double>(cpu_end.tv_nsec - cpu_start.tv_nsec) -
                reference_seconds;
  return out;
}

}  // namespace stengmc
