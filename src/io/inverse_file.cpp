#include "io/inverse_file.hpp"

#include <cstdio>

#include "core/hdf5_file.hpp"
#include "io/run_file.hpp"
#include "io/output_vocabulary.hpp"

namespace stengmc {

namespace {

constexpr std::size_t KEPT_TRACES = 16;

std::string join(const std::vector<std::string>& lines, const char* separator) {
  std::string out;
  for (const auto& l : lines) out += (out.empty() ? "" : separator) + l;
  return out;
}

void write_laws(Hdf5Writer& f, const std::string& group, const std::vector<std::vector<LawFit>>& per_record) {
  std::vector<std::int64_t> record, fitted;
  std::vector<std::string> family;
  std::vector<double> first, first_low, first_high, second, second_low, second_high, aic, delta, median, sd;
  for (std::size_t r = 0; r < per_record.size(); ++r) {
    const double best = per_record[r].empty() ? 0.0 : per_record[r].front().aic;
    for (const LawFit& law : per_record[r]) {
      record.push_back(static_cast<std::int64_t>(r));
      family.emplace_back(stiffness_family_name(law.family));
      fitted.push_back(law.fitted ? 1 : 0);
      first.push_back(law.parameters[0]);
      second.push_back(law.parameters[1]);
      first_low.push_back(law.interval[0][0]);
      first_high.push_back(law.interval[0][1]);
      second_low.push_back(law.interval[1][0]);
      second_high.push_back(law.interval[1][1]);
      aic.push_back(law.aic);
      delta.push_back(law.fitted ? law.aic - best : 0.0);
      median.push_back(law.median);
      sd.push_back(law.sd_log);
    }
  }
  f.write(group + "/record", record);
  f.write(group + "/family", family);
  f.write(group + "/fitted", fitted);
  f.write(group + "/first", first);
  f.write(group + "/first_low", first_low);
  f.write(group + "/first_high", first_high);
  f.write(group + "/second", second);
  f.write(group + "/second_low", second_low);
  f.write(group + "/second_high", second_high);
  f.write(group + "/aic", aic);
  f.write(group + "/delta_aic", delta);
  f.write(group + "/median", median);
  f.write(group + "/sd_log", sd);
}

}  // namespace

void write_inverse_file(const std::string& path, const InverseFileContext& context, const std::vector<Inversion>& inversions,
                        const std::vector<LawFit>& pooled) {
  Hdf5Writer f(path, describe_output);
  write_provenance(f, {.file_type = "stengmc-inverse",
                       .input_file = context.known_file,
                       .input_text = context.known_text,
                       .seed = 0,
                       .surface_file = "",
                       .surface_text = "",
                       .auxiliary_inputs = ""});
  char hash[32];
  std::snprintf(hash, sizeof hash, "%016llx", static_cast<unsigned long long>(context.bank_identity_hash));
  f.attribute("/", "bank", context.bank_path);
  f.attribute("/", "bank_identity_hash", context.bank_path.empty() ? std::string() : std::string(hash));
  f.attribute("/", "bank_git_revision", context.bank_git_revision);
  f.attribute("/", "calibrated", static_cast<std::int64_t>(context.bank_path.empty() ? 0 : 1));
  f.attribute("/", "records", static_cast<std::int64_t>(inversions.size()));

  std::vector<std::string> names, verdicts, warnings;
  std::vector<double> noise, residual, snr, band, seconds, naive;
  std::vector<std::int64_t> outside, onset_steps, estimate, low, high, offsets{0}, line_record, intervals;
  std::vector<std::vector<double>> probability, raw_probability;
  std::vector<double> k, k_low, k_high, se, inflation, frequency, amplitude, separation;
  std::vector<double> median, median_low, median_high, sd, sd_low, sd_high;
  std::vector<std::vector<LawFit>> laws;
  for (std::size_t r = 0; r < inversions.size(); ++r) {
    const Inversion& inv = inversions[r];
    const RecordEstimate& e = inv.raw;
    const CalibratedEstimate& c = inv.calibrated;
    names.push_back(inv.name);
    verdicts.push_back(join(inv.verdict, " "));
    warnings.push_back(join(inv.warnings, "; "));
    noise.push_back(e.noise.sigma_v);
    residual.push_back(e.residual_sigma_v);
    snr.push_back(e.signal_to_noise_db);
    band.push_back(e.in_band_power_ratio);
    seconds.push_back(e.seconds);
    outside.push_back(static_cast<std::int64_t>(e.lines_outside_prior));
    onset_steps.push_back(static_cast<std::int64_t>(e.onset_steps));
    estimate.push_back(static_cast<std::int64_t>(c.count));
    low.push_back(static_cast<std::int64_t>(c.interval_low));
    high.push_back(static_cast<std::int64_t>(c.interval_high));
    naive.push_back(inv.naive_count);
    probability.push_back(c.probability);
    std::vector<double> raw(c.counts.size(), 0.0);
    for (std::size_t j = 0; j < e.posterior.counts.size(); ++j) {
      const std::size_t n = e.posterior.counts[j];
      if (n >= c.counts.front() && n <= c.counts.back()) raw[n - c.counts.front()] = e.posterior.probability[j];
    }
    raw_probability.push_back(raw);
    for (std::size_t i = 0; i < e.lines.size(); ++i) {
      const EstimatedLine& line = e.lines[i];
      line_record.push_back(static_cast<std::int64_t>(r));
      k.push_back(line.stiffness_n_per_m);
      k_low.push_back(c.line_low[i]);
      k_high.push_back(c.line_high[i]);
      se.push_back(line.log_stiffness_se);
      inflation.push_back(line.se_inflation);
      frequency.push_back(line.frequency_hz);
      amplitude.push_back(line.amplitude_v);
      separation.push_back(line.nearest_separation_hz);
    }
    offsets.push_back(static_cast<std::int64_t>(k.size()));
    median.push_back(c.median);
    median_low.push_back(c.median_low);
    median_high.push_back(c.median_high);
    sd.push_back(c.sd_log);
    sd_low.push_back(c.sd_log_low);
    sd_high.push_back(c.sd_log_high);
    intervals.push_back(c.population_intervals ? 1 : 0);
    laws.push_back(inv.laws);
  }
  f.write("/inverse/records/name", names);
  f.write("/inverse/records/noise_sigma_v", noise);
  f.write("/inverse/records/residual_sigma_v", residual);
  f.write("/inverse/records/signal_to_noise_db", snr);
  f.write("/inverse/records/band_power_ratio", band);
  f.write("/inverse/records/lines_outside_prior", outside);
  f.write("/inverse/records/onset_steps", onset_steps);
  f.write("/inverse/records/seconds", seconds);
  f.write("/inverse/records/verdict", verdicts);
  f.write("/inverse/records/warnings", warnings);
  std::vector<std::int64_t> counts;
  if (!inversions.empty())
    for (std::size_t n : inversions.front().calibrated.counts) counts.push_back(static_cast<std::int64_t>(n));
  f.write("/inverse/count/counts", counts);
  f.write("/inverse/count/estimate", estimate);
  f.write("/inverse/count/interval_low", low);
  f.write("/inverse/count/interval_high", high);
  f.write("/inverse/count/naive_fft", naive);
  f.write("/inverse/count/probability", probability);
  f.write("/inverse/count/raw_probability", raw_probability);
  f.write("/inverse/lines/record", line_record);
  f.write("/inverse/lines/stiffness_n_per_m", k);
  f.write("/inverse/lines/stiffness_low", k_low);
  f.write("/inverse/lines/stiffness_high", k_high);
  f.write("/inverse/lines/log_stiffness_se", se);
  f.write("/inverse/lines/se_inflation", inflation);
  f.write("/inverse/lines/frequency_hz", frequency);
  f.write("/inverse/lines/amplitude_v", amplitude);
  f.write("/inverse/lines/nearest_separation_hz", separation);
  f.write("/inverse/lines/offset", offsets);
  f.write("/inverse/stiffness/median", median);
  f.write("/inverse/stiffness/median_low", median_low);
  f.write("/inverse/stiffness/median_high", median_high);
  f.write("/inverse/stiffness/sd_log", sd);
  f.write("/inverse/stiffness/sd_log_low", sd_low);
  f.write("/inverse/stiffness/sd_log_high", sd_high);
  f.write("/inverse/stiffness/intervals_calibrated", intervals);
  write_laws(f, "/inverse/stiffness/laws", laws);
  write_laws(f, "/inverse/pooled/laws", {pooled});
  for (std::size_t r = 0; r < inversions.size() && r < KEPT_TRACES; ++r) {
    const std::string g = "/inverse/traces/record_" + std::to_string(r);
    f.write(g + "/time", context.times[r]);
    f.write(g + "/voltage", context.voltages[r]);
    f.write(g + "/model", inversions[r].model_v);
  }
  f.commit();
}

}  // namespace stengmc
