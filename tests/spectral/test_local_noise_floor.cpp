// The local noise floor and the band limit of the peak finder: on noise whose level changes
// across the band (white plus differenced white noise, whose spectrum is known in closed
// form), the running median follows the level, and a peak search with a local floor finds a
// weak line in the quiet part that one global floor hides, while a band limit drops a strong
// line above it.
#include <gtest/gtest.h>

#include <boost/random/normal_distribution.hpp>
#include <cmath>
#include <vector>

#include "core/random_stream.hpp"
#include "spectral/amplitude_spectrum.hpp"
#include "spectral/local_noise_floor.hpp"
#include "spectral/peaks.hpp"

namespace stengmc {
namespace {

constexpr double PI_ = 3.14159265358979323846;
constexpr double QUIET = 1e-4, LOUD = 1e-2;

//! White noise of sigma QUIET plus the first difference of white noise of sigma LOUD (a
//! high-pass: power 4 sin^2(pi f / fs) LOUD^2 at f), plus the given lines.
std::vector<double> signal(std::size_t n, double rate, const std::vector<std::pair<double, double>>& lines) {
  RandomEngine engine = random_stream(4, 0, StreamKind::noise);
  boost::random::normal_distribution<double> normal(0.0, 1.0);
  std::vector<double> x(n);
  double previous = LOUD * normal(engine);
  for (double& v : x) {
    const double w = LOUD * normal(engine);
    v = QUIET * normal(engine) + (w - previous);
    previous = w;
  }
  for (const auto& [f, a] : lines)
    for (std::size_t m = 0; m < n; ++m) x[m] += a * std::sin(2.0 * PI_ * f * static_cast<double>(m) / rate);
  return x;
}

//! The rms amplitude a bin of this noise has at f (noise_floor's white-noise formula,
//! 2 sigma sqrt(sum w^2) / sum w, with the local power).
double expected_floor(const SpectrumAnalyzer& analyzer, double f, double rate) {
  double sum = 0.0, squares = 0.0;
  for (double w : analyzer.window()) sum += w, squares += w * w;
  const double power = QUIET * QUIET + 4.0 * std::pow(std::sin(PI_ * f / rate), 2) * LOUD * LOUD;
  return 2.0 * std::sqrt(power * squares) / sum;
}

TEST(LocalNoiseFloor, FollowsNoiseWhoseLevelChangesAcrossTheBand) {
  const std::size_t n = 8192;
  const double rate = 1e6;
  SpectrumAnalyzer analyzer(n, WindowKind::hann);
  const AmplitudeSpectrum s = analyzer.analyse(signal(n, rate, {}), rate);
  const std::vector<double> floor = local_noise_floor(s, 20e3);
  const double global = noise_floor(s);
  // A 20 kHz window holds ~160 bins: its median has a relative sd of ~5 %, and the level
  // changes by at most ~6 % across it above 50 kHz: 20 % is 3 sd plus the slope.
  for (std::size_t k = 1; k < s.frequency_hz.size(); ++k) {
    const double f = s.frequency_hz[k];
    if (f < 50e3 || f > 480e3) continue;
    EXPECT_NEAR(floor[k] / expected_floor(analyzer, f, rate), 1.0, 0.2) << f;
  }
  // One global floor is off by a factor of several at both ends of that range.
  EXPECT_GT(global / expected_floor(analyzer, 50e3, rate), 2.0);
  EXPECT_LT(global / expected_floor(analyzer, 480e3, rate), 0.8);
}

TEST(LocalNoiseFloor, FindsAWeakLineTheGlobalFloorHidesAndHonoursTheBandLimit) {
  const std::size_t n = 8192;
  const double rate = 1e6;
  SpectrumAnalyzer analyzer(n, WindowKind::hann);
  // A weak line at 40 kHz where the noise is quiet (~20 x the local floor there, ~1/3 of the
  // global one), a strong one at 400 kHz.
  const double weak = 20.0 * expected_floor(analyzer, 40e3, rate);
  const std::vector<double> x = signal(n, rate, {{40.3e3, weak}, {400.7e3, 0.5}});
  const AmplitudeSpectrum s = analyzer.analyse(x, rate);
  PeakOptions global;
  global.prominence_over_floor = 10.0;
  PeakOptions local = global;
  local.floor_window_hz = 20e3;
  auto has = [](const std::vector<Peak>& peaks, double f) {
    for (const Peak& p : peaks)
      if (std::abs(p.frequency_hz - f) < 1e3) return true;
    return false;
  };
  const std::vector<Peak> with_global = find_peaks(s, analyzer, x, rate, global);
  const std::vector<Peak> with_local = find_peaks(s, analyzer, x, rate, local);
  EXPECT_FALSE(has(with_global, 40.3e3)) << "the global median, raised by the loud part, should hide the weak line";
  EXPECT_TRUE(has(with_local, 40.3e3));
  EXPECT_TRUE(has(with_local, 400.7e3));
  local.max_frequency_hz = 300e3;
  const std::vector<Peak> banded = find_peaks(s, analyzer, x, rate, local);
  EXPECT_TRUE(has(banded, 40.3e3));
  for (const Peak& p : banded) EXPECT_LE(p.frequency_hz, 300e3);
}

// A sweep of thresholds over one spectrum sharing its floor and refinements (the inverse's
// naive counter) must give bitwise the peaks separate searches give, also when the floor
// window changes between calls (the shared floor must then be recomputed).
TEST(PeakSearchShared, GivesBitwiseTheLinesOfSeparateSearches) {
  const std::size_t n = 8192;
  const double rate = 1e6;
  SpectrumAnalyzer analyzer(n, WindowKind::hann);
  const double weak = 20.0 * expected_floor(analyzer, 40e3, rate);
  const std::vector<double> x =
      signal(n, rate, {{40.3e3, weak}, {97.1e3, 3.0 * weak}, {120.4e3, 0.02}, {400.7e3, 0.5}, {402.9e3, 0.05}});
  const AmplitudeSpectrum s = analyzer.analyse(x, rate);
  PeakSearchShared shared;
  std::size_t compared = 0;
  for (double window_hz : {20e3, 0.0, 50e3}) {
    for (double threshold : {1.5, 3.0, 10.0, 30.0}) {
      PeakOptions options;
      options.prominence_over_floor = threshold;
      options.floor_window_hz = window_hz;
      const std::vector<Peak> alone = find_peaks(s, analyzer, x, rate, options);
      const std::vector<Peak> reused = find_peaks(s, analyzer, x, rate, options, &shared);
      ASSERT_EQ(alone.size(), reused.size()) << "window " << window_hz << " Hz, threshold " << threshold;
      for (std::size_t i = 0; i < alone.size(); ++i) {
        EXPECT_EQ(alone[i].bin, reused[i].bin);
        EXPECT_EQ(alone[i].frequency_hz, reused[i].frequency_hz);
        EXPECT_EQ(alone[i].amplitude, reused[i].amplitude);
        EXPECT_EQ(alone[i].prominence, reused[i].prominence);
      }
      compared += alone.size();
    }
  }
  EXPECT_GE(compared, 12u) << "the sweep should find lines to compare";
}

}  // namespace
}  // namespace stengmc
