#include "ensemble/ensemble_summary.hpp"

#include <cstdio>

#include "core/random_stream.hpp"

namespace stengmc {

namespace {

// Bootstrap sub-streams: one per scalar (its index), then the pooled ratios.
constexpr std::uint64_t FFT_POOLED_STREAM = 1000;
constexpr std::uint64_t HR_POOLED_STREAM = 1001;

Interval pooled_ratio(const std::vector<RealisationRecord>& records, Scalar numerator, std::uint64_t seed,
                      std::uint64_t stream) {
  std::vector<double> num, den;
  for (const RealisationRecord& r : records)
    if (r.valid) {
      num.push_back(r.scalar(numerator));
      den.push_back(r.scalar(Scalar::n_sliding));
    }
  double total = 0.0;
  for (double d : den) total += d;
  if (num.empty() || total <= 0.0) return {};
  RandomEngine engine = random_stream(seed, 0, StreamKind::bootstrap, stream);
  return ratio_of_sums_interval(num, den, engine);
}

}  // namespace

EnsembleSummary summarise_ensemble(const std::vector<RealisationRecord>& records, std::uint64_t seed) {
  EnsembleSummary s;
  s.realisations = records.size();
  for (const RealisationRecord& r : records) {
    if (r.valid) ++s.valid;
    else s.invalid.emplace_back(r.realisation, r.failure);
  }
  s.valid_fraction = proportion_interval(s.valid, s.realisations);
  for (std::size_t k = 0; k < SCALAR_COUNT; ++k) {
    std::vector<double> values;
    for (const RealisationRecord& r : records)
      if (r.valid) values.push_back(r.scalars[k]);
    RandomEngine engine = random_stream(seed, 0, StreamKind::bootstrap, k);
    s.scalars[k] = summarise(values, engine);
  }
  s.fft_pooled_ratio = pooled_ratio(records, Scalar::fft_identifiable, seed, FFT_POOLED_STREAM);
  s.hr_pooled_ratio = pooled_ratio(records, Scalar::hr_identifiable, seed, HR_POOLED_STREAM);
  return s;
}

std::string format_ensemble_summary(const EnsembleSummary& s, const EnsembleRun& run) {
  std::string out;
  char line[320];
  const std::string resumed =
      run.resumed > 0 ? " (" + std::to_string(run.resumed) + " resumed from an interrupted run)" : std::string();
  std::snprintf(line, sizeof line, "%zu realisations%s, %zu valid; %.1f s on %d thread%s%s\n", s.realisations,
                resumed.c_str(), s.valid, run.seconds, run.threads, run.threads == 1 ? "" : "s",
                run.stopped_at_target ? "; stopped: target half-width reached" : "");
  out += line;
  std::snprintf(line, sizeof line, "  %-22s %6s  %-34s %-11s %-34s %-11s %-11s\n", "statistic", "n", "mean [95 % CI]", "std",
                "median [95 % CI]", "5 %", "95 %");
  out += line;
  if (s.valid == 0) out += "  no valid realisation: no statistics\n";
  std::string all_zero;
  for (std::size_t k = 0; k < SCALAR_COUNT; ++k) {
    const ScalarSummary& v = s.scalars[k];
    if (v.count == 0) continue;
    if (v.min == 0.0 && v.max == 0.0) {  // e.g. ESPRIT counts without ESPRIT: one line for all
      all_zero += (all_zero.empty() ? "" : ", ") + std::string(scalar_info(static_cast<Scalar>(k)).name);
      continue;
    }
    char mean[64], median[64];
    std::snprintf(mean, sizeof mean, "%.4g [%.4g, %.4g]%s", v.mean.estimate, v.mean.low, v.mean.high, v.mean.known ? "" : " ?");
    std::snprintf(median, sizeof median, "%.4g [%.4g, %.4g]%s", v.median.estimate, v.median.low, v.median.high,
                  v.median.known ? "" : " ?");
    std::snprintf(line, sizeof line, "  %-22s %6zu  %-34s %-11.4g %-34s %-11.4g %-11.4g\n",
                  std::string(scalar_info(static_cast<Scalar>(k)).name).c_str(), v.count, mean,
                  v.standard_deviation.estimate, median, v.p05.estimate, v.p95.estimate);
    out += line;
  }
  auto ratio_line = [&](const char* name, const Interval& i) {
    if (!i.known || i.estimate == 0.0) return;
    std::snprintf(line, sizeof line, "  %-22s %.4g [%.4g, %.4g]  (sum identifiable / sum sliding, paired bootstrap)\n", name,
                  i.estimate, i.low, i.high);
    out += line;
  };
  if (!all_zero.empty()) out += "  zero in every valid realisation: " + all_zero + "\n";
  ratio_line("FFT pooled ratio", s.fft_pooled_ratio);
  ratio_line("ESPRIT pooled ratio", s.hr_pooled_ratio);
  out += "  \"?\": too few values for a trustworthy interval\n";
  if (!s.invalid.empty()) {
    std::snprintf(line, sizeof line, "%zu invalid realisation%s, kept out of the statistics (valid fraction %.3g [%.3g, %.3g]):\n",
                  s.invalid.size(), s.invalid.size() == 1 ? "" : "s", s.valid_fraction.estimate, s.valid_fraction.low,
                  s.valid_fraction.high);
    out += line;
    constexpr std::size_t SHOWN = 10;
    for (std::size_t k = 0; k < std::min(SHOWN, s.invalid.size()); ++k)
      out += "  realisation " + std::to_string(s.invalid[k].first) + ": " + s.invalid[k].second + "\n";
    if (s.invalid.size() > SHOWN) out += "  ... (all of them: /realisations/failure in the output file)\n";
  }
  return out;
}

}  // namespace stengmc
