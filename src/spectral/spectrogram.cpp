#include "spectral/spectrogram.hpp"

#include <cmath>
#include <string>

#include "core/error.hpp"
#include "spectral/amplitude_spectrum.hpp"

namespace stengmc {

Spectrogram compute_spectrogram(std::span<const double> signal, double sample_rate_hz,
                                const SpectrogramOptions& options) {
  const std::size_t length = options.window_samples;
  if (length == 0) throw InputError("spectrogram: window_samples must be >= 1");
  if (options.hop_samples == 0) throw InputError("spectrogram: hop_samples must be >= 1");
  if (length > signal.size()) {
    throw InputError("spectrogram: window_samples = " + std::to_string(length) + " is longer than the signal (" +
                     std::to_string(signal.size()) + " samples)");
  }
  if (!(std::isfinite(sample_rate_hz) && sample_rate_hz > 0.0)) {
    throw InputError("spectrogram: sample rate must be a positive finite number of Hz");
  }

  // One analyzer (one FFTW plan, one window) for every segment: tfrstft's sliding window.
  SpectrumAnalyzer& analyzer = thread_spectrum_analyzer(length, options.window, 1);

  // A segment's spectrum is the window-weighted average of its samples' content, so it is
  // dated at the window's centroid: sample L/2 for the periodic Hann and Blackman-Harris
  // windows (w_n = w_{L-n}), (L-1)/2 for the rectangular one. For a linear chirp this is
  // where the instantaneous frequency equals the segment's spectral centroid.
  const auto& w = analyzer.window();
  double weighted_index = 0.0;
  double weight = 0.0;
  for (std::size_t n = 0; n < w.size(); ++n) {
    weighted_index += static_cast<double>(n) * w[n];
    weight += w[n];
  }
  const double centre_offset = weighted_index / weight;

  Spectrogram result;
  const std::size_t segments = (signal.size() - length) / options.hop_samples + 1;
  result.time_s.reserve(segments);
  result.amplitude.reserve(segments);
  for (std::size_t s = 0; s < segments; ++s) {
    const std::size_t start = s * options.hop_samples;
    AmplitudeSpectrum spectrum = analyzer.analyse(signal.subspan(start, length), sample_rate_hz);
    if (s == 0) result.frequency_hz = std::move(spectrum.frequency_hz);
    result.time_s.push_back((static_cast<double>(start) + centre_offset) / sample_rate_hz);
    result.amplitude.push_back(std::move(spectrum.amplitude));
  }
  return result;
}

}  // namespace stengmc
