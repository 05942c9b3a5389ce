#include "inverse/naive_count.hpp"

#include <numeric>

#include "spectral/amplitude_spectrum.hpp"
#include "spectral/peaks.hpp"

namespace stengmc {

const std::vector<double>& naive_count_thresholds() {
  static const std::vector<double> thresholds = {1.5, 2.0, 2.5, 3.0, 4.0, 5.0, 6.0, 8.0, 10.0, 14.0, 20.0, 30.0};
  return thresholds;
}

NaiveCounter::NaiveCounter(std::size_t samples, double sample_rate_hz, double band_low_hz, double band_high_hz)
    : analyzer_(std::make_unique<SpectrumAnalyzer>(samples, WindowKind::hann)),
      sample_rate_hz_(sample_rate_hz),
      band_low_hz_(band_low_hz),
      band_high_hz_(band_high_hz) {}

NaiveCounter::~NaiveCounter() = default;

std::vector<double> NaiveCounter::count(std::span<const double> voltage, std::span<const double> thresholds) {
  // The mean (the belt-carried plateaus' offset) is removed as `spectrum` does.
  const double mean = std::accumulate(voltage.begin(), voltage.end(), 0.0) / static_cast<double>(voltage.size());
  std::vector<double> centred(voltage.begin(), voltage.end());
  for (double& v : centred) v -= mean;
  const AmplitudeSpectrum spectrum = analyzer_->analyse(centred, sample_rate_hz_);
  std::vector<double> counts;
  PeakSearchShared shared;  // one floor and one refinement per peak for all thresholds
  for (double threshold : thresholds) {
    PeakOptions options;
    options.prominence_over_floor = threshold;
    options.min_frequency_hz = band_low_hz_;
    options.max_frequency_hz = band_high_hz_;
    // A floor window of half the band: local enough to follow the lines' skirts, wide
    // enough that the lines themselves do not raise it.
    options.floor_window_hz = 0.5 * (band_high_hz_ - band_low_hz_);
    counts.push_back(static_cast<double>(find_peaks(spectrum, *analyzer_, centred, sample_rate_hz_, options, &shared).size()));
  }
  return counts;
}

}  // namespace stengmc
