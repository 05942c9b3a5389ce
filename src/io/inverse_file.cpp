#include "io/inverse_file.hpp"

#include <cstdio>

#include "core/hdf5_file.hpp"
#include "io/run_file.hpp"

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
  f.write(group + "/record", record, "index");
  f.write(group + "/family", family, "text");
  f.write(group + "/fitted", fitted, "1");
  f.write(group + "/first", first, "median [N/m] (lognormal) or shape [-]");
  f.write(group + "/first_low", first_low, "as first");
  f.write(group + "/first_high", first_high, "as first");
  f.write(group + "/second", second, "sigma_log [-] (lognormal) or scale [N/m]");
  f.write(group + "/second_low", second_low, "as second");
  f.write(group + "/second_high", second_high, "as second");
  f.write(group + "/aic", aic, "1");
  f.write(group + "/delta_aic", delta, "1");
  f.write(group + "/median", median, "N/m");
  f.write(group + "/sd_log", sd, "1");
}

}  // namespace

void write_inverse_file(const std::string& path, const InverseFileContext& context, const std::vector<Inversion>& inversions,
                        const std::vector<LawFit>& pooled) {
  Hdf5Writer f(path);
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
  std::vector<std::int64_t> outside, estimate, low, high, offsets{0}, line_record, intervals;
  std::vector<std::vector<double>> probability, raw_probability;
  std::vector<double> k, k_low, k_high, se, frequency, amplitude, separation;
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
  f.write("/inverse/records/name", names, "text");
  f.write("/inverse/records/noise_sigma_v", noise, "V");
  f.write("/inverse/records/residual_sigma_v", residual, "V");
  f.write("/inverse/records/signal_to_noise_db", snr, "dB");
  f.write("/inverse/records/band_power_ratio", band, "1");
  f.write("/inverse/records/lines_outside_prior", outside, "1");
  f.write("/inverse/records/seconds", seconds, "s");
  f.write("/inverse/records/verdict", verdicts, "text");
  f.write("/inverse/records/warnings", warnings, "text");
  std::vector<std::int64_t> counts;
  if (!inversions.empty())
    for (std::size_t n : inversions.front().calibrated.counts) counts.push_back(static_cast<std::int64_t>(n));
  f.write("/inverse/count/counts", counts, "1");
  f.write("/inverse/count/estimate", estimate, "1");
  f.write("/inverse/count/interval_low", low, "1");
  f.write("/inverse/count/interval_high", high, "1");
  f.write("/inverse/count/naive_fft", naive, "1");
  f.write("/inverse/count/probability", probability, "1");
  f.write("/inverse/count/raw_probability", raw_probability, "1");
  f.write("/inverse/lines/record", line_record, "index");
  f.write("/inverse/lines/stiffness_n_per_m", k, "N/m");
  f.write("/inverse/lines/stiffness_low", k_low, "N/m");
  f.write("/inverse/lines/stiffness_high", k_high, "N/m");
  f.write("/inverse/lines/log_stiffness_se", se, "1");
  f.write("/inverse/lines/frequency_hz", frequency, "Hz");
  f.write("/inverse/lines/amplitude_v", amplitude, "V");
  f.write("/inverse/lines/nearest_separation_hz", separation, "Hz");
  f.write("/inverse/lines/offset", offsets, "index");
  f.write("/inverse/stiffness/median", median, "N/m");
  f.write("/inverse/stiffness/median_low", median_low, "N/m");
  f.write("/inverse/stiffness/median_high", median_high, "N/m");
  f.write("/inverse/stiffness/sd_log", sd, "1");
  f.write("/inverse/stiffness/sd_log_low", sd_low, "1");
  f.write("/inverse/stiffness/sd_log_high", sd_high, "1");
  f.write("/inverse/stiffness/intervals_calibrated", intervals, "1");
  write_laws(f, "/inverse/stiffness/laws", laws);
  write_laws(f, "/inverse/pooled/laws", {pooled});
  for (std::size_t r = 0; r < inversions.size() && r < KEPT_TRACES; ++r) {
    const std::string g = "/inverse/traces/record_" + std::to_string(r);
    f.write(g + "/time", context.times[r], "s");
    f.write(g + "/voltage", context.voltages[r], "V");
    f.write(g + "/model", inversions[r].model_v, "V");
  }
  f.commit();
}

}  // namespace stengmc
