// Amplitude spectrum, noise floor and peaks (MODEL.md §3) against closed forms: a pure
// sinusoid is one line of its own amplitude, Parseval for the rectangular window, the
// Rayleigh statistics of white noise.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <random>
#include <thread>
#include <vector>

#include "core/constants.hpp"
#include "core/error.hpp"
#include "spectral/amplitude_spectrum.hpp"
#include "spectral/peaks.hpp"

namespace stengmc {
namespace {

std::string sci(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", value);
  return text;
}

constexpr WindowKind ALL_WINDOWS[] = {WindowKind::rectangular, WindowKind::hann, WindowKind::blackman_harris};

std::vector<double> sine(std::size_t m, double fs, double f, double a, double phase) {
  std::vector<double> y(m);
  for (std::size_t n = 0; n < m; ++n) y[n] = a * std::sin(2.0 * PI * f * static_cast<double>(n) / fs + phase);
  return y;
}

std::vector<double> white_noise(std::size_t m, double sigma, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, sigma);
  std::vector<double> y(m);
  for (double& v : y) v = normal(rng);
  return y;
}

// A 2^14-sample sine near bin 2000: its negative-frequency image is ~4000 bins away, where
// even the rectangular window's side lobes (1 / (pi d)) are below 1e-4 of the line, and
// Hann's (1/d^3) below 1e-11; so 0.1 % and 1e-3 bin test the method, not the image.
constexpr std::size_t M = 16384;
constexpr double FS = 1000.0;  // [Hz]
constexpr double BIN = FS / M;
// These tests are about the amplitude and the refinement, not detection (noise-free, the
// floor is rounding or far leakage), so they take the strongest peak only.
const PeakOptions STRONGEST{.max_peaks = 1};

TEST(Spectrum, PureSineOnBinIsItsAmplitudeForEachWindow) {
  // On a bin, every periodic window's DFT has zeros at all other integer offsets, so A_k
  // is the amplitude itself up to FFT rounding; 0.1 % is the bound.
  const double f = 2000.0 * BIN;
  const auto y = sine(M, FS, f, 1.7, 0.3);
  for (WindowKind kind : ALL_WINDOWS) {
    SpectrumAnalyzer analyzer(M, kind);
    const auto s = analyzer.analyse(y, FS);
    EXPECT_NEAR(s.amplitude[2000], 1.7, 1e-3 * 1.7) << window_name(kind);
    const auto peaks = find_peaks(s, analyzer, y, FS, STRONGEST);
    ASSERT_EQ(peaks.size(), 1u) << window_name(kind);
    EXPECT_NEAR(peaks[0].amplitude, 1.7, 1e-3 * 1.7) << window_name(kind);
    EXPECT_NEAR(peaks[0].frequency_hz, f, 1e-3 * BIN) << window_name(kind);
  }
}

TEST(Spectrum, PureSineOffBinRefinedToAmplitudeAndFrequency) {
  // 0.37 bin off: A_k alone is scalloped (Hann loses ~5 %, rectangular ~20 %), so the
  // refinement on the windowed DTFT must recover 0.1 % in amplitude and 1e-3 bin (issue 3).
  const double f = 2000.37 * BIN;
  const auto y = sine(M, FS, f, 1.7, 1.1);
  for (WindowKind kind : ALL_WINDOWS) {
    SpectrumAnalyzer analyzer(M, kind);
    const auto s = analyzer.analyse(y, FS);
    EXPECT_GT(std::abs(s.amplitude[2000] - 1.7), 5e-3) << "scalloping should be visible: " << window_name(kind);
    const auto peaks = find_peaks(s, analyzer, y, FS, STRONGEST);
    ASSERT_EQ(peaks.size(), 1u) << window_name(kind);
    EXPECT_NEAR(peaks[0].amplitude, 1.7, 1e-3 * 1.7) << window_name(kind);
    EXPECT_NEAR(peaks[0].frequency_hz, f, 1e-3 * BIN) << window_name(kind);
    RecordProperty(std::string(window_name(kind)) + "_amplitude_rel_error",
                   sci(std::abs(peaks[0].amplitude / 1.7 - 1.0)));
    RecordProperty(std::string(window_name(kind)) + "_frequency_error_bins",
                   sci(std::abs(peaks[0].frequency_hz - f) / BIN));
  }
}

TEST(Spectrum, RectangularParsevalAndMean) {
  // Rectangular window, sum w = M: A_0 = |mean| and, from Parseval sum_k |X_k|^2 = M sum y^2
  // folded onto the single-sided bins, mean(y^2) = A_0^2 + 1/2 sum_{0<k<M/2} A_k^2 + A_{M/2}^2
  // (last term only for even M). Exact algebra, so only FFT rounding (~eps log M) remains: 1e-12.
  for (std::size_t m : {std::size_t{1000}, std::size_t{1001}}) {
    auto y = white_noise(m, 2.0, 7);
    for (double& v : y) v += 0.75;
    double mean = 0.0;
    double mean_square = 0.0;
    for (double v : y) {
      mean += v / static_cast<double>(m);
      mean_square += v * v / static_cast<double>(m);
    }
    SpectrumAnalyzer analyzer(m, WindowKind::rectangular);
    const auto s = analyzer.analyse(y, 10.0);
    EXPECT_NEAR(s.amplitude[0], std::abs(mean), 1e-12);
    double folded = s.amplitude[0] * s.amplitude[0];
    for (std::size_t k = 1; k < s.amplitude.size(); ++k) {
      const bool nyquist = 2 * k == m;
      folded += (nyquist ? 1.0 : 0.5) * s.amplitude[k] * s.amplitude[k];
    }
    EXPECT_NEAR(folded, mean_square, 1e-12 * mean_square) << "M = " << m;
    EXPECT_DOUBLE_EQ(s.bin_width_hz, 10.0 / static_cast<double>(m));
  }
}

TEST(Spectrum, DcAndNyquistAreNotDoubled) {
  // y = 3 + 2 cos(pi n): the offset and the Nyquist line each have one bin, no mirror image.
  std::vector<double> y(64);
  for (std::size_t n = 0; n < y.size(); ++n) y[n] = 3.0 + 2.0 * (n % 2 == 0 ? 1.0 : -1.0);
  SpectrumAnalyzer analyzer(64, WindowKind::hann);
  const auto s = analyzer.analyse(y, 1.0);
  ASSERT_EQ(s.amplitude.size(), 33u);
  EXPECT_NEAR(s.amplitude[0], 3.0, 1e-12);
  EXPECT_NEAR(s.amplitude[32], 2.0, 1e-12);
  EXPECT_NEAR(s.amplitude[10], 0.0, 1e-12);
}

TEST(Spectrum, WhiteNoiseFloorWithinTenPercent) {
  // Truth: A_k = 2 |X_k| / sum w with E|X_k|^2 = sigma^2 sum w^2, so rms = 2 sigma sqrt(sum w^2) / sum w.
  // The sample median of K Rayleigh values has relative standard error 0.72 / sqrt(K)
  // (1 / (2 f(m) sqrt(K)) over m): 0.8 % for K = 8192 bins, a little more because windows
  // correlate neighbouring bins (measured rms 0.8-1.1 %, worst 3.5 % over 300 seeds). 10 %
  // (issue 3) is > 9 of those, yet a missing sqrt(ln 2) (+20 %), or a mean that the strong
  // line below inflates, fails it.
  const double sigma = 0.3;
  auto y = white_noise(M, sigma, 2024);
  // A strong line must not raise the floor. On a bin, so its leakage is nil for every window
  // (off-bin, the rectangular window's 1/(pi d) leakage would lift the median: see README).
  const auto line = sine(M, FS, 2021.0 * BIN, 50.0, 0.0);
  for (std::size_t n = 0; n < M; ++n) y[n] += line[n];
  for (WindowKind kind : ALL_WINDOWS) {
    SpectrumAnalyzer analyzer(M, kind);
    double sum_w = 0.0;
    double sum_w2 = 0.0;
    for (double w : analyzer.window()) {
      sum_w += w;
      sum_w2 += w * w;
    }
    const double truth = 2.0 * sigma * std::sqrt(sum_w2) / sum_w;
    const double floor = noise_floor(analyzer.analyse(y, FS));
    EXPECT_NEAR(floor, truth, 0.10 * truth) << window_name(kind);
    RecordProperty(std::string(window_name(kind)) + "_floor_rel_error", sci(floor / truth - 1.0));
  }
}

TEST(Peaks, ThreeSinesInNoiseGiveExactlyThreePeaks) {
  // Hann floor 2 sigma sqrt(sum w^2) / sum w = 4 sigma sqrt(3/8) / sqrt(M) = 0.0057 at
  // sigma = 0.3: amplitudes 1, 0.3, 0.1 are 174, 52 and 17 x the floor, above the default 10x;
  // noise maxima (Rayleigh, P(A > 10 rms) = e^-100) and Hann side lobes (-31 dB of 1 = 4.7x)
  // are not. Noise perturbs each refined line: amplitude rms sigma sqrt(sum w^2) / sum w =
  // sigma sqrt(3 / M) = 0.0041 for every line; frequency rms ~ 0.03 bin for the weakest
  // (both measured over 300 seeds; Cramer-Rao with Hann's 1.5 bins noise bandwidth predicts
  // 0.016 bin). Tolerances are ~5 rms: 0.02 absolute in amplitude, 0.15 bin in frequency.
  const double sigma = 0.3;
  auto y = white_noise(M, sigma, 99);
  const double freqs[] = {50.13, 180.6, 333.3};
  const double amps[] = {1.0, 0.3, 0.1};
  for (int i = 0; i < 3; ++i) {
    const auto s = sine(M, FS, freqs[i], amps[i], 0.5 * i);
    for (std::size_t n = 0; n < M; ++n) y[n] += s[n];
  }
  SpectrumAnalyzer analyzer(M, WindowKind::hann);
  const auto spectrum = analyzer.analyse(y, FS);
  const auto peaks = find_peaks(spectrum, analyzer, y, FS, PeakOptions{});
  ASSERT_EQ(peaks.size(), 3u);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(peaks[i].frequency_hz, freqs[i], 0.15 * BIN);
    EXPECT_NEAR(peaks[i].amplitude, amps[i], 0.02);
    RecordProperty("line" + std::to_string(i) + "_error_bins", sci((peaks[i].frequency_hz - freqs[i]) / BIN));
    RecordProperty("line" + std::to_string(i) + "_amplitude_rel_error", sci(peaks[i].amplitude / amps[i] - 1.0));
  }

  // The noise does have local maxima with some prominence: at threshold 1x the floor
  // they are reported (so the default's silence is the threshold's doing, not an empty search).
  PeakOptions loose;
  loose.prominence_over_floor = 1.0;
  loose.max_peaks = 20;
  EXPECT_EQ(find_peaks(spectrum, analyzer, y, FS, loose).size(), 20u);
}

TEST(Peaks, MinSeparationDropsTheWeakerOfTwoClosePeaks) {
  // Two resolved lines 8 bins apart (Hann main lobe +-2 bins): both found without a minimum
  // separation; with min_separation = 10 bins only the stronger remains.
  const double f1 = 2000.2 * BIN;
  const double f2 = 2008.6 * BIN;
  auto y = sine(M, FS, f1, 1.0, 0.0);
  const auto weak = sine(M, FS, f2, 0.4, 0.7);
  const auto noise = white_noise(M, 0.3, 11);  // sets a floor the Hann side lobes stay under
  for (std::size_t n = 0; n < M; ++n) y[n] += weak[n] + noise[n];
  SpectrumAnalyzer analyzer(M, WindowKind::hann);
  const auto s = analyzer.analyse(y, FS);
  PeakOptions options;
  ASSERT_EQ(find_peaks(s, analyzer, y, FS, options).size(), 2u);
  options.min_separation_hz = 10.0 * BIN;
  const auto peaks = find_peaks(s, analyzer, y, FS, options);
  ASSERT_EQ(peaks.size(), 1u);
  EXPECT_NEAR(peaks[0].frequency_hz, f1, 0.01 * BIN);
}

TEST(Peaks, SideLobesOfNoiseFreeLinesAreNotPeaks) {
  // Noise-free, the floor is far leakage (1e-8 of the lines for Blackman-Harris) and the side
  // lobes near each line are local maxima far above 10x it; Blackman-Harris sampled on bins,
  // and any window zero padded, shows them. The leakage test (a peak must exceed twice what
  // the stronger lines' window responses put there) leaves the four lines. Without it
  // (leakage_margin = 0) the side lobes come back, so this test sees the guard work.
  const std::size_t m = 10000;
  const double fs = 1e4;  // [Hz]
  const double freqs[] = {312.3, 455.1, 700.7, 1021.9};
  const double amps[] = {1.0, 0.5, 0.8, 0.3};
  std::vector<double> y(m, 0.0);
  for (int i = 0; i < 4; ++i) {
    const auto s = sine(m, fs, freqs[i], amps[i], i);
    for (std::size_t n = 0; n < m; ++n) y[n] += s[n];
  }
  for (auto [kind, pad] : {std::pair{WindowKind::blackman_harris, 1}, std::pair{WindowKind::hann, 4}}) {
    SpectrumAnalyzer analyzer(m, kind, static_cast<std::size_t>(pad));
    const auto spectrum = analyzer.analyse(y, fs);
    const auto peaks = find_peaks(spectrum, analyzer, y, fs, PeakOptions{});
    ASSERT_EQ(peaks.size(), 4u) << window_name(kind) << " pad " << pad;
    for (int i = 0; i < 4; ++i) EXPECT_NEAR(peaks[i].frequency_hz, freqs[i], 1e-3) << window_name(kind);
    PeakOptions unguarded;
    unguarded.leakage_margin = 0.0;
    unguarded.max_peaks = 5;  // a fifth peak is a side lobe; refining all of them is slow
    EXPECT_EQ(find_peaks(spectrum, analyzer, y, fs, unguarded).size(), 5u) << window_name(kind);
  }
}

TEST(Spectrum, ZeroPaddingSamplesTheWindowedDtft) {
  // A padded FFT evaluates the same windowed DTFT on a finer grid, so A_k (0 < k < N/2)
  // equals amplitude_at(k fs / N): two independent computations (FFT vs direct sum) of one
  // quantity. fs = 512 Hz and N = 4096 make every f_k and f_k / fs exact binary fractions;
  // otherwise the ~1e-16 rounding of the frequency itself, times the DTFT's slope, moves
  // the weakest bins by ~3e-12 relative (measured), which is not an error of either method.
  // 1e-12 relative then allows ~1e4 eps; measured ~1e-13.
  const std::size_t m = 1024;
  const double fs = 512.0;  // [Hz]
  auto y = white_noise(m, 1.0, 5);
  const auto line = sine(m, fs, 31.7, 2.0, 0.2);
  for (std::size_t n = 0; n < m; ++n) y[n] += line[n];
  for (WindowKind kind : ALL_WINDOWS) {
    SpectrumAnalyzer analyzer(m, kind, 4);
    const auto s = analyzer.analyse(y, fs);
    ASSERT_EQ(s.amplitude.size(), 2049u);
    EXPECT_DOUBLE_EQ(s.bin_width_hz, fs / 4096.0);
    EXPECT_DOUBLE_EQ(s.resolution_hz, fs / 1024.0);
    double worst = 0.0;
    for (std::size_t k = 1; k + 1 < s.amplitude.size(); ++k) {
      const double direct = analyzer.amplitude_at(y, fs, s.frequency_hz[k]);
      worst = std::max(worst, std::abs(direct - s.amplitude[k]) / s.amplitude[k]);
    }
    EXPECT_LT(worst, 1e-12) << window_name(kind);
    RecordProperty(std::string(window_name(kind)) + "_padding_worst_rel", sci(worst));
  }
}

TEST(Spectrum, ClosedFormWindowResponseIsTheWindowsDtft) {
  // window_response (Dirichlet kernels) against the direct sum amplitude_at(ones) / 2: two
  // computations of |W(f)| / W(0); 1e-12 absolute (W(0) = 1) covers the sin(pi x) rounding
  // at x up to M/2 bins (~x eps). Offsets span the main lobe, side lobes and the far range.
  for (std::size_t m : {std::size_t{7}, std::size_t{1000}, std::size_t{1001}}) {
    const std::vector<double> ones(m, 1.0);
    for (WindowKind kind : ALL_WINDOWS) {
      SpectrumAnalyzer analyzer(m, kind);
      for (double bins : {0.0, 0.25, 1.0, 1.5, 2.5, 3.0, 3.7, 10.2, 0.3 * static_cast<double>(m), 0.5 * static_cast<double>(m)}) {
        const double f = bins * 50.0 / static_cast<double>(m);  // fs = 50 Hz
        EXPECT_NEAR(analyzer.window_response(f, 50.0), 0.5 * analyzer.amplitude_at(ones, 50.0, f), 1e-12)
            << window_name(kind) << " M = " << m << " offset " << bins << " bins";
      }
    }
  }
}

TEST(Spectrum, AnalyzersBuiltOnManyThreadsGiveIdenticalSpectra) {
  // FFTW's planner is not thread-safe; the analyzer serialises planning behind a mutex. Many
  // threads making and dropping analyzers at once must neither crash nor change a bit of the
  // result (FFTW_ESTIMATE plans are deterministic): compared bit for bit with one thread.
  const auto y = white_noise(3000, 1.0, 3);
  SpectrumAnalyzer reference_analyzer(3000, WindowKind::hann, 2);
  const auto reference = reference_analyzer.analyse(y, 1.0).amplitude;
  std::vector<int> identical(8, 0);
  std::vector<std::thread> threads;
  for (std::size_t t = 0; t < identical.size(); ++t) {
    threads.emplace_back([&, t] {
      bool same = true;
      for (int repeat = 0; repeat < 20; ++repeat) {
        SpectrumAnalyzer other(1000 + t + static_cast<std::size_t>(repeat), WindowKind::blackman_harris);  // other plans
        SpectrumAnalyzer analyzer(3000, WindowKind::hann, 2);
        same = same && analyzer.analyse(y, 1.0).amplitude == reference;
      }
      identical[t] = same ? 1 : 0;
    });
  }
  for (auto& thread : threads) thread.join();
  for (int same : identical) EXPECT_EQ(same, 1);
}

TEST(Spectrum, BadParametersAreInputErrors) {
  EXPECT_THROW(SpectrumAnalyzer(0, WindowKind::hann), InputError);
  EXPECT_THROW(SpectrumAnalyzer(16, WindowKind::hann, 0), InputError);
  SpectrumAnalyzer analyzer(16, WindowKind::hann);
  const std::vector<double> short_signal(8, 1.0);
  const std::vector<double> signal(16, 1.0);
  EXPECT_THROW((void)analyzer.analyse(short_signal, 1.0), InputError);
  EXPECT_THROW((void)analyzer.analyse(signal, 0.0), InputError);
  EXPECT_THROW((void)analyzer.amplitude_at(signal, 1.0, std::nan("")), InputError);
  EXPECT_THROW(parse_window("hamming", "study.toml:3: spectrum.window"), InputError);
  EXPECT_EQ(parse_window("blackman_harris", "x"), WindowKind::blackman_harris);
}

}  // namespace
}  // namespace stengmc
