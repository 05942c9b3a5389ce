#include "inverse/calibration_sample.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "inverse/sample_statistics.hpp"

namespace stengmc {

double CalibrationSample::true_median() const { return sample_median(true_stiffness); }

RecordEstimate CalibrationSample::raw_estimate() const {
  RecordEstimate e;
  e.count = count;
  const double top = log_evidence.empty() ? 0.0 : *std::max_element(log_evidence.begin(), log_evidence.end());
  double total = 0.0;
  for (double l : log_evidence) total += std::exp(l - top);
  for (std::size_t j = 0; j < counts.size(); ++j) {
    e.posterior.counts.push_back(static_cast<std::size_t>(counts[j]));
    e.posterior.log_evidence.push_back(log_evidence[j]);
    e.posterior.probability.push_back(std::exp(log_evidence[j] - top) / total);
  }
  e.posterior.best = count;
  for (std::size_t i = 0; i < stiffness.size(); ++i) {
    EstimatedLine line;
    line.stiffness_n_per_m = stiffness[i];
    line.log_stiffness_se = log_stiffness_se[i];
    e.lines.push_back(line);
  }
  e.median_stiffness_n_per_m = median;
  e.sd_log_stiffness = sd_log;
  e.noise.sigma_v = noise_sigma_v;
  e.residual_sigma_v = residual_sigma_v;
  e.in_band_power_ratio = band_power_ratio;
  e.signal_to_noise_db = snr_estimate_db;
  e.seconds = seconds;
  return e;
}
double CalibrationSample::true_sd_log() const { return sample_sd_log(true_stiffness); }

void store_estimate(RealisationRecord& record, const RecordEstimate& e, const std::vector<double>& naive_counts) {
  std::vector<double> counts(e.posterior.counts.begin(), e.posterior.counts.end());
  std::vector<double> k, se;
  for (const EstimatedLine& line : e.lines) {
    k.push_back(line.stiffness_n_per_m);
    se.push_back(line.log_stiffness_se);
  }
  auto add = [&](const char* name, std::vector<double> values) { record.extras.push_back({name, std::move(values)}); };
  add("estimate:count", {static_cast<double>(e.count)});
  add("estimate:counts", std::move(counts));
  add("estimate:log_evidence", e.posterior.log_evidence);
  add("estimate:stiffness", std::move(k));
  add("estimate:log_stiffness_se", std::move(se));
  add("estimate:population", {e.median_stiffness_n_per_m, e.sd_log_stiffness});
  add("estimate:noise", {e.noise.sigma_v, e.residual_sigma_v, e.in_band_power_ratio, e.signal_to_noise_db});
  add("estimate:seconds", {e.seconds});
  add("naive:counts", naive_counts);
}

CalibrationSample calibration_sample(const RealisationRecord& record, const std::string& first_key,
                                     const std::string& second_key) {
  CalibrationSample s;
  s.realisation = record.realisation;
  auto extra = [&](const std::string& name) -> const std::vector<double>& {
    const RecordExtra* e = record.extra(name);
    if (!e) throw InputError("calibration record " + std::to_string(record.realisation) + " has no '" + name + "'");
    return e->values;
  };
  auto first = [&](const std::string& name) {
    const auto& v = extra(name);
    return v.empty() ? 0.0 : v.front();
  };
  s.snr_db = first("draw:noise.snr_db");
  s.law_first = first("draw:" + first_key);
  s.law_second = first("draw:" + second_key);
  s.valid = record.valid && record.extra("estimate:count") != nullptr;
  if (!s.valid) return s;
  s.true_stiffness = record.asperities[static_cast<std::size_t>(AsperityColumn::stiffness_n_per_m)];
  s.count = static_cast<std::size_t>(first("estimate:count"));
  s.counts = extra("estimate:counts");
  s.log_evidence = extra("estimate:log_evidence");
  s.stiffness = extra("estimate:stiffness");
  s.log_stiffness_se = extra("estimate:log_stiffness_se");
  const auto& population = extra("estimate:population");
  const auto& noise = extra("estimate:noise");
  if (population.size() != 2 || noise.size() != 4) throw InputError("calibration record " + std::to_string(record.realisation) + " is malformed");
  s.median = population[0];
  s.sd_log = population[1];
  s.noise_sigma_v = noise[0];
  s.residual_sigma_v = noise[1];
  s.band_power_ratio = noise[2];
  s.snr_estimate_db = noise[3];
  s.seconds = first("estimate:seconds");
  s.naive_counts = extra("naive:counts");
  return s;
}

}  // namespace stengmc
