#include "inverse/inverse_prior.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/error.hpp"
#include "core/format.hpp"
#include "pipeline/measurement_noise.hpp"
#include "surface/load_spread.hpp"

namespace stengmc {

Distribution InversePrior::law(double p1, double p2) const {
  switch (family) {
    case StiffnessFamily::lognormal: return Distribution::lognormal(p1, p2);
    case StiffnessFamily::gamma: return Distribution::gamma(p1, p2);
    case StiffnessFamily::weibull: return Distribution::weibull(p1, p2);
  }
  throw Error("unknown stiffness family");
}

std::pair<std::string, std::string> InversePrior::parameter_keys() const {
  if (family == StiffnessFamily::lognormal) return {"median_n_per_m", "sigma_log"};
  return {"shape", "scale_n_per_m"};
}

std::pair<double, double> InversePrior::support(double tail) const {
  double low = INFINITY, high = 0.0;
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 5; ++j) {
      const Distribution d = law(first[0] + (first[1] - first[0]) * i / 4.0, second[0] + (second[1] - second[0]) * j / 4.0);
      low = std::min(low, d.quantile(tail));
      high = std::max(high, d.quantile(1.0 - tail));
    }
  return {low, high};
}

std::vector<std::pair<double, double>> InversePrior::log_stiffness_density(std::size_t points) const {
  const auto [low, high] = support(1e-6);
  const double a = std::log(low), b = std::log(high);
  std::vector<std::pair<double, double>> table(points);
  // Midpoint rule over the parameter box (the density is smooth in both parameters).
  constexpr int GRID = 24;
  for (std::size_t p = 0; p < points; ++p) table[p] = {a + (b - a) * static_cast<double>(p) / static_cast<double>(points - 1), 0.0};
  for (int i = 0; i < GRID; ++i)
    for (int j = 0; j < GRID; ++j) {
      const Distribution d = law(first[0] + (first[1] - first[0]) * (i + 0.5) / GRID, second[0] + (second[1] - second[0]) * (j + 0.5) / GRID);
      for (auto& [x, density] : table) density += std::exp(x) * d.pdf(std::exp(x)) / (GRID * GRID);
    }
  return table;
}

std::string InversePrior::describe() const {
  std::ostringstream out;
  out.precision(17);
  const auto [k1, k2] = parameter_keys();
  out << "count = [" << count_min << ", " << count_max << "]\n"
      << "stiffness_law = " << stiffness_family_name(family) << "\n"
      << k1 << " = [" << first[0] << ", " << first[1] << "]\n"
      << k2 << " = [" << second[0] << ", " << second[1] << "]\n"
      << "snr_db = [" << snr_db[0] << ", " << snr_db[1] << "]\n"
      << "load_cv = [" << load_cv[0] << ", " << load_cv[1] << "]\n"
      << "onset_s = [" << onset_s[0] << ", " << onset_s[1] << "]\n"
      << "parameter_tolerance = " << parameter_tolerance << "\n"
      << "noise = " << NOISE_COLOUR_NAMES.name(noise) << "\n"
      << "offset = " << (offset ? "true" : "false") << "\n"
      << "calibration_records = " << calibration_records << "\n"
      << "seed = " << seed << "\n";
  return out.str();
}

bool InversePrior::ideal_device() const {
  return load_cv[1] == 0.0 && onset_s[1] == 0.0 && parameter_tolerance == 0.0 && noise == NoiseColour::white && !offset;
}

double InversePrior::largest_load_ratio(double tail) const {
  const double spread = load_cv[1] > 0.0 ? LoadSpread(1.0, load_cv[1]).load_quantile(1.0 - tail) : 1.0;
  return spread * (1.0 + parameter_tolerance);
}

namespace {

std::array<double, 2> read_range(TomlTable& t, std::string_view key, std::array<double, 2> fallback, bool positive) {
  if (!t.has(key)) return fallback;
  const std::vector<double> v = t.number_list(key);
  if (v.size() != 2) t.fail(key, "must be an array [min, max] of two numbers");
  if (v[0] > v[1]) t.fail(key, "= [" + format_number(v[0]) + ", " + format_number(v[1]) + "]: min must not exceed max");
  if (positive && !(v[0] > 0.0)) t.fail(key, "= [" + format_number(v[0]) + ", " + format_number(v[1]) + "] must be > 0");
  return {v[0], v[1]};
}

}  // namespace

InversePrior read_inverse_prior(TomlTable& t) {
  InversePrior p;
  if (t.has("count")) {
    const std::array<double, 2> c = read_range(t, "count", {1, 16}, false);
    if (c[0] < 0.0) t.fail("count", "= [" + format_number(c[0]) + ", " + format_number(c[1]) + "] must be >= 0 (0: nothing slides)");
    if (!(c[1] > 0.0)) t.fail("count", "= [" + format_number(c[0]) + ", " + format_number(c[1]) + "]: the largest count must be > 0");
    if (c[0] != std::floor(c[0]) || c[1] != std::floor(c[1])) t.fail("count", "must hold two whole numbers [min, max]");
    if (c[1] > 64) t.fail("count", "= [" + format_number(c[0]) + ", " + format_number(c[1]) + "]: at most 64 sliding asperities are supported");
    p.count_min = static_cast<std::size_t>(c[0]);
    p.count_max = static_cast<std::size_t>(c[1]);
  }
  p.family = t.enumeration("stiffness_law", StiffnessFamily::lognormal, STIFFNESS_FAMILY_NAMES);
  if (p.family == StiffnessFamily::lognormal) {
    p.first = read_range(t, "median_n_per_m", p.first, true);
    p.second = read_range(t, "sigma_log", p.second, true);
  } else {
    // No paper value to default to: a gamma or Weibull prior states its ranges.
    if (!t.has("shape")) t.fail("shape", "is missing: a " + std::string(stiffness_family_name(p.family)) + " stiffness law needs shape = [min, max]");
    if (!t.has("scale_n_per_m")) t.fail("scale_n_per_m", "is missing: a " + std::string(stiffness_family_name(p.family)) + " stiffness law needs scale_n_per_m = [min, max]");
    p.first = read_range(t, "shape", p.first, true);
    p.second = read_range(t, "scale_n_per_m", p.second, true);
  }
  p.snr_db = read_range(t, "snr_db", p.snr_db, false);
  // A calibration adds its records' noise as [noise] does: refused here, at this key, not
  // when the calibration's own study (made from this table) reads it.
  if (!(std::abs(p.snr_db[0]) <= MAX_SNR_DB && std::abs(p.snr_db[1]) <= MAX_SNR_DB))
    t.fail("snr_db", "= [" + format_number(p.snr_db[0]) + ", " + format_number(p.snr_db[1]) + "] must lie in [" +
                         format_number(-MAX_SNR_DB) + ", " + format_number(MAX_SNR_DB) + "] dB (as [noise] snr_db)");
  p.load_cv = read_range(t, "load_cv", p.load_cv, false);
  if (!(p.load_cv[0] >= 0.0 && p.load_cv[1] <= MAX_LOAD_CV))
    t.fail("load_cv", "= [" + format_number(p.load_cv[0]) + ", " + format_number(p.load_cv[1]) + "] must lie in [0, " +
                          format_number(MAX_LOAD_CV) + "] (the loads' coefficient of variation; 0: equal loads)");
  p.onset_s = read_range(t, "onset_s", p.onset_s, false);
  if (!(p.onset_s[0] >= 0.0) || !std::isfinite(p.onset_s[1]))
    t.fail("onset_s", "= [" + format_number(p.onset_s[0]) + ", " + format_number(p.onset_s[1]) +
                          "] must lie in [0, inf) s (contact onsets after the record starts)");
  p.parameter_tolerance = t.non_negative("parameter_tolerance", p.parameter_tolerance);
  if (!(p.parameter_tolerance <= MAX_PARAMETER_TOLERANCE))
    t.fail("parameter_tolerance", "= " + format_number(p.parameter_tolerance) + " must lie in [0, " +
                                      format_number(MAX_PARAMETER_TOLERANCE) + "] (relative)");
  p.noise = t.enumeration("noise", p.noise, NOISE_COLOUR_NAMES);
  p.offset = t.boolean("offset", p.offset);
  p.calibration_records = static_cast<std::size_t>(t.integer("calibration_records", static_cast<long long>(p.calibration_records), 50));
  if (p.calibration_records > 1'000'000) t.fail("calibration_records", "must be <= 1000000");
  p.seed = static_cast<std::uint64_t>(t.integer("seed", static_cast<long long>(p.seed), 0));
  return p;
}

InversePrior inverse_prior_of_study(const std::string& study_text, const std::string& study_file) {
  auto document = TomlDocument::from_string(study_text, study_file);
  TomlTable root = document->root();
  auto table = root.table("inverse");
  if (!table) return {};
  InversePrior prior = read_inverse_prior(*table);
  document->reject_unknown_keys("inverse");
  return prior;
}

LogStiffnessDensity::LogStiffnessDensity(const InversePrior& prior) {
  for (const auto& [x, density] : prior.log_stiffness_density()) {
    x_.push_back(x);
    log_density_.push_back(std::log(std::max(density, 1e-300)));
  }
}

double LogStiffnessDensity::operator()(double k) const {
  const double x = std::log(k);
  const double step = x_[1] - x_[0];
  if (x <= x_.front()) return log_density_.front() - 50.0 * (x_.front() - x) / step;
  if (x >= x_.back()) return log_density_.back() - 50.0 * (x - x_.back()) / step;
  const double position = (x - x_.front()) / step;
  const auto i = std::min(static_cast<std::size_t>(position), x_.size() - 2);
  const double f = position - static_cast<double>(i);
  return log_density_[i] + f * (log_density_[i + 1] - log_density_[i]);
}

}  // namespace stengmc
