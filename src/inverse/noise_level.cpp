#include "inverse/noise_level.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

#include "spectral/amplitude_spectrum.hpp"

namespace stengmc {

namespace {
constexpr std::size_t MIN_BAND_BINS = 64;
}  // namespace

NoiseEstimator::NoiseEstimator(std::size_t samples, double sample_rate_hz, double band_low_hz)
    : analyzer_(std::make_unique<SpectrumAnalyzer>(samples, WindowKind::hann)),
      sample_rate_hz_(sample_rate_hz),
      band_low_hz_(band_low_hz) {
  const std::vector<double>& w = analyzer_->window();
  const double sum = std::accumulate(w.begin(), w.end(), 0.0);
  const double squares = std::inner_product(w.begin(), w.end(), w.begin(), 0.0);
  window_factor_ = 2.0 * std::sqrt(std::log(2.0) * squares) / sum;
}

NoiseEstimator::~NoiseEstimator() = default;

NoiseLevel NoiseEstimator::estimate(std::span<const double> voltage) {
  const AmplitudeSpectrum s = analyzer_->analyse(voltage, sample_rate_hz_);
  std::vector<double> band;
  const double top = 0.95 * 0.5 * sample_rate_hz_;
  for (std::size_t k = 1; k < s.frequency_hz.size(); ++k)
    if (s.frequency_hz[k] >= band_low_hz_ && s.frequency_hz[k] <= top) band.push_back(s.amplitude[k]);
  if (band.size() < MIN_BAND_BINS) return {};
  auto middle = band.begin() + static_cast<std::ptrdiff_t>(band.size() / 2);
  std::nth_element(band.begin(), middle, band.end());
  return {*middle / window_factor_, band.size()};
}

double NoiseEstimator::band_power_ratio(std::span<const double> residual, double low_hz, double high_hz) {
  const AmplitudeSpectrum s = analyzer_->analyse(residual, sample_rate_hz_);
  const double top = 0.95 * 0.5 * sample_rate_hz_;
  double inside = 0.0, outside = 0.0;
  std::size_t n_inside = 0, n_outside = 0;
  for (std::size_t k = 1; k < s.frequency_hz.size(); ++k) {
    const double f = s.frequency_hz[k], a2 = s.amplitude[k] * s.amplitude[k];
    if (f >= low_hz && f <= high_hz) inside += a2, ++n_inside;
    else if (f >= band_low_hz_ && f <= top) outside += a2, ++n_outside;
  }
  if (n_inside == 0 || n_outside == 0 || outside <= 0.0) return 1.0;
  return (inside / static_cast<double>(n_inside)) / (outside / static_cast<double>(n_outside));
}

}  // namespace stengmc
