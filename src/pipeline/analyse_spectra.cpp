#include "pipeline/analyse_spectra.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/column.hpp"
#include "core/constants.hpp"
#include "core/error.hpp"
#include "core/format.hpp"

namespace stengmc {

namespace {

// Fewer samples than this make neither a spectrum nor a line estimate worth reporting.
constexpr std::size_t MIN_SAMPLES = 16;

// ESPRIT poles wider than this many resolution cells (d / pi > 10 / T) are dropped.
constexpr double MAX_LINE_BANDWIDTH_CELLS = 10.0;

//! Sliding asperities whose lines lie closer than the window's main-lobe half-width
//! cannot be told apart by FFT peaks: credit for them means little. Says so plainly.
void note_unresolvable_lines(SpectralResult& result, const SpectrumSettings& settings) {
  // Main-lobe half-width in bins: rectangular 1, Hann 2, 4-term Blackman-Harris 4.
  const double lobe_bins = settings.window == WindowKind::rectangular ? 1.0 : settings.window == WindowKind::hann ? 2.0 : 4.0;
  const double lobe_hz = lobe_bins * result.voltage.resolution_hz;
  const auto& f = result.expected_frequency_hz;
  std::vector<std::string> pairs;
  for (std::size_t i = 0; i < f.size(); ++i)
    for (std::size_t j = i + 1; j < f.size(); ++j)
      if (result.sliding[i] && result.sliding[j] && std::abs(f[i] - f[j]) < lobe_hz)
        pairs.push_back(std::to_string(i + 1) + " and " + std::to_string(j + 1) + " (" +
                        format_number(std::abs(f[i] - f[j])) + " Hz apart)");
  if (pairs.empty()) return;
  // A rough surface can have dozens of such pairs: one note, the first few named.
  constexpr std::size_t NAMED = 4;
  std::string list;
  for (std::size_t k = 0; k < std::min(pairs.size(), NAMED); ++k) list += (k ? ", " : "") + pairs[k];
  if (pairs.size() > NAMED) list += " and " + std::to_string(pairs.size() - NAMED) + " more pairs";
  std::string advice;  // only where the other method is there and did at least as well
  if (!result.high_resolution) advice = "; [spectrum] high_resolution = true adds ESPRIT lines, which can resolve lines this close";
  else if (result.high_resolution->n_identifiable > result.fft.n_identifiable) advice = "; prefer the ESPRIT result, which identifies more";
  result.notes.push_back("asperities " + list + ": lines inside the window's main lobe (" + format_number(lobe_hz) +
                         " Hz): the FFT cannot resolve them" + advice);
}

//! Sample rate of a uniform grid; spectra (MODEL.md §3) assume one.
double uniform_rate(std::span<const double> t) {
  if (t.size() < 2) throw InputError("spectrum: need at least 2 samples");
  for (std::size_t j = 1; j < t.size(); ++j)
    if (!(t[j] > t[j - 1])) throw InputError("spectrum: times must strictly increase (sample " + std::to_string(j) + ")");
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

AnalysisRange analysis_range(std::span<const double> times_s, const SpectrumSettings& settings) {
  const double rate = uniform_rate(times_s);
  // Half-open [t0 + start_s, t0 + end_s): M = (end_s - start_s) x rate samples exactly,
  // so a 40 us interval at 100 MHz is 4000 samples and 1/T = 25 kHz.
  const auto first = static_cast<std::size_t>(std::llround(settings.start_s * rate));
  const std::size_t available = first < times_s.size() ? times_s.size() - first : 0;
  const std::size_t wanted = settings.end_s > 0.0
      ? static_cast<std::size_t>(std::llround((settings.end_s - settings.start_s) * rate))
      : available;
  return {first, std::min(wanted, available), rate};
}

SpectralResult analyse_spectra(const SpectralInput& input, const SpectrumSettings& settings) {
  SpectralResult result;
  const AnalysisRange range = analysis_range(input.times_s, settings);
  result.sample_rate_hz = range.sample_rate_hz;
  result.first_sample = range.first_sample;
  result.samples = range.samples;
  result.start_time_s = input.times_s.front() + static_cast<double>(range.first_sample) / range.sample_rate_hz;
  result.expected_frequency_hz = input.expected_frequency_hz;
  result.sliding = input.sliding;
  // An over-damped asperity (zeta >= 1) has no line to look for, whether or not it slides.
  for (std::size_t i = 0; i < result.sliding.size(); ++i)
    if (!(result.expected_frequency_hz.at(i) > 0.0)) result.sliding[i] = false;
  if (result.samples < MIN_SAMPLES)
    throw InputError("spectrum: the analysis interval [start_s, end_s) = [" + std::to_string(settings.start_s) + ", " +
                     (settings.end_s > 0.0 ? std::to_string(settings.end_s) : std::string("end")) + ") s holds " +
                     std::to_string(result.samples) + " samples of a signal lasting " +
                     std::to_string(input.times_s.back() - input.times_s.front()) + " s; at least " +
                     std::to_string(MIN_SAMPLES) + " are needed");
  // The offset is removed before analysis: its window leakage would otherwise be the
  // strongest "line" and hide weak ones. A_0 is reported as `mean_v`.
  const auto segment = [&](std::span<const double> signal, const char* what) {
    std::vector<double> values(signal.begin() + static_cast<std::ptrdiff_t>(result.first_sample),
                               signal.begin() + static_cast<std::ptrdiff_t>(result.first_sample + result.samples));
    double mean = 0.0;
    for (std::size_t j = 0; j < values.size(); ++j) {
      if (!std::isfinite(values[j]))
        throw InputError(std::string("spectrum: ") + what + " is not finite at sample " + std::to_string(result.first_sample + j) +
                         " (t = " + std::to_string(input.times_s[result.first_sample + j]) + " s)");
      mean += values[j];
    }
    mean /= static_cast<double>(values.size());
    for (double& v : values) v -= mean;
    return std::pair{values, mean};
  };

  SpectrumAnalyzer& analyzer = thread_spectrum_analyzer(result.samples, settings.window, settings.zero_pad_factor);
  const auto [voltage, mean_voltage] = segment(input.voltage_v, "the voltage");
  result.mean_v = mean_voltage;
  result.voltage = analyzer.analyse(voltage, result.sample_rate_hz);
  result.noise_floor_v = noise_floor(result.voltage);
  PeakOptions peak_options = settings.peaks;
  peak_options.skip_below_db = settings.dynamic_range_db;  // cut below, exactly, after refinement
  result.peaks = find_peaks(result.voltage, analyzer, voltage, result.sample_rate_hz, peak_options);
  keep_within_dynamic_range(result.peaks, settings.dynamic_range_db);
  if (settings.element_currents && input.currents_a)
    for (const auto& current : *input.currents_a)
      result.current_amplitude.push_back(analyzer.analyse(segment(current, "an element current").first, result.sample_rate_hz).amplitude);

  const auto peak_frequencies = column(result.peaks, [](const Peak& p) { return p.frequency_hz; });
  const auto peak_amplitudes = column(result.peaks, [](const Peak& p) { return p.amplitude; });
  result.fft = assess_identifiability(result.expected_frequency_hz, result.sliding, peak_frequencies, peak_amplitudes,
                                      settings.identifiability);
  if (settings.high_resolution) {
    result.lines = estimate_lines(voltage, result.sample_rate_hz, settings.esprit);
    // A pole whose bandwidth d/pi spans many resolution cells is a transient or drift the
    // exponential model absorbed, not a spectral line.
    std::erase_if(result.lines, [&](const Line& l) {
      return l.damping_per_s / PI > MAX_LINE_BANDWIDTH_CELLS * result.voltage.resolution_hz;
    });
    keep_within_dynamic_range(result.lines, settings.dynamic_range_db);
    const auto line_frequencies = column(result.lines, [](const Line& l) { return l.frequency_hz; });
    const auto line_amplitudes = column(result.lines, [](const Line& l) { return l.amplitude; });
    result.high_resolution = assess_identifiability(result.expected_frequency_hz, result.sliding, line_frequencies,
                                                    line_amplitudes, settings.identifiability);
  }
  note_unresolvable_lines(result, settings);
  if (settings.spectrogram) {
    result.spectrogram = compute_spectrogram(input.voltage_v, result.sample_rate_hz, *settings.spectrogram);
    for (double& t : result.spectrogram->time_s) t += input.times_s.front();
  }
  return result;
}

}  // namespace stengmc
