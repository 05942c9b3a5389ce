// The segment test of a residual (inverse/residual_segments.hpp), on white Gaussian noise of a
// known level drawn here: each segment's p-value is uniform (its sum is chi^2_L exactly when the
// level is right), Bonferroni's bound holds the worst segment's false alarms to their level,
// and a transient the global chi^2 dilutes below its bound stands out in its segment.
#include <gtest/gtest.h>

#include <algorithm>
#include <boost/random/normal_distribution.hpp>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "core/error.hpp"
#include "core/random_stream.hpp"
#include "inverse/noise_judge.hpp"
#include "inverse/residual_segments.hpp"

namespace stengmc {
namespace {

constexpr std::size_t SAMPLES = 10001;

std::vector<double> white_noise(double sigma_v, std::uint64_t seed) {
  RandomEngine engine = random_stream(seed, 0, StreamKind::noise, 3);
  boost::random::normal_distribution<double> normal(0.0, sigma_v);
  std::vector<double> x(SAMPLES);
  for (double& v : x) v = normal(engine);
  return x;
}

double ks_from_uniform(std::vector<double> p) {
  std::sort(p.begin(), p.end());
  const auto n = static_cast<double>(p.size());
  double d = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i)
    d = std::max({d, std::abs(p[i] - static_cast<double>(i) / n), std::abs(p[i] - static_cast<double>(i + 1) / n)});
  return d;
}

// One segment's p-value, from a residual that is zero outside it, is uniform (KS at 1 %); the
// worst of ten crosses alpha / 10 in at most a fraction alpha of the draws (Bonferroni), and
// not far fewer (ten independent segments: 1 - (1 - alpha/10)^10 = 0.096 at alpha = 0.1).
TEST(ResidualSegments, WhiteNoiseGivesUniformSegmentPValuesAndFewFalseAlarms) {
  constexpr int DRAWS = 400;
  const double sigma = 2e-3;
  std::vector<double> third;
  int alarms = 0;
  for (int d = 0; d < DRAWS; ++d) {
    const std::vector<double> x = white_noise(sigma, 100 + d);
    const WorstSegment worst = worst_residual_segment(x, sigma);
    ASSERT_EQ(worst.segments, RESIDUAL_SEGMENTS);
    if (worst.p_value < 0.1 / static_cast<double>(worst.segments)) ++alarms;
    std::vector<double> only(x.size(), 0.0);
    const std::size_t length = SAMPLES / RESIDUAL_SEGMENTS;
    std::copy(x.begin() + 2 * length, x.begin() + 3 * length, only.begin() + 2 * length);
    const WorstSegment one = worst_residual_segment(only, sigma);
    ASSERT_EQ(one.first_sample, 2 * length);
    third.push_back(one.p_value);
  }
  const double critical = 1.63 / std::sqrt(static_cast<double>(DRAWS));
  std::printf("KS distance of one segment's p from uniform %.3f (1 %% critical %.3f); alarms %d of %d\n", ks_from_uniform(third), critical,
              alarms, DRAWS);
  EXPECT_LT(ks_from_uniform(third), critical) << "a segment's p-value is not uniform: its law is off";
  EXPECT_LE(alarms, 40 + 3 * std::sqrt(400 * 0.1 * 0.9));
  EXPECT_GE(alarms, 38 - 3 * std::sqrt(400 * 0.1 * 0.9)) << "so conservative that it hears nothing";
}

// A ringing in the first microseconds (energy 0.03 M sigma^2:
// chi^2 / M 1.03, inside the global bound of 1.07) lifts the first tenth ~30 %: out far beyond
// 5 sigma. The same noise without it passes.
TEST(ResidualSegments, ATransientTheGlobalChiSquareDilutesStandsOutInItsSegment) {
  const double sigma = 2e-3;
  std::vector<double> x = white_noise(sigma, 7);
  // A breakaway-like transient: a 1 MHz ringing decaying with tau = 1 us, from t = 0 (100 MHz).
  double energy = 0.0;
  std::vector<double> burst(SAMPLES);
  for (std::size_t t = 0; t < SAMPLES; ++t) {
    const double time_s = static_cast<double>(t) * 1e-8;
    burst[t] = std::exp(-time_s / 1e-6) * std::sin(2.0 * std::numbers::pi * 1e6 * time_s);
    energy += burst[t] * burst[t];
  }
  const double scale = std::sqrt(0.03 * static_cast<double>(SAMPLES) * sigma * sigma / energy);
  double rss = 0.0;
  for (std::size_t t = 0; t < SAMPLES; ++t) x[t] += scale * burst[t], rss += x[t] * x[t];
  EXPECT_LT(rss / (sigma * sigma), fitting_chi2(SAMPLES)) << "the transient is not diluted: the test tests nothing";
  const WorstSegment worst = worst_residual_segment(x, sigma);
  EXPECT_EQ(worst.first_sample, 0u);
  EXPECT_LT(worst.p_value, bonferroni_p_bound(FITS_SIGMAS, worst.segments));
  const WorstSegment clean = worst_residual_segment(white_noise(sigma, 7), sigma);
  EXPECT_GE(clean.p_value, bonferroni_p_bound(FITS_SIGMAS, clean.segments));
}

TEST(ResidualSegments, RefusesANonPositiveLevelAndTooFewSamples) {
  EXPECT_THROW((void)worst_residual_segment(white_noise(1.0, 1), 0.0), Error);
  EXPECT_THROW((void)worst_residual_segment(std::vector<double>(5, 1.0), 1.0), Error);
}

}  // namespace
}  // namespace stengmc
