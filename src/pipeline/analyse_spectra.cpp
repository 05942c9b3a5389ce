#include "pipeline/analyse_spectra.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/column.hpp"
#include "core/error.hpp"

namespace stengmc {

namespace {

// Fewer samples than this make neither a spectrum nor a line estimate worth reporting.
constexpr std::size_t MIN_SAMPLES = 16;

//! Sample rate of a uniform grid; spectra (MODEL.md §3) assume one.
double uniform_rate(std::span<const double> t) {
  if (t.size() < 2) throw InputError("spectrum: need at least 2 samples");
  const double step = (t.back() - t.front()) / static_cast<double>(t.size() - 1);
  for (std::size_t j = 1; j < t.size(); ++j)
    if (std::abs((t[j] - t[j - 1]) - step) > 1e-6 * step)
      throw InputError("spectrum: the time grid is not uniform (sample " + std::to_string(j) +
                       "); spectra need uniformly sampled signals");
  return 1.0 / step;
}


//! Drops items weaker than the strongest by more than `dynamic_range_db`.
template <class Items>
void keep_within_dynamic_range(Items& items, double dynamic_range_db) {
  double strongest = 0.0;
  for (const auto& item : items) strongest = std::max(strongest, item.amplitude);
  const double weakest = strongest * std::pow(10.0, -dynamic_range_db / 20.0);
  std::erase_if(items, [&](const auto& item) { return item.amplitude < weakest; });
}

}  // namespace

SpectralResult analyse_spectra(const SpectralInput& input, const SpectrumSettings& settings) {
  SpectralResult result;
  result.sample_rate_hz = uniform_rate(input.times_s);
  result.expected_frequency_hz = input.expected_frequency_hz;
  result.sliding = input.sliding;
  const double t0 = input.times_s.front();
  const auto begin = std::lower_bound(input.times_s.begin(), input.times_s.end(), t0 + settings.start_s - 1e-12 / result.sample_rate_hz);
  const auto end = settings.end_s > 0.0
      ? std::upper_bound(input.times_s.begin(), input.times_s.end(), t0 + settings.end_s + 1e-6 / result.sample_rate_hz)
      : input.times_s.end();
  result.first_sample = static_cast<std::size_t>(begin - input.times_s.begin());
  result.samples = end > begin ? static_cast<std::size_t>(end - begin) : 0;
  if (result.samples < MIN_SAMPLES)
    throw InputError("spectrum: the analysis interval [start_s, end_s] holds " + std::to_string(result.samples) +
                     " samples; at least " + std::to_string(MIN_SAMPLES) + " are needed");
  const auto segment = [&](std::span<const double> signal) { return signal.subspan(result.first_sample, result.samples); };

  SpectrumAnalyzer analyzer(result.samples, settings.window, settings.zero_pad_factor);
  const auto voltage = segment(input.voltage_v);
  result.voltage = analyzer.analyse(voltage, result.sample_rate_hz);
  result.noise_floor_v = noise_floor(result.voltage);
  result.peaks = find_peaks(result.voltage, analyzer, voltage, result.sample_rate_hz, settings.peaks);
  keep_within_dynamic_range(result.peaks, settings.dynamic_range_db);
  if (settings.element_currents && input.currents_a)
    for (const auto& current : *input.currents_a)
      result.current_amplitude.push_back(analyzer.analyse(segment(current), result.sample_rate_hz).amplitude);

  const auto peak_frequencies = column(result.peaks, [](const Peak& p) { return p.frequency_hz; });
  const auto peak_amplitudes = column(result.peaks, [](const Peak& p) { return p.amplitude; });
  result.fft = assess_identifiability(input.expected_frequency_hz, input.sliding, peak_frequencies, peak_amplitudes,
                                      settings.identifiability);
  if (settings.high_resolution) {
    result.lines = estimate_lines(voltage, result.sample_rate_hz, settings.esprit);
    keep_within_dynamic_range(result.lines, settings.dynamic_range_db);
    const auto line_frequencies = column(result.lines, [](const Line& l) { return l.frequency_hz; });
    const auto line_amplitudes = column(result.lines, [](const Line& l) { return l.amplitude; });
    result.high_resolution = assess_identifiability(input.expected_frequency_hz, input.sliding, line_frequencies,
                                                    line_amplitudes, settings.identifiability);
  }
  if (settings.spectrogram) result.spectrogram = compute_spectrogram(input.voltage_v, result.sample_rate_hz, *settings.spectrogram);
  return result;
}

}  // namespace stengmc
