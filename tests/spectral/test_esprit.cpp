// High-resolution line estimation (ESPRIT): exact on noiseless exponential models, resolves
// lines closer than 1/T where FFT peaks merge, model orders from MDL / AIC / ESTER.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <numbers>
#include <random>
#include <vector>

#include "core/error.hpp"
#include "spectral/amplitude_spectrum.hpp"
#include "spectral/esprit.hpp"
#include "spectral/peaks.hpp"

namespace stengmc {
namespace {

constexpr double PI = std::numbers::pi;

//! n samples at `rate` of sum a e^{-d t} cos(2 pi f t + phi), plus white Gaussian noise.
std::vector<double> synthesize(const std::vector<Line>& lines, std::size_t n, double rate, double noise_rms = 0.0,
                               std::uint64_t seed = 0) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, 1.0);
  std::vector<double> y(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) / rate;
    for (const Line& l : lines) y[i] += l.amplitude * std::exp(-l.damping_per_s * t) * std::cos(2 * PI * l.frequency_hz * t + l.phase_rad);
    if (noise_rms > 0.0) y[i] += noise_rms * noise(rng);
  }
  return y;
}

EspritOptions with_criterion(OrderCriterion c) {
  EspritOptions o;
  o.criterion = c;
  return o;
}

TEST(Esprit, ExactOnNoiselessDampedLinesWithEveryCriterion) {
  // The signal is exactly the model, so only rounding separates the estimates from the
  // truth: measured <= 3e-13 from ESPRIT alone (the Gram matrix squares the condition
  // number), ~1e-15 after the refinement. 1e-8 relative (and 1e-8 rad for phases) leaves a
  // wide margin yet fails on any modelling error (a wrong sign, a missing pair, a biased fit).
  const std::vector<Line> truth = {{0.8e6, 1.0, 2e4, 0.3}, {1.1e6, 0.5, 5e4, -1.2}, {2.3e6, 0.25, 1e5, 2.0}};
  const double rate = 10e6;
  const auto y = synthesize(truth, 300, rate);
  for (const auto criterion : {OrderCriterion::mdl, OrderCriterion::aic, OrderCriterion::ester}) {
    SCOPED_TRACE(std::string(order_criterion_name(criterion)));
    const auto lines = estimate_lines(y, rate, with_criterion(criterion));
    ASSERT_EQ(lines.size(), truth.size());
    for (std::size_t i = 0; i < truth.size(); ++i) {
      EXPECT_NEAR(lines[i].frequency_hz / truth[i].frequency_hz, 1.0, 1e-8);
      EXPECT_NEAR(lines[i].damping_per_s / truth[i].damping_per_s, 1.0, 1e-8);
      EXPECT_NEAR(lines[i].amplitude / truth[i].amplitude, 1.0, 1e-8);
      EXPECT_NEAR(lines[i].phase_rad, truth[i].phase_rad, 1e-8);
    }
  }
  EspritOptions fixed;
  fixed.fixed_lines = 3;
  EXPECT_EQ(estimate_lines(y, rate, fixed).size(), 3u);
}

// Two equal lines 0.6/T apart, 40 dB SNR (total signal power A^2 over noise variance).
struct CloseLinesResult {
  std::size_t fft_peaks = 0;
  std::size_t esprit_lines = 0;
  double worst_error_over_spacing = 0.0;  // max over the true lines of |nearest estimate - f| / spacing
  double largest_extra_amplitude = 0.0;   // of lines beyond the two nearest the truth
};

CloseLinesResult close_lines(std::size_t n, std::uint64_t seed, bool random_phases) {
  const double rate = 100e6;
  const double duration = static_cast<double>(n) / rate;
  const double spacing = 0.6 / duration;
  const double f1 = 1.0123e6;  // off-bin
  std::mt19937_64 rng(seed ^ 0x9e3779b97f4a7c15ULL);
  std::uniform_real_distribution<double> angle(-PI, PI);
  std::vector<Line> truth = {{f1, 1.0, 0.0, 0.0}, {f1 + spacing, 1.0, 0.0, 0.0}};
  for (Line& l : truth)  // in phase at mid-record unless random: the FFT's merging case
    l.phase_rad = random_phases ? angle(rng) : -PI * l.frequency_hz * duration;
  const auto y = synthesize(truth, n, rate, std::sqrt(1.0 / 1e4), seed);

  CloseLinesResult r;
  SpectrumAnalyzer analyzer(n, WindowKind::hann);
  const auto spectrum = analyzer.analyse(y, rate);
  r.fft_peaks = find_peaks(spectrum, analyzer, y, rate, PeakOptions{}).size();
  auto lines = estimate_lines(y, rate, EspritOptions{});
  r.esprit_lines = lines.size();
  for (const Line& t : truth) {
    if (lines.empty()) return {r.fft_peaks, 0, INFINITY, 0.0};
    const auto nearest = std::min_element(lines.begin(), lines.end(), [&](const Line& a, const Line& b) {
      return std::abs(a.frequency_hz - t.frequency_hz) < std::abs(b.frequency_hz - t.frequency_hz);
    });
    r.worst_error_over_spacing = std::max(r.worst_error_over_spacing, std::abs(nearest->frequency_hz - t.frequency_hz) / spacing);
    lines.erase(nearest);
  }
  for (const Line& extra : lines) r.largest_extra_amplitude = std::max(r.largest_extra_amplitude, extra.amplitude);
  return r;
}

// Issue 3's must-show. The Hann main lobe is 4/T wide, so lines 0.6/T apart in phase make
// one FFT peak; ESPRIT must find two, each within 1 % of the spacing. 1 % is ~3x the
// worst error seen over 100 seeds at N = 4096 (0.37 %) and ~1.2x at N = 1000 (0.83 % over
// 300 seeds: there the nonlinear refinement is at the Cramér–Rao level, so 1 % is tight
// by the physics, not by the code). (In antiphase the FFT shows two lobes ~1/T either
// side of the pair, both misplaced; the random-phase test covers ESPRIT there.)
void check_close_lines(std::size_t n, bool random_phases, std::size_t allowed_extra) {
  double worst = 0.0, extra_amplitude = 0.0;
  std::size_t with_extra = 0;
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    const auto r = close_lines(n, seed, random_phases);
    if (!random_phases) {
      EXPECT_EQ(r.fft_peaks, 1u) << "N " << n << " seed " << seed;
    }
    EXPECT_GE(r.esprit_lines, 2u) << "N " << n << " seed " << seed;
    EXPECT_LE(r.worst_error_over_spacing, 0.01) << "N " << n << " seed " << seed;
    // An extra line from an over-estimated order must be noise-sized (noise rms 0.01).
    EXPECT_LE(r.largest_extra_amplitude, 0.01) << "N " << n << " seed " << seed;
    with_extra += r.esprit_lines > 2 ? 1 : 0;
    worst = std::max(worst, r.worst_error_over_spacing);
    extra_amplitude = std::max(extra_amplitude, r.largest_extra_amplitude);
  }
  EXPECT_LE(with_extra, allowed_extra) << "N " << n;
  std::cout << "[ close lines ] N = " << n << (random_phases ? ", random phases" : ", in phase")
            << ": worst |error| / spacing over 20 seeds = " << worst << ", seeds with an extra line " << with_extra
            << " (largest amplitude " << extra_amplitude << ")\n";
}

TEST(Esprit, ResolvesTwoLinesCloserThanOneOverTWhereFftFindsOne) {
  // N = 4096 is the default analysis length (41 us at 100 MHz, like Fig. 6), L capped at
  // 256: all 20 seeds give exactly two lines.
  check_close_lines(4096, false, 0);
  // N = 1000, L = 256 ~ N/4: the Hankel columns overlap heavily (L/M = 0.34), the noise
  // eigenvalues spread more than MDL's independent-snapshot model allows, and MDL adds a
  // noise-sized line in 2 of 300 seeds (one of them, seed 18, is among these 20). The two
  // true lines are still resolved within 1 %, so one such seed is allowed.
  check_close_lines(1000, false, 1);
}

TEST(Esprit, ResolvesTwoCloseLinesWhateverTheirPhases) {
  // The Hankel signal subspace does not depend on the phases; neither must the result.
  check_close_lines(4096, true, 0);
  check_close_lines(1000, true, 1);
}

// Fig. 6-like: the four Table 1 lines with Model 2's damping c / 2m = 5e4 /s, sampled at
// 100 MHz for 50 us (5000 samples; the default analyses the first 4096).
std::vector<Line> fig6_lines() {
  return {{0.796e6, 1.0, 5e4, 0.4}, {1.125e6, 0.8, 5e4, -2.0}, {1.592e6, 0.6, 5e4, 1.1}, {1.981e6, 0.5, 5e4, 2.7}};
}

TEST(Esprit, MdlAndEsterFindTheFourFig6LinesInNoise) {
  // Noise rms 0.1: per-line SNR 17 to 11 dB at the start, decaying by e^-2 in amplitude over
  // the record. The lines are ~14/T apart, so the question is the order. Frequencies are
  // checked to 0.1 %: the observed scatter is ~1e-4 relative (std over 200 seeds, worst
  // 3e-4), so ~10 sigma, and 20x inside the 2 % identification tolerance. (AIC is not
  // asked: on Hankel data it over-estimates the order, see esprit.cpp.)
  const auto truth = fig6_lines();
  for (const auto criterion : {OrderCriterion::mdl, OrderCriterion::ester}) {
    double worst_relative = 0.0;
    for (std::uint64_t seed = 1; seed <= 10; ++seed) {
      const auto y = synthesize(truth, 5000, 100e6, 0.1, seed);
      const auto lines = estimate_lines(y, 100e6, with_criterion(criterion));
      ASSERT_EQ(lines.size(), 4u) << order_criterion_name(criterion) << " seed " << seed;
      for (std::size_t i = 0; i < 4; ++i) {
        const double relative = std::abs(lines[i].frequency_hz / truth[i].frequency_hz - 1.0);
        EXPECT_LE(relative, 1e-3) << order_criterion_name(criterion) << " seed " << seed << " line " << i;
        worst_relative = std::max(worst_relative, relative);
      }
    }
    std::cout << "[ fig6 " << order_criterion_name(criterion) << " ] worst relative frequency error over 10 seeds = "
              << worst_relative << "\n";
  }
}

TEST(Esprit, LongSignalIsCutToMaxSamplesAndStaysFast) {
  // 10^4 samples with default options: the first 4096 are analysed (100 MHz, 41 us).
  const auto truth = fig6_lines();
  const auto y = synthesize(truth, 10000, 100e6, 0.1, 7);
  const auto start = std::chrono::steady_clock::now();
  constexpr int REPEATS = 10;
  std::vector<Line> lines;
  for (int r = 0; r < REPEATS; ++r) lines = estimate_lines(y, 100e6, EspritOptions{});
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() / REPEATS;
  std::cout << "[ timing ] estimate_lines, 10^4 samples, 4 lines, defaults: " << seconds * 1e3 << " ms\n";
  ASSERT_EQ(lines.size(), 4u);
  // Amplitudes are referred to the first sample, as the truth's; a block taken elsewhere
  // would be off by e^{-d t0}. Their scatter is ~sigma sqrt(2 / N_eff) ~ 0.003; 0.05 = 15x.
  for (std::size_t i = 0; i < 4; ++i) EXPECT_NEAR(lines[i].amplitude, truth[i].amplitude, 0.05);
}

TEST(Esprit, DcOffsetIsARealPoleAndMinFrequencyDropsIt) {
  // A DC offset is one real pole, not a pair: the line count stays right and the offset
  // is reported as a 0 Hz line of its size until min_frequency_hz removes it. Noiseless,
  // so 1e-8 as in the exact test.
  auto y = synthesize({{1.0e6, 1.0, 0.0, 0.5}}, 200, 10e6);
  for (double& v : y) v += 0.3;
  const auto lines = estimate_lines(y, 10e6, EspritOptions{});
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_NEAR(lines[0].frequency_hz, 0.0, 1e-6);
  EXPECT_NEAR(lines[0].amplitude, 0.3, 1e-8);
  EXPECT_NEAR(lines[1].frequency_hz / 1.0e6, 1.0, 1e-8);
  EspritOptions above_dc;
  above_dc.min_frequency_hz = 1e3;
  ASSERT_EQ(estimate_lines(y, 10e6, above_dc).size(), 1u);
}

TEST(Esprit, ZeroSignalHasNoLineAndBadInputIsRejected) {
  const std::vector<double> zeros(100, 0.0);
  EXPECT_TRUE(estimate_lines(zeros, 1e6, EspritOptions{}).empty());
  const auto y = synthesize({{1.0e5, 1.0, 0.0, 0.0}}, 100, 1e6);
  EXPECT_THROW(estimate_lines(y, 0.0, EspritOptions{}), InputError);
  EXPECT_THROW(estimate_lines(std::vector<double>(5, 1.0), 1e6, EspritOptions{}), InputError);
  auto bad = y;
  bad[3] = std::nan("");
  EXPECT_THROW(estimate_lines(bad, 1e6, EspritOptions{}), InputError);
  EspritOptions too_many;
  too_many.fixed_lines = 20;  // 100 samples give L = 33 rows: at most 15 lines
  EXPECT_THROW(estimate_lines(y, 1e6, too_many), InputError);
  EXPECT_THROW(parse_order_criterion("bic", "[spectrum] order_criterion"), InputError);
  EXPECT_EQ(parse_order_criterion("ester", "x"), OrderCriterion::ester);
}

}  // namespace
}  // namespace stengmc
