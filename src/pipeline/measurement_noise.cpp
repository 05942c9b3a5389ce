#include "pipeline/measurement_noise.hpp"

#include <boost/random/normal_distribution.hpp>
#include <cmath>

#include "core/format.hpp"

namespace stengmc {

NoisyVoltage add_white_noise(std::span<const double> voltage_v, std::size_t first, std::size_t count, double snr_db,
                             RandomEngine& engine) {
  NoisyVoltage out;
  out.voltage_v.assign(voltage_v.begin(), voltage_v.end());
  first = std::min(first, voltage_v.size());
  count = std::min(count, voltage_v.size() - first);
  if (count == 0) return out;
  double mean = 0.0;
  for (std::size_t j = first; j < first + count; ++j) mean += voltage_v[j];
  mean /= static_cast<double>(count);
  double power = 0.0;
  for (std::size_t j = first; j < first + count; ++j) power += (voltage_v[j] - mean) * (voltage_v[j] - mean);
  power /= static_cast<double>(count);
  out.sigma_v = std::sqrt(power / std::pow(10.0, snr_db / 10.0));
  if (!(out.sigma_v > 0.0)) return out;
  boost::random::normal_distribution<double> normal(0.0, out.sigma_v);
  for (double& v : out.voltage_v) v += normal(engine);
  return out;
}

NoiseSettings read_noise_settings(TomlTable& t) {
  NoiseSettings s;
  if (!t.has("snr_db")) t.fail("snr_db", "is missing: the signal-to-noise ratio of the white noise added to V [dB]");
  s.snr_db = t.number("snr_db", 0.0);
  if (!std::isfinite(s.snr_db) || std::abs(s.snr_db) > MAX_SNR_DB)
    t.fail("snr_db", "= " + format_number(s.snr_db) + " must lie in [" + format_number(-MAX_SNR_DB) + ", " +
                         format_number(MAX_SNR_DB) + "] dB");
  return s;
}

}  // namespace stengmc
