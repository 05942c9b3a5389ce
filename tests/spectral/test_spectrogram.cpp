// STFT (MODEL.md §3, the paper's tftb tfrstft) against closed forms: a linear chirp's
// instantaneous frequency, and Parseval summed over overlapping segments.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <random>
#include <vector>

#include "core/constants.hpp"
#include "core/error.hpp"
#include "spectral/spectrogram.hpp"

namespace stengmc {
namespace {

constexpr double FS = 1000.0;  // [Hz]

std::string sci(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", value);
  return text;
}

// y = sin(2 pi (f0 t + k t^2 / 2)), instantaneous frequency f0 + k t.
std::vector<double> chirp(std::size_t m, double f0, double k) {
  std::vector<double> y(m);
  for (std::size_t n = 0; n < m; ++n) {
    const double t = static_cast<double>(n) / FS;
    y[n] = std::sin(2.0 * PI * (f0 * t + 0.5 * k * t * t));
  }
  return y;
}

TEST(Spectrogram, LinearChirpTracksInstantaneousFrequencyWithinOneBin) {
  // f = 20 Hz + 60 Hz/s t over 6 s, Hann segments of 256 samples (bin 3.9 Hz). The sweep is
  // fast enough that dating a segment by its start instead of its centre (128 samples = 7.7 Hz
  // = 2 bins) fails, slow enough (15 Hz = 4 bins across a segment) that the smeared line's
  // maximum sits at the centre's frequency to about half a bin (symmetric window, linear sweep).
  const double f0 = 20.0;
  const double k = 60.0;
  const auto y = chirp(6000, f0, k);
  SpectrogramOptions options{.window_samples = 256, .hop_samples = 64, .window = WindowKind::hann};
  const auto s = compute_spectrogram(y, FS, options);
  ASSERT_EQ(s.time_s.size(), (6000u - 256u) / 64u + 1u);
  ASSERT_EQ(s.amplitude.size(), s.time_s.size());
  ASSERT_EQ(s.frequency_hz.size(), 129u);
  const double bin = FS / 256.0;
  EXPECT_DOUBLE_EQ(s.time_s[0], 128.0 / FS);  // periodic Hann: centre at sample L/2
  double worst_bins = 0.0;
  for (std::size_t i = 0; i < s.time_s.size(); ++i) {
    const auto& a = s.amplitude[i];
    ASSERT_EQ(a.size(), s.frequency_hz.size());
    const auto k_max = static_cast<std::size_t>(std::max_element(a.begin(), a.end()) - a.begin());
    const double error_bins = std::abs(s.frequency_hz[k_max] - (f0 + k * s.time_s[i])) / bin;
    worst_bins = std::max(worst_bins, error_bins);
    EXPECT_LE(error_bins, 1.0) << "segment " << i << " at t = " << s.time_s[i] << " s";
  }
  RecordProperty("chirp_worst_error_bins", sci(worst_bins));
}

// Parseval per segment s (length L, window w, single-sided A_k, Nyquist bin L/2, L even):
//   sum_{k<L} |X_k|^2 = L sum_n w_n^2 y_{s+n}^2,   |X_0| = A_0 S, |X_{L/2}| = A_{L/2} S,
//   |X_k| = |X_{L-k}| = A_k S / 2 otherwise (S = sum w), so
//   sum_n w_n^2 y_{s+n}^2 = S^2 / L (A_0^2 + 1/2 sum_{0<k<L/2} A_k^2 + A_{L/2}^2).
// Summed over segments every sample m is weighted by G(m) = sum_s w^2_{m - s hop}; wherever
// G is a constant C, the STFT energy S^2 / (L C) sum_s (...) equals sum_m y_m^2.
double stft_energy(const Spectrogram& s, std::size_t length, double window_sum, double overlap_weight) {
  double total = 0.0;
  for (const auto& a : s.amplitude) {
    double folded = a.front() * a.front() + a.back() * a.back();
    for (std::size_t k = 1; k + 1 < a.size(); ++k) folded += 0.5 * a[k] * a[k];
    total += folded;
  }
  return window_sum * window_sum / (static_cast<double>(length) * overlap_weight) * total;
}

// Nonzero samples only where every full overlap of segments covers them: L zeros at each end.
std::vector<double> guarded(std::vector<double> core, std::size_t guard) {
  std::vector<double> y(guard, 0.0);
  y.insert(y.end(), core.begin(), core.end());
  y.insert(y.end(), guard, 0.0);
  return y;
}

double energy(const std::vector<double>& y) {
  double e = 0.0;
  for (double v : y) e += v * v;
  return e;
}

TEST(Spectrogram, EnergyConsistentWithinOnePercentHannHalfOverlap) {
  // Periodic Hann, hop L/2: w is constant-overlap-add (w_n + w_{n+L/2} = 1), but w^2 is not:
  // G(m) = 1/2 + 1/2 cos^2(2 pi m / L), between 1/2 and 1. Its mean C = sum w^2 / hop
  // = (3L/8) / (L/2) = 3/4 is exact in expectation for white noise and, for a chirp, off by
  // only the beat of y^2 with cos(4 pi m / L), which averages out away from bin 1. Residual:
  // for noise ~ sqrt(2) x 0.18 / (0.75 sqrt(N)) = 0.2 % at N = 16000; 1 % (issue 3) holds it.
  const std::size_t length = 256;
  const double sum_w = length / 2.0;
  std::mt19937_64 rng(17);
  std::normal_distribution<double> normal(0.0, 1.5);
  std::vector<double> noise(16000);
  for (double& v : noise) v = normal(rng);
  const std::pair<const char*, std::vector<double>> cases[] = {{"noise", noise}, {"chirp", chirp(16000, 30.0, 20.0)}};
  for (const auto& [name, core] : cases) {
    const auto y = guarded(core, length);
    const auto s = compute_spectrogram(y, FS, {.window_samples = length, .hop_samples = length / 2});
    const double ratio = stft_energy(s, length, sum_w, 0.75) / energy(y);
    EXPECT_NEAR(ratio, 1.0, 0.01) << name;
    RecordProperty(std::string(name) + "_energy_ratio_minus_1", sci(ratio - 1.0));
  }
}

TEST(Spectrogram, EnergyExactWhenWindowSquaredOverlapAddsToConstant) {
  // Periodic Hann, hop L/4: the four shifts of w^2 = (1 - cos)^2 / 4 sum to exactly 3/2 (the
  // cosine terms cancel pairwise, cos^2 + sin^2 = 1), so Parseval holds to rounding for any
  // signal. Tolerance 1e-10: ~1e6 eps of FFT and summation rounding.
  const std::size_t length = 128;
  const auto y = guarded(chirp(5000, 10.0, 50.0), length);
  const auto s = compute_spectrogram(y, FS, {.window_samples = length, .hop_samples = length / 4});
  const double ratio = stft_energy(s, length, length / 2.0, 1.5) / energy(y);
  EXPECT_NEAR(ratio, 1.0, 1e-10);
  RecordProperty("quarter_hop_energy_ratio_minus_1", sci(ratio - 1.0));
}

TEST(Spectrogram, BadParametersAreInputErrors) {
  const std::vector<double> y(100, 1.0);
  EXPECT_THROW(compute_spectrogram(y, FS, {.window_samples = 101, .hop_samples = 10}), InputError);
  EXPECT_THROW(compute_spectrogram(y, FS, {.window_samples = 50, .hop_samples = 0}), InputError);
  EXPECT_THROW(compute_spectrogram(y, FS, {.window_samples = 0, .hop_samples = 1}), InputError);
  EXPECT_THROW(compute_spectrogram(y, 0.0, {.window_samples = 50, .hop_samples = 10}), InputError);
  // A window exactly as long as the signal is one segment, not an error.
  EXPECT_EQ(compute_spectrogram(y, FS, {.window_samples = 100, .hop_samples = 10}).time_s.size(), 1u);
}

}  // namespace
}  // namespace stengmc
