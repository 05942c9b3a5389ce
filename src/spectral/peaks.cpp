#include "spectral/peaks.hpp"

#include <algorithm>
#include <complex>
#include <optional>
#include <boost/math/tools/minima.hpp>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include "core/error.hpp"
#include "spectral/local_noise_floor.hpp"
#include "spectral/dtft.hpp"

namespace stengmc {

namespace {

// Refinement grid: amplitude_at() at offsets -1, -3/4, ..., +1 bin before Brent's method.
// The rectangular window's main lobe is only +-1 bin wide, so over +-1 bin the DTFT of a
// line half a bin away is not unimodal (its first side lobe is inside); the grid finds the
// main lobe and Brent then works on a quarter-bin bracket where the amplitude is unimodal.
constexpr int GRID_STEPS_PER_BIN = 4;
constexpr double GRID_STEP_BINS = 1.0 / GRID_STEPS_PER_BIN;
// Brent's method locates a maximum to ~sqrt(eps) (the function is flat there to second
// order), here in bins: ~1e-8 bin, far below any statistical error of a real spectrum.
constexpr int BRENT_BITS = std::numeric_limits<double>::digits / 2;
constexpr std::uintmax_t BRENT_MAX_ITERATIONS = 100;

struct Candidate {
  std::size_t bin = 0;
  double prominence = 0.0;
};

// Local maxima as scipy.signal.find_peaks finds them: strictly higher than the left
// neighbour and than the first different value on the right; a flat top reports its middle.
// The two end bins are never peaks (DC is not a line; the last bin has no right flank).
std::vector<std::size_t> local_maxima(const std::vector<double>& a) {
  std::vector<std::size_t> maxima;
  const std::size_t n = a.size();
  std::size_t i = 1;
  while (i + 1 < n) {
    if (a[i - 1] < a[i]) {
      std::size_t ahead = i + 1;
      while (ahead + 1 < n && a[ahead] == a[i]) ++ahead;
      if (a[ahead] < a[i]) {
        maxima.push_back((i + ahead - 1) / 2);
        i = ahead;
      }
    }
    ++i;
  }
  return maxima;
}

// Topographic prominence as scipy's peak_prominences (unbounded window): walk each way until
// a higher bin or the end, take the lowest bin on each side; the peak stands above the
// higher of the two minima by its prominence.
double prominence(const std::vector<double>& a, std::size_t peak) {
  const double height = a[peak];
  double left_min = height;
  for (std::size_t i = peak + 1; i-- > 0 && a[i] <= height;) left_min = std::min(left_min, a[i]);
  double right_min = height;
  for (std::size_t i = peak; i < a.size() && a[i] <= height; ++i) right_min = std::min(right_min, a[i]);
  return height - std::max(left_min, right_min);
}

// Refinement by the grid and Brent: maximise the windowed DTFT amplitude (amplitude_at)
// over +-1 bin around the local maximum, by a quarter-bin grid then Brent's method (Brent 1973, "Algorithms for
// Minimization without Derivatives", ch. 5; boost::math::tools::brent_find_minima). For an
// isolated sinusoid that maximum lies exactly at its frequency and equals its amplitude,
// whatever the window and offset from the bins (no scalloping loss, unlike parabolic
// interpolation of A_k); the only errors are leakage from other components and from the
// line's own negative-frequency image, both tiny for lines many bins from 0 and each other.
Peak refine_by_grid(const AmplitudeSpectrum& spectrum, const SpectrumAnalyzer& analyzer, std::span<const double> signal,
                    double sample_rate_hz, const Candidate& c) {
  const double centre = spectrum.frequency_hz[c.bin];
  const double bin_width = spectrum.bin_width_hz;
  auto amplitude_at_offset = [&](double offset_bins) {
    return analyzer.amplitude_at(signal, sample_rate_hz, centre + offset_bins * bin_width);
  };
  double best_offset = 0.0;
  double best_amplitude = -1.0;
  for (int i = -GRID_STEPS_PER_BIN; i <= GRID_STEPS_PER_BIN; ++i) {
    const double offset = i * GRID_STEP_BINS;
    const double value = amplitude_at_offset(offset);
    if (value > best_amplitude) {
      best_amplitude = value;
      best_offset = offset;
    }
  }
  const double lo = std::max(-1.0, best_offset - GRID_STEP_BINS);
  const double hi = std::min(1.0, best_offset + GRID_STEP_BINS);
  std::uintmax_t iterations = BRENT_MAX_ITERATIONS;
  const auto [offset, negative_amplitude] = boost::math::tools::brent_find_minima(
      [&](double u) { return -amplitude_at_offset(u); }, lo, hi, BRENT_BITS, iterations);
  Peak peak;
  peak.bin = c.bin;
  peak.prominence = c.prominence;
  // Brent keeps its best point, so it cannot end below the grid's best; guard anyway.
  const bool brent_better = -negative_amplitude >= best_amplitude;
  peak.frequency_hz = centre + (brent_better ? offset : best_offset) * bin_width;
  peak.amplitude = brent_better ? -negative_amplitude : best_amplitude;
  return peak;
}

// Refinement by Newton's method on the same maximum: G(u) = |X(u)|^2 at u bins from the
// local maximum, with G' and G'' from the DTFT's own derivatives (dtft.hpp: one pass gives
// X, X' and X''), started from the parabola through the log-amplitudes of the three
// bins around the maximum (within a few hundredths of a bin for a tapered window) and
// kept inside a bracket [lo, hi] where G' changes sign (a step leaving it, or G'' >= 0,
// bisects instead: rtsafe, Press et al., Numerical Recipes 3rd ed. Sec. 9.4). Quadratic
// convergence: ~4 passes to 1e-10 bin, where the grid and Brent took ~25 passes to the
// ~1e-8 bin Brent's tolerance allows. The maximum is the same as the grid's whenever the
// main lobe holds one maximum within +-3/4 bin; where Newton cannot confirm one (the
// bracket's ends do not straddle it) the grid and Brent decide.
constexpr double NEWTON_BRACKET_BINS = 0.75;
constexpr double NEWTON_TOLERANCE_BINS = 1e-10;
constexpr int NEWTON_MAX_ITERATIONS = 40;

struct SlopeCurvature {
  double g1 = 0.0;  // dG/du
  double g2 = 0.0;  // d2G/du2
  std::complex<double> value;
};

std::optional<Peak> refine_by_newton(const AmplitudeSpectrum& spectrum, std::span<const double> windowed,
                                     double window_sum, double sample_rate_hz, const Candidate& c) {
  const auto& a = spectrum.amplitude;
  const std::size_t k = c.bin;
  if (k == 0 || k + 1 >= a.size() || !(a[k - 1] > 0.0 && a[k] > 0.0 && a[k + 1] > 0.0)) return std::nullopt;
  const double centre = spectrum.frequency_hz[k];
  const double scale = spectrum.bin_width_hz / sample_rate_hz;  // cycles per sample per bin
  auto evaluate = [&](double u) {
    const Dtft d = windowed_dtft(windowed, (centre + u * spectrum.bin_width_hz) / sample_rate_hz, true);
    SlopeCurvature s;
    s.value = d.value;
    s.g1 = 2.0 * std::real(std::conj(d.value) * d.first) * scale;
    s.g2 = 2.0 * (std::norm(d.first) + std::real(std::conj(d.value) * d.second)) * scale * scale;
    return s;
  };
  // Bracket: G' > 0 left of the maximum, < 0 right of it.
  double lo = -NEWTON_BRACKET_BINS, hi = NEWTON_BRACKET_BINS;
  if (!(evaluate(lo).g1 > 0.0 && evaluate(hi).g1 < 0.0)) return std::nullopt;
  const double l0 = std::log(a[k - 1]), l1 = std::log(a[k]), l2 = std::log(a[k + 1]);
  const double denominator = l0 - 2.0 * l1 + l2;
  double u = denominator < 0.0 ? std::clamp(0.5 * (l0 - l2) / denominator, -0.5, 0.5) : 0.0;
  SlopeCurvature s = evaluate(u);
  for (int iteration = 0; iteration < NEWTON_MAX_ITERATIONS; ++iteration) {
    (s.g1 > 0.0 ? lo : hi) = u;
    const double newton = s.g2 < 0.0 ? u - s.g1 / s.g2 : INFINITY;
    const double next = newton > lo && newton < hi ? newton : 0.5 * (lo + hi);
    const double step = next - u;
    u = next;
    s = evaluate(u);
    if (std::abs(step) < NEWTON_TOLERANCE_BINS || hi - lo < NEWTON_TOLERANCE_BINS) {
      Peak peak;
      peak.bin = c.bin;
      peak.prominence = c.prominence;
      peak.frequency_hz = centre + u * spectrum.bin_width_hz;
      peak.amplitude = 2.0 * std::abs(s.value) / window_sum;
      return peak;
    }
  }
  return std::nullopt;
}

}  // namespace

double noise_floor(const AmplitudeSpectrum& spectrum) {
  // For white noise every bin but DC (and Nyquist) is a complex Gaussian of variance
  // sigma^2 sum w^2, so |X_k| is Rayleigh and A_k = 2 |X_k| / sum w has
  //   rms = 2 sigma sqrt(sum w^2) / sum w,   median = rms sqrt(ln 2).
  // The median ignores the few bins a handful of lines occupy (and their leakage), unlike
  // the mean; DC is skipped because it carries the offset and drift, not noise. Zero
  // padding correlates neighbouring bins but leaves each bin's distribution unchanged.
  const auto& a = spectrum.amplitude;
  if (a.size() < 2) throw InputError("noise floor: the spectrum has no bin above DC");
  std::vector<double> values(a.begin() + 1, a.end());
  const std::size_t half = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(half), values.end());
  double median = values[half];
  if (values.size() % 2 == 0) {
    median = 0.5 * (median + *std::max_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(half)));
  }
  return median / std::sqrt(std::log(2.0));
}

std::vector<Peak> find_peaks(const AmplitudeSpectrum& spectrum, const SpectrumAnalyzer& analyzer,
                             std::span<const double> signal, double sample_rate_hz, const PeakOptions& options,
                             PeakSearchShared* shared) {
  const auto& a = spectrum.amplitude;
  if (a.size() != spectrum.frequency_hz.size()) throw InputError("find_peaks: spectrum frequency and amplitude sizes differ");
  if (!(options.prominence_over_floor >= 0.0) || !(options.min_separation_hz >= 0.0) ||
      !(options.leakage_margin >= 0.0) || !(options.max_frequency_hz >= 0.0) || !(options.floor_window_hz >= 0.0)) {
    throw InputError("find_peaks: prominence_over_floor, min_separation_hz, leakage_margin, max_frequency_hz and "
                     "floor_window_hz must be >= 0");
  }
  // The spectrum must come from these samples at this rate, or refinement looks elsewhere.
  const double expected_resolution = sample_rate_hz / static_cast<double>(signal.size());
  if (signal.size() != analyzer.samples() ||
      !(std::abs(spectrum.resolution_hz - expected_resolution) <= 1e-9 * expected_resolution)) {
    throw InputError("find_peaks: the spectrum was not computed from this signal at " + std::to_string(sample_rate_hz) +
                     " Hz");
  }

  // Every test below only removes a candidate, so they run cheapest first: height (a
  // prominence never exceeds its height) drops the noise maxima, side lobes go at the leakage
  // test, and the O(N) prominence walk is left for the few that could be lines.
  PeakSearchShared local;
  PeakSearchShared& reused = shared ? *shared : local;
  if (reused.floor_window_hz != options.floor_window_hz) {
    reused.floor = options.floor_window_hz > 0.0 ? local_noise_floor(spectrum, options.floor_window_hz)
                                                 : std::vector<double>(a.size(), noise_floor(spectrum));
    reused.floor_window_hz = options.floor_window_hz;
  }
  const std::vector<double>& floor = reused.floor;
  auto threshold = [&](std::size_t bin) { return options.prominence_over_floor * floor[bin]; };
  const double top = options.max_frequency_hz > 0.0 ? options.max_frequency_hz : INFINITY;
  std::vector<std::size_t> candidates;
  for (std::size_t bin : local_maxima(a)) {
    const double f = spectrum.frequency_hz[bin];
    if (f >= options.min_frequency_hz && f <= top && a[bin] > threshold(bin)) candidates.push_back(bin);
  }
  // Strongest first (ties: lower bin, so the result never depends on sort stability).
  std::sort(candidates.begin(), candidates.end(),
            [&a](std::size_t x, std::size_t y) { return a[x] != a[y] ? a[x] > a[y] : x < y; });

  // The windowed samples once, for every refinement's DTFT passes.
  std::vector<double> windowed(signal.size());
  double window_sum = 0.0;
  for (std::size_t n = 0; n < signal.size(); ++n) {
    windowed[n] = analyzer.window()[n] * signal[n];
    window_sum += analyzer.window()[n];
  }
  // Candidates too weak to survive a later dynamic-range cut (options.skip_below_db): the
  // refined amplitude exceeds the bin's by at most the scalloping loss (3.9 dB for the
  // rectangular window) plus interference; 12 dB covers both. Candidates come strongest
  // first, so the first one below ends the loop.
  constexpr double REFINEMENT_GAIN_ALLOWANCE_DB = 12.0;
  const double weakest_refined =
      options.skip_below_db > 0.0 && !candidates.empty()
          ? a[candidates.front()] * std::pow(10.0, -(options.skip_below_db + REFINEMENT_GAIN_ALLOWANCE_DB) / 20.0)
          : 0.0;
  std::vector<Peak> peaks;
  for (std::size_t bin : candidates) {
    if (peaks.size() >= options.max_peaks || a[bin] < weakest_refined) break;
    const double centre = spectrum.frequency_hz[bin];
    // Of two peaks closer than min_separation the weaker goes, as with scipy's `distance`.
    const bool too_close = std::any_of(peaks.begin(), peaks.end(), [&](const Peak& k) {
      return std::abs(spectrum.frequency_hz[k.bin] - centre) < options.min_separation_hz;
    });
    if (too_close) continue;
    // Kept lines a_j at f_j leak at most sum_j a_j (|W(f - f_j)| + |W(f + f_j)|) / W(0) into f
    // (triangle inequality; the second term is the negative-frequency image): a side lobe is
    // never above that, a real line is.
    if (options.leakage_margin > 0.0 && !peaks.empty()) {
      double leakage = 0.0;
      for (const Peak& k : peaks) {
        leakage += k.amplitude * (analyzer.window_response(centre - k.frequency_hz, sample_rate_hz) +
                                  analyzer.window_response(centre + k.frequency_hz, sample_rate_hz));
      }
      if (a[bin] <= options.leakage_margin * leakage) continue;
    }
    const double p = prominence(a, bin);
    if (p <= threshold(bin)) continue;
    if (const auto known = reused.refined.find(bin); known != reused.refined.end()) {
      peaks.push_back(known->second);
      continue;
    }
    const Candidate candidate{bin, p};
    const std::optional<Peak> newton = refine_by_newton(spectrum, windowed, window_sum, sample_rate_hz, candidate);
    peaks.push_back(newton ? *newton : refine_by_grid(spectrum, analyzer, signal, sample_rate_hz, candidate));
    reused.refined.emplace(bin, peaks.back());
  }
  std::sort(peaks.begin(), peaks.end(), [](const Peak& x, const Peak& y) { return x.frequency_hz < y.frequency_hz; });
  return peaks;
}

}  // namespace stengmc
