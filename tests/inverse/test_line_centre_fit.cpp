// The Whittle fit of a driven line's centre (inverse/line_centre_fit.hpp) on the process it
// assumes: a damped oscillator under white forcing (an AR(2) process whose poles are the
// oscillator's, e^{(-gamma +- i omega_d) dt}: its spectrum near omega_d is a Lorentzian of
// half-width gamma), in white measurement noise. Against the closed form: the centre's
// Cramer-Rao standard deviation sqrt(gamma / T) [rad/s].
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <vector>

#include "inverse/line_centre_fit.hpp"

namespace stengmc {
namespace {

constexpr double FS = 100e6;          // [Hz]
constexpr double GAMMA = 5e4;         // c / 2m with Table 1 values [1/s]
constexpr double F_LINE = 1.2328e6;   // damped frequency of k = 60 N/m, m = 1e-12 kg [Hz]

//! `samples` of the driven oscillator's response (unit forcing) plus white noise `snr_db`
//! below its power.
std::vector<double> driven_line(std::size_t samples, double snr_db, std::mt19937_64& rng) {
  const double dt = 1.0 / FS, r = std::exp(-GAMMA * dt), theta = 2.0 * std::numbers::pi * F_LINE * dt;
  const double a1 = 2.0 * r * std::cos(theta), a2 = -r * r;
  std::normal_distribution<double> unit(0.0, 1.0);
  std::vector<double> x(samples + 20000);  // 20000 samples (10 tau) of burn-in: stationary
  for (std::size_t n = 2; n < x.size(); ++n) x[n] = a1 * x[n - 1] + a2 * x[n - 2] + unit(rng);
  x.erase(x.begin(), x.begin() + 20000);
  double power = 0.0;
  for (double v : x) power += v * v / static_cast<double>(x.size());
  std::normal_distribution<double> noise(0.0, std::sqrt(power / std::pow(10.0, snr_db / 10.0)));
  for (double& v : x) v += noise(rng);
  return x;
}

// 200 realisations of 300 us at 25 dB: the fitted centres' 90 % intervals (curvature of the
// Whittle likelihood) cover the true centre in 0.85-0.95 of them (a binomial 90 % over 200
// lies there with probability 0.98), the standardised errors' mean square lies within the
// chi-square(200)/200 central 99.9 % (0.70-1.35), and each error bar is within 0.8-1.25 of the
// closed form sqrt(gamma / T) / 2 pi (2.05 kHz: 0.17 % of f, 0.33 % of k).
TEST(TrackingLineCentreFit, IntervalsCoverTheCentreAndMatchTheClosedFormBound) {
  const std::size_t samples = 30000;
  const double half_width_hz = GAMMA / (2.0 * std::numbers::pi);
  const double bound_hz = centre_standard_deviation_hz(half_width_hz, static_cast<double>(samples) / FS);
  EXPECT_NEAR(bound_hz, std::sqrt(GAMMA / 300e-6) / (2.0 * std::numbers::pi), 1e-9 * bound_hz);
  std::mt19937_64 rng(2026);
  std::size_t covered = 0, fits = 0;
  double sum_z2 = 0.0, smallest = 1e9, largest = 0.0;
  const int draws = 200;
  for (int draw = 0; draw < draws; ++draw) {
    const std::vector<double> v = driven_line(samples, 25.0, rng);
    // Started a half-width off, as a track's median window frequency would be.
    const double guess = F_LINE + half_width_hz;
    const LocalPeriodogram p = local_periodogram(v, FS, guess - 12.0 * half_width_hz, guess + 12.0 * half_width_hz);
    const LorentzianFit fit = fit_lorentzian(p, guess, half_width_hz);
    ASSERT_TRUE(fit.valid) << draw;
    ++fits;
    const double z = (fit.centre_hz - F_LINE) / fit.centre_se_hz;
    sum_z2 += z * z;
    if (std::abs(z) <= 1.6448536269514722) ++covered;
    smallest = std::min(smallest, fit.centre_se_hz / bound_hz);
    largest = std::max(largest, fit.centre_se_hz / bound_hz);
  }
  const double coverage = static_cast<double>(covered) / static_cast<double>(fits);
  const double mean_z2 = sum_z2 / static_cast<double>(fits);
  std::printf("  coverage %.3f, mean z^2 %.3f, se / bound in [%.3f, %.3f] (bound %.0f Hz)\n", coverage, mean_z2, smallest,
              largest, bound_hz);
  EXPECT_GE(coverage, 0.85);
  EXPECT_LE(coverage, 0.95);
  EXPECT_GE(mean_z2, 0.70);
  EXPECT_LE(mean_z2, 1.35);
  EXPECT_GE(smallest, 0.8);
  EXPECT_LE(largest, 1.25);
}

}  // namespace
}  // namespace stengmc
