#include "pipeline/measurement_noise.hpp"

#include <boost/random/normal_distribution.hpp>
#include <cmath>

#include "core/constants.hpp"
#include "core/format.hpp"
#include "spectral/power_law_noise.hpp"

namespace stengmc {

std::vector<double> first_order_lowpass(std::span<const double> x, double sample_rate_hz, double bandwidth_hz) {
  std::vector<double> y(x.begin(), x.end());
  if (x.empty()) return y;
  // Over one step h with x linear, y(h) = e y0 + (1 - e) x0 + (1 - (1 - e)/(lambda h)) (x1 - x0),
  // e = exp(-lambda h): the convolution of the filter's impulse response with the ramp.
  const double lambda_h = 2.0 * PI * bandwidth_hz / sample_rate_hz;
  const double e = std::exp(-lambda_h);
  const double ramp = 1.0 + std::expm1(-lambda_h) / lambda_h;
  for (std::size_t j = 1; j < x.size(); ++j) y[j] = e * y[j - 1] + (1.0 - e) * x[j - 1] + ramp * (x[j] - x[j - 1]);
  return y;
}

NoisyVoltage measure_voltage(std::span<const double> voltage_v, std::size_t first, std::size_t count,
                             double sample_rate_hz, const NoiseSettings& settings, RandomEngine& white,
                             RandomEngine& coloured) {
  NoisyVoltage out;
  out.voltage_v.assign(voltage_v.begin(), voltage_v.end());
  first = std::min(first, voltage_v.size());
  count = std::min(count, voltage_v.size() - first);
  if (count > 0) {
    double mean = 0.0;
    for (std::size_t j = first; j < first + count; ++j) mean += voltage_v[j];
    mean /= static_cast<double>(count);
    double power = 0.0;
    for (std::size_t j = first; j < first + count; ++j) power += (voltage_v[j] - mean) * (voltage_v[j] - mean);
    power /= static_cast<double>(count);
    // Nothing slides: the SNR refers to the reference the study gives (MODEL.md §3.6).
    if (power == 0.0) power = settings.reference_rms_v * settings.reference_rms_v;
    out.sigma_v = std::sqrt(power / std::pow(10.0, settings.snr_db / 10.0));
  }
  if (out.sigma_v > 0.0) {
    // White: drawn exactly as before the coloured part existed (same stream, same order).
    const double white_sigma = settings.coloured_share > 0.0 ? out.sigma_v * std::sqrt(1.0 - settings.coloured_share) : out.sigma_v;
    if (white_sigma > 0.0) {
      boost::random::normal_distribution<double> normal(0.0, white_sigma);
      for (double& v : out.voltage_v) v += normal(white);
    }
    if (settings.coloured_share > 0.0 && out.voltage_v.size() >= 2) {
      std::vector<double> flicker = power_law_noise(out.voltage_v.size(), settings.coloured_exponent, coloured);
      // Its variance over the analysis interval is the share (the series is unit-variance
      // over the whole record; the interval may be part of it).
      double mean = 0.0, variance = 0.0;
      for (std::size_t j = first; j < first + count; ++j) mean += flicker[j];
      mean /= static_cast<double>(count);
      for (std::size_t j = first; j < first + count; ++j) variance += (flicker[j] - mean) * (flicker[j] - mean);
      variance /= static_cast<double>(count);
      const double scale = variance > 0.0 ? out.sigma_v * std::sqrt(settings.coloured_share / variance) : 0.0;
      for (std::size_t j = 0; j < out.voltage_v.size(); ++j) out.voltage_v[j] += scale * flicker[j];
    }
  }
  if (settings.bandwidth_hz > 0.0) out.voltage_v = first_order_lowpass(out.voltage_v, sample_rate_hz, settings.bandwidth_hz);
  if (settings.offset_v != 0.0)
    for (double& v : out.voltage_v) v += settings.offset_v;
  return out;
}

NoiseSettings read_noise_settings(TomlTable& t) {
  NoiseSettings s;
  if (!t.has("snr_db")) t.fail("snr_db", "is missing: the signal-to-noise ratio of the noise added to V [dB]");
  s.snr_db = t.number("snr_db", 0.0);
  if (!std::isfinite(s.snr_db) || std::abs(s.snr_db) > MAX_SNR_DB)
    t.fail("snr_db", "= " + format_number(s.snr_db) + " must lie in [" + format_number(-MAX_SNR_DB) + ", " +
                         format_number(MAX_SNR_DB) + "] dB");
  s.coloured_share = t.number("coloured_share", 0.0);
  if (!(s.coloured_share >= 0.0 && s.coloured_share <= 1.0))
    t.fail("coloured_share", "= " + format_number(s.coloured_share) + " must lie in [0, 1] (the share of the noise power in the 1/f^alpha part)");
  s.coloured_exponent = t.number("coloured_exponent", 1.0);
  if (!(s.coloured_exponent >= 0.5 && s.coloured_exponent <= 2.0))
    t.fail("coloured_exponent", "= " + format_number(s.coloured_exponent) + " must lie in [0.5, 2] (alpha of 1/f^alpha)");
  s.offset_v = t.number("offset_v", 0.0);
  if (!(std::isfinite(s.offset_v) && std::abs(s.offset_v) <= 1e6))
    t.fail("offset_v", "= " + format_number(s.offset_v) + " must be a finite voltage within +-1e6 V");
  s.bandwidth_hz = t.number("bandwidth_hz", 0.0);
  if (!(std::isfinite(s.bandwidth_hz) && s.bandwidth_hz >= 0.0))
    t.fail("bandwidth_hz", "= " + format_number(s.bandwidth_hz) + " must be >= 0 Hz (0: no amplifier bandwidth)");
  s.reference_rms_v = t.number("reference_rms_v", 0.0);
  if (!(std::isfinite(s.reference_rms_v) && s.reference_rms_v >= 0.0 && s.reference_rms_v <= 1e6))
    t.fail("reference_rms_v", "= " + format_number(s.reference_rms_v) +
                                  " must lie in [0, 1e6] V (the rms the SNR refers to when nothing slides; 0: no noise then)");
  return s;
}

}  // namespace stengmc
