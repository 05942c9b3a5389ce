#include "inverse/calibration_maps.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "core/error.hpp"
#include "inverse/naive_count.hpp"

namespace stengmc {

namespace {

constexpr long JEFFREYS_OFFSETS = 3;          // offsets n - n-hat given the prior's 1/2
constexpr double JEFFREYS = 0.5;
constexpr std::size_t CONFUSION_RECORDS = 60;  // pooled until this many
// Scale floor (relative, in ln k): only guards against a zero standard error. The scores are
// calibrated whatever the scale, but a floor above the errors themselves (a first choice of
// 1e-4, the model's accuracy) undid the normalisation at high SNR, where the lines' errors
// are ~1e-6: coverage 0.99 at 30-40 dB and 0.79 at 20-30 dB on the validation.
constexpr double SCALE_FLOOR = 1e-12;
constexpr double Z90 = 1.6448536269514722;

//! The split-conformal quantile: the ceil(level (N + 1))-th smallest score (the largest when
//! that exceeds N).
double conformal_quantile(std::vector<double> scores, double level) {
  if (scores.empty()) return 0.0;
  std::sort(scores.begin(), scores.end());
  const auto rank = static_cast<std::size_t>(std::ceil(level * static_cast<double>(scores.size() + 1)));
  return scores[std::min(rank, scores.size()) - 1];
}

//! Indices of samples whose n-hat lies within the smallest window around m holding `least`
//! samples that `keep` accepts (or all of them).
using Samples = std::vector<const CalibrationSample*>;

//! The samples whose n-hat lies within the smallest window around m holding `least` of them
//! (or all of them).
Samples neighbourhood(const Samples& samples, std::size_t m, std::size_t least) {
  Samples out;
  for (std::size_t w = 0; w <= 64; ++w) {
    out.clear();
    for (const CalibrationSample* s : samples)
      if (s->count + w >= m && s->count <= m + w) out.push_back(s);
    if (out.size() >= least) break;
  }
  return out;
}

//! The maps of one class, learnt from `samples` (valid ones).
ClassMaps fit_class_maps(const Samples& samples, const InversePrior& prior) {
  ClassMaps maps;
  maps.records = samples.size();
  const std::size_t counts = prior.count_max - prior.count_min + 1;
  const long max_offset = static_cast<long>(counts);

  // Count confusion.
  maps.confusion.assign(counts, std::vector<double>(counts, 0.0));
  for (std::size_t mi = 0; mi < counts; ++mi) {
    const std::size_t m = prior.count_min + mi;
    std::vector<double> offsets(2 * static_cast<std::size_t>(max_offset) + 1, 0.0);
    for (long d = -JEFFREYS_OFFSETS; d <= JEFFREYS_OFFSETS; ++d) offsets[static_cast<std::size_t>(d + max_offset)] = JEFFREYS;
    for (const CalibrationSample* s : neighbourhood(samples, m, CONFUSION_RECORDS)) {
      const long d = std::clamp(static_cast<long>(s->true_count()) - static_cast<long>(s->count), -max_offset, max_offset);
      offsets[static_cast<std::size_t>(d + max_offset)] += 1.0;
    }
    double total = 0.0;
    for (long d = -max_offset; d <= max_offset; ++d) {
      const long n = static_cast<long>(m) + d;
      if (n < static_cast<long>(prior.count_min) || n > static_cast<long>(prior.count_max)) continue;
      maps.confusion[mi][static_cast<std::size_t>(n) - prior.count_min] = offsets[static_cast<std::size_t>(d + max_offset)];
      total += offsets[static_cast<std::size_t>(d + max_offset)];
    }
    for (double& p : maps.confusion[mi]) p /= total;
  }

  // Population intervals: normalised scores, Mondrian by bins of n-hat.
  const std::size_t bins = (counts + POPULATION_BIN_COUNTS - 1) / POPULATION_BIN_COUNTS;
  maps.median_score_quantile.assign(bins, 0.0);
  maps.sd_score_quantile.assign(bins, 0.0);
  for (std::size_t b = 0; b < bins; ++b) {
    const std::size_t first = prior.count_min + b * POPULATION_BIN_COUNTS, last = first + POPULATION_BIN_COUNTS - 1;
    std::vector<double> median_scores, sd_scores, all_median, all_sd;
    for (const CalibrationSample* s : samples) {
      // The population needs lines on both sides: nothing slides in the record, or nothing was found.
      if (s->count == 0 || s->true_count() == 0) continue;
      const bool in_bin = s->count >= first && s->count <= last;
      const double m = std::abs(std::log(s->median / s->true_median())) / median_log_scale(s->stiffness, s->log_stiffness_se);
      all_median.push_back(m);
      if (in_bin) median_scores.push_back(m);
      if (s->count >= 2 && s->true_count() >= 2) {
        const double d = std::abs(s->sd_log - s->true_sd_log()) / sd_log_scale(s->stiffness, s->log_stiffness_se);
        all_sd.push_back(d);
        if (in_bin) sd_scores.push_back(d);
      }
    }
    constexpr std::size_t FEWEST = 20;
    maps.median_score_quantile[b] = conformal_quantile(median_scores.size() >= FEWEST ? median_scores : all_median, INTERVAL_LEVEL);
    maps.sd_score_quantile[b] = conformal_quantile(sd_scores.size() >= FEWEST ? sd_scores : all_sd, INTERVAL_LEVEL);
  }

  // Line errors: records counted exactly, lines paired in order (the optimal matching for
  // a convex cost in one dimension).
  std::vector<double> z;
  for (const CalibrationSample* s : samples) {
    if (s->count != s->true_count()) continue;
    std::vector<double> truth = s->true_stiffness;
    std::sort(truth.begin(), truth.end());
    for (std::size_t i = 0; i < s->count; ++i)
      if (s->log_stiffness_se[i] > 0.0) z.push_back(std::abs(std::log(s->stiffness[i] / truth[i])) / s->log_stiffness_se[i]);
  }
  if (!z.empty()) maps.line_error_scale = conformal_quantile(z, INTERVAL_LEVEL) / Z90;
  return maps;
}

//! The ceil(q N)-th smallest of `values`, at least `floor` (`floor` when there are none): a
//! fit class boundary that a share q of the bank's right answers stay within.
double quantile_at_least(std::vector<double> values, double q, double floor) {
  if (values.empty()) return floor;
  std::sort(values.begin(), values.end());
  const auto rank = static_cast<std::size_t>(std::ceil(q * static_cast<double>(values.size())));
  return std::max(floor, values[std::clamp<std::size_t>(rank, 1, values.size()) - 1]);
}

//! The fit classes' boundary: MISFIT_QUANTILE of noise_misfit over the records counted right
//! below the prior's largest count, at least DEFAULT_MISFIT_RATIO. A count at the prior's top
//! can be right because the prior stops there: a fit the atoms cannot make adds atoms up to
//! that limit whatever the truth (in the broadened test bank, 30 of the 38 right counts at the
//! top misfit), so those records say nothing of how well right answers fit.
double misfit_boundary(const Samples& samples, std::size_t count_max) {
  std::vector<double> right;
  for (const CalibrationSample* s : samples)
    if (s->count == s->true_count() && s->count < count_max) right.push_back(noise_misfit(s->residual_sigma_v, s->noise_sigma_v));
  return quantile_at_least(std::move(right), MISFIT_QUANTILE, DEFAULT_MISFIT_RATIO);
}

//! The bound on the worst line's error: LINE_SE_QUANTILE of worst_line_se over the records
//! counted right below the prior's largest count whose residual fits (the others are warned
//! about already), at least DEFAULT_LINE_SE_BOUND.
double line_se_boundary(const Samples& samples, std::size_t count_max, double misfit_ratio) {
  std::vector<double> right;
  for (const CalibrationSample* s : samples)
    if (s->count == s->true_count() && s->count < count_max && noise_misfit(s->residual_sigma_v, s->noise_sigma_v) <= misfit_ratio)
      right.push_back(worst_line_se(s->stiffness, s->log_stiffness_se));
  return quantile_at_least(std::move(right), LINE_SE_QUANTILE, DEFAULT_LINE_SE_BOUND);
}

}  // namespace

double worst_line_se(const std::vector<double>& stiffness, const std::vector<double>& log_stiffness_se) {
  double worst = 0.0;
  for (std::size_t i = 0; i < stiffness.size(); ++i) {
    const double se = log_stiffness_se[i];
    bool apart = true;
    for (std::size_t j = 0; j < stiffness.size() && apart; ++j)
      apart = j == i || !(std::abs(std::log(stiffness[i] / stiffness[j])) <= se);
    if (apart) worst = std::max(worst, se);
  }
  return worst;
}

double median_log_scale(std::vector<double> k, std::vector<double> se) {
  const std::size_t n = k.size();
  if (n == 0) return SCALE_FLOOR;
  std::vector<std::size_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return k[a] < k[b]; });
  const double s = n % 2 ? se[order[n / 2]] : 0.5 * std::hypot(se[order[n / 2 - 1]], se[order[n / 2]]);
  return std::max(SCALE_FLOOR, s);
}

double sd_log_scale(const std::vector<double>& k, const std::vector<double>& se) {
  const std::size_t n = k.size();
  if (n < 2) return 0.0;
  double mean = 0.0;
  for (double x : k) mean += std::log(x) / static_cast<double>(n);
  double var = 0.0;
  for (double x : k) var += (std::log(x) - mean) * (std::log(x) - mean) / static_cast<double>(n - 1);
  const double sd = std::sqrt(var);
  if (!(sd > 0.0)) return SCALE_FLOOR;
  // d sd / d ln k_i = (ln k_i - mean) / ((n - 1) sd)
  double sum = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double g = (std::log(k[i]) - mean) / (static_cast<double>(n - 1) * sd);
    sum += g * g * se[i] * se[i];
  }
  return std::max(SCALE_FLOOR, std::sqrt(sum));
}

double noise_misfit(double residual_sigma_v, double noise_sigma_v) {
  return noise_sigma_v > 0.0 && std::isfinite(residual_sigma_v) ? residual_sigma_v / noise_sigma_v : 1.0;
}

CalibrationMaps fit_calibration_maps(const std::vector<CalibrationSample>& samples, const InversePrior& prior) {
  CalibrationMaps maps;
  maps.count_min = prior.count_min;
  maps.count_max = prior.count_max;
  Samples valid;
  for (const CalibrationSample& s : samples)
    if (s.valid) valid.push_back(&s);
  maps.records = valid.size();
  if (maps.records == 0) throw Error("calibration: no valid record to fit the maps on");

  // The fit classes; a class with too few records of its own for a confusion is learnt from
  // all of them (on the ideal device nearly every record fits).
  maps.misfit_ratio = misfit_boundary(valid, prior.count_max);
  maps.line_se_bound = line_se_boundary(valid, prior.count_max, maps.misfit_ratio);
  std::array<Samples, FIT_CLASSES> by_class;
  for (const CalibrationSample* s : valid) {
    const FitClass c = maps.fit_class(noise_misfit(s->residual_sigma_v, s->noise_sigma_v), worst_line_se(s->stiffness, s->log_stiffness_se));
    by_class[static_cast<std::size_t>(c)].push_back(s);
  }
  for (std::size_t c = 0; c < FIT_CLASSES; ++c) {
    const bool pooled = by_class[c].size() < CONFUSION_RECORDS;
    maps.classes[c] = fit_class_maps(pooled ? valid : by_class[c], prior);
    maps.classes[c].records = by_class[c].size();
    maps.classes[c].pooled = pooled;
  }

  // The naive count's best threshold, and the bank's own figures.
  const std::size_t thresholds = samples.front().naive_counts.size();
  double best = INFINITY;
  for (std::size_t t = 0; t < thresholds; ++t) {
    double se = 0.0;
    std::size_t n = 0;
    for (const CalibrationSample& s : samples)
      if (s.valid && t < s.naive_counts.size()) {
        const double e = s.naive_counts[t] - static_cast<double>(s.true_count());
        se += e * e;
        ++n;
      }
    if (n > 0 && se / static_cast<double>(n) < best) best = se / static_cast<double>(n), maps.naive_threshold_index = t;
  }
  maps.naive_threshold = naive_count_thresholds()[std::min(maps.naive_threshold_index, naive_count_thresholds().size() - 1)];
  double se = 0.0, exact = 0.0, naive_exact = 0.0;
  for (const CalibrationSample& s : samples) {
    if (!s.valid) continue;
    const double e = static_cast<double>(s.count) - static_cast<double>(s.true_count());
    se += e * e;
    exact += e == 0.0;
    if (maps.naive_threshold_index < s.naive_counts.size())
      naive_exact += s.naive_counts[maps.naive_threshold_index] == static_cast<double>(s.true_count());
  }
  const double n = static_cast<double>(maps.records);
  maps.bank_count_rmse = std::sqrt(se / n);
  maps.bank_exact_rate = exact / n;
  maps.bank_naive_rmse = std::sqrt(best);
  maps.bank_naive_exact_rate = naive_exact / n;
  return maps;
}

CalibratedEstimate calibrate_estimate(const RecordEstimate& e, const CalibrationMaps* maps, const InversePrior& prior) {
  CalibratedEstimate out;
  out.calibrated = maps != nullptr;
  out.misfit = noise_misfit(e.residual_sigma_v, e.noise.sigma_v);
  std::vector<double> line_k, line_se;
  for (const EstimatedLine& line : e.lines) line_k.push_back(line.stiffness_n_per_m), line_se.push_back(line.log_stiffness_se);
  out.worst_line_se = worst_line_se(line_k, line_se);
  out.fit_class = maps ? maps->fit_class(out.misfit, out.worst_line_se)
                       : fit_class_of(out.misfit, out.worst_line_se, DEFAULT_MISFIT_RATIO, DEFAULT_LINE_SE_BOUND);
  const ClassMaps* own = maps ? &maps->of(out.fit_class) : nullptr;
  const std::size_t counts = prior.count_max - prior.count_min + 1;
  for (std::size_t i = 0; i < counts; ++i) out.counts.push_back(prior.count_min + i);
  out.probability.assign(counts, 0.0);
  for (std::size_t j = 0; j < e.posterior.counts.size(); ++j) {
    const std::size_t m = e.posterior.counts[j];
    if (m < prior.count_min || m > prior.count_max) continue;
    const double p = e.posterior.probability[j];
    if (!maps) {
      out.probability[m - prior.count_min] += p;
      continue;
    }
    for (std::size_t i = 0; i < counts; ++i) out.probability[i] += p * own->confusion[m - prior.count_min][i];
  }
  std::size_t mode = 0;
  for (std::size_t i = 1; i < counts; ++i)
    if (out.probability[i] > out.probability[mode]) mode = i;
  out.count = out.counts[mode];
  // Shortest run around the mode holding >= 0.9: grow towards the more probable side.
  std::size_t lo = mode, hi = mode;
  double mass = out.probability[mode];
  while (mass < INTERVAL_LEVEL - 1e-12 && (lo > 0 || hi + 1 < counts)) {
    const double left = lo > 0 ? out.probability[lo - 1] : -1.0;
    const double right = hi + 1 < counts ? out.probability[hi + 1] : -1.0;
    if (left >= right) mass += out.probability[--lo];
    else mass += out.probability[++hi];
  }
  out.interval_low = out.counts[lo];
  out.interval_high = out.counts[hi];

  out.median = e.median_stiffness_n_per_m;
  out.sd_log = e.sd_log_stiffness;
  out.sd_known = e.count >= 2;
  const double scale = own ? own->line_error_scale : 1.0;
  for (const EstimatedLine& line : e.lines) {
    out.line_low.push_back(line.stiffness_n_per_m * std::exp(-Z90 * scale * line.log_stiffness_se));
    out.line_high.push_back(line.stiffness_n_per_m * std::exp(Z90 * scale * line.log_stiffness_se));
  }
  if (maps && e.count >= prior.count_min && e.count <= prior.count_max) {
    const std::size_t bin = (e.count - prior.count_min) / POPULATION_BIN_COUNTS;
    std::vector<double> k, se;
    for (const EstimatedLine& line : e.lines) k.push_back(line.stiffness_n_per_m), se.push_back(line.log_stiffness_se);
    // A bank record whose estimate claimed a tiny error and missed makes a huge score, and a
    // small bank's conformal quantile may be that score: the interval is then as wide as the
    // prior allows, not wider (it had overflowed to infinity). The realised median lies within
    // the prior's support of k, and the sd (n - 1 denominator) of any n >= 2 values of ln k
    // within it is at most half its width x sqrt(2) (n = 2, one at each end); in logs, so that
    // no bound overflows.
    const auto [k_low, k_high] = prior.support();
    const double h = own->median_score_quantile[bin] * median_log_scale(k, se);
    if (out.median > 0.0) {
      const double ln_median = std::log(out.median);
      out.median_low = std::exp(std::min(ln_median, std::max(ln_median - h, std::log(k_low))));
      out.median_high = std::exp(std::max(ln_median, std::min(ln_median + h, std::log(k_high))));
    } else {
      out.median_low = out.median_high = out.median;
    }
    const double hs = own->sd_score_quantile[bin] * sd_log_scale(k, se);
    const double widest_sd = 0.5 * std::log(k_high / k_low) * std::sqrt(2.0);
    out.sd_log_low = std::max(0.0, out.sd_log - hs);
    out.sd_log_high = std::max(out.sd_log, std::min(out.sd_log + hs, widest_sd));
    out.population_intervals = true;
  } else {
    out.median_low = out.median_high = out.median;
    out.sd_log_low = out.sd_log_high = out.sd_log;
  }
  return out;
}

}  // namespace stengmc
