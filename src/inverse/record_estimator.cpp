#include "inverse/record_estimator.hpp"

#include <algorithm>
#include <ctime>
#include <cmath>

#include "core/constants.hpp"
#include "core/error.hpp"
#include "inverse/sample_statistics.hpp"

namespace stengmc {

namespace {

// The noise band starts this far above the prior's highest plausible line (its 1 - 1e-4
// quantile): a line's Lorentzian skirt, d / pi wide, is far below the noise there.
constexpr double NOISE_BAND_MARGIN = 1.25;

}  // namespace

RecordEstimator::RecordEstimator(const AtomTable& atoms, const InversePrior& prior, const LineSearchOptions& options)
    : atoms_(&atoms),
      prior_(prior),
      density_(prior),
      model_(atoms),
      proposals_(atoms),
      options_(options),
      noise_(atoms.grid().samples, atoms.grid().sample_rate_hz(),
             NOISE_BAND_MARGIN * atoms.device().angular_frequency(prior.support().second) / (2.0 * PI)) {
  const auto [low, high] = prior.support();
  support_low_ = low;
  support_high_ = high;
  band_low_hz_ = atoms.device().angular_frequency(low) / (2.0 * PI);
  band_high_hz_ = atoms.device().angular_frequency(high) / (2.0 * PI);
}

RecordEstimate RecordEstimator::estimate(std::span<const double> voltage) {
  // CPU time of this thread: wall time would count whatever else the machine runs.
  timespec cpu_start{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &cpu_start);
  const std::size_t samples = atoms_->grid().samples;
  if (voltage.size() != samples) throw Error("RecordEstimator: the record has another length than the atom table's grid");
  RecordEstimate out;
  out.noise = noise_.estimate(voltage);

  LineSearch search(model_, proposals_, voltage, options_);
  const std::vector<OrderFit> fits = search.search(prior_.count_max + 1, prior_.count_min);
  for (const OrderFit& f : fits) out.fit_residual_v2.push_back(f.residual_v2);

  // Noise for the evidence: the band's, else the residual of the largest fit; plus the model's
  // own accuracy as a floor.
  double mean_square = 0.0;
  for (double v : voltage) mean_square += v * v / static_cast<double>(samples);
  double sigma2 = out.noise.bins > 0 ? out.noise.sigma_v * out.noise.sigma_v
                                     : fits.back().residual_v2 / static_cast<double>(samples - (fits.size() - 1));
  sigma2 += MODEL_RELATIVE_ACCURACY * MODEL_RELATIVE_ACCURACY * mean_square;
  // A record far below the device's amplitude (one scaled by 1e-200) squares to 0.
  const double floor_v = MIN_RELATIVE_NOISE * atoms_->device().voltage_scale_v();
  sigma2 = std::max(sigma2, floor_v * floor_v);
  out.sigma_v = std::sqrt(sigma2);
  out.posterior = count_posterior(fits, out.sigma_v, prior_, density_);
  if (out.posterior.counts.empty())
    throw Error("RecordEstimator: no fit within the prior's count range (the search stopped early)");
  out.count = out.posterior.best;
  // The chosen order is normally among those refitted in full; if not, refit it now.
  const OrderFit best = fits[out.count].normal_matrix.rows() == static_cast<Eigen::Index>(out.count)
                            ? fits[out.count]
                            : search.refine(fits[out.count].stiffness_n_per_m);
  out.residual_sigma_v = std::sqrt(best.residual_v2 / static_cast<double>(samples - out.count));
  if (out.count + 1 < fits.size() && out.count == prior_.count_max) {
    const double gain = best.residual_v2 - fits[out.count + 1].residual_v2;
    out.more_than_prior_allows = gain > 0.5 * proposals_.atom_energy(fits[out.count + 1].stiffness_n_per_m.back());
  }

  // Lines and their standard errors: H^-1 with H as in the evidence (J^T J / sigma^2 plus the
  // prior's curvature, so a coincident pair gets a wide but finite error).
  const auto [low, high] = prior_.support(1e-3);
  const double spread = std::max(0.05, std::log(high / low) / 6.0);
  Eigen::MatrixXd h = best.normal_matrix / sigma2;
  h.diagonal().array() += 1.0 / (spread * spread);
  const Eigen::MatrixXd covariance = out.count > 0 ? Eigen::MatrixXd(h.inverse()) : Eigen::MatrixXd();
  // Said here, not by a writer refusing a NaN later: a fit whose atoms change ~1e16 times
  // more with ln k than the noise resolves leaves H singular to rounding.
  if (!covariance.allFinite() || !std::all_of(best.stiffness_n_per_m.begin(), best.stiffness_n_per_m.end(),
                                              [](double k) { return std::isfinite(k); }))
    throw ModelError("the fit of " + std::to_string(out.count) + " atoms to the record is not finite (its stiffnesses or "
                     "their errors): the record does not determine them; the known device is likely outside the "
                     "regime the atoms model (a belt-carried stick, then a free oscillation)");
  const KnownDevice& device = atoms_->device();
  for (std::size_t i = 0; i < out.count; ++i) {
    EstimatedLine line;
    line.stiffness_n_per_m = best.stiffness_n_per_m[i];
    line.log_stiffness_se = std::sqrt(std::max(0.0, covariance(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(i))));
    line.frequency_hz = device.angular_frequency(line.stiffness_n_per_m) / (2.0 * PI);
    line.amplitude_v = device.voltage_scale_v();
    if (line.stiffness_n_per_m < support_low_ || line.stiffness_n_per_m > support_high_) ++out.lines_outside_prior;
    out.lines.push_back(line);
  }
  for (std::size_t i = 0; i < out.lines.size(); ++i) {
    double nearest = INFINITY;
    if (i > 0) nearest = std::min(nearest, out.lines[i].frequency_hz - out.lines[i - 1].frequency_hz);
    if (i + 1 < out.lines.size()) nearest = std::min(nearest, out.lines[i + 1].frequency_hz - out.lines[i].frequency_hz);
    out.lines[i].nearest_separation_hz = std::isfinite(nearest) ? nearest : 0.0;
  }

  // The realised population.
  out.median_stiffness_n_per_m = sample_median(best.stiffness_n_per_m);
  out.sd_log_stiffness = sample_sd_log(best.stiffness_n_per_m);

  // Checks for the verdict: is what is left white, and how strong was the record.
  const std::vector<double> r = search.residual(best.stiffness_n_per_m);
  out.in_band_power_ratio = noise_.band_power_ratio(r, band_low_hz_, band_high_hz_);
  std::vector<double> model(samples);
  model_.evaluate(best.stiffness_n_per_m, model);
  double mean = 0.0, var = 0.0;
  for (double v : model) mean += v / static_cast<double>(samples);
  for (double v : model) var += (v - mean) * (v - mean) / static_cast<double>(samples);
  const double noise_var = out.noise.bins > 0 ? out.noise.sigma_v * out.noise.sigma_v : out.residual_sigma_v * out.residual_sigma_v;
  out.signal_to_noise_db = noise_var > 0.0 && var > 0.0 ? 10.0 * std::log10(var / noise_var) : 0.0;
  timespec cpu_end{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &cpu_end);
  out.seconds = static_cast<double>(cpu_end.tv_sec - cpu_start.tv_sec) + 1e-9 * static_cast<double>(cpu_end.tv_nsec - cpu_start.tv_nsec);
  return out;
}

}  // namespace stengmc
