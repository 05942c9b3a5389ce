// The measurement chain (pipeline/measurement_noise.hpp, docs/model.md "The measurement
// chain"): each part against its closed form: the power law's slope, the first-order
// filter's response, the noise power the SNR asks for, the offset; and white noise alone
// drawn exactly as it always was (the files of earlier studies do not move).
#include <gtest/gtest.h>

#include <boost/random/normal_distribution.hpp>
#include <cmath>
#include <complex>
#include <numeric>
#include <vector>

#include "core/constants.hpp"
#include "core/error.hpp"
#include "core/random_stream.hpp"
#include "core/toml_reader.hpp"
#include "pipeline/measurement_noise.hpp"
#include "spectral/power_law_noise.hpp"

namespace stengmc {
namespace {

//! Least-squares slope of ln S against ln f of the mean periodogram of `runs` series.
double periodogram_slope(double exponent, std::size_t samples, int runs) {
  std::vector<double> mean_power(samples / 2 + 1, 0.0);
  for (int r = 0; r < runs; ++r) {
    RandomEngine engine = random_stream(11, static_cast<std::uint64_t>(r), StreamKind::noise, 1);
    const std::vector<double> x = power_law_noise(samples, exponent, engine);
    for (std::size_t k = 1; k <= samples / 2; ++k) {  // a plain DFT of the bins used below
      if (k < 4 || k > samples / 8) continue;
      std::complex<double> sum = 0.0;
      for (std::size_t j = 0; j < samples; ++j) sum += x[j] * std::polar(1.0, -2.0 * PI * static_cast<double>(k * j) / static_cast<double>(samples));
      mean_power[k] += std::norm(sum) / runs;
    }
  }
  double sx = 0, sy = 0, sxx = 0, sxy = 0, n = 0;
  for (std::size_t k = 4; k <= samples / 8; ++k) {
    const double lx = std::log(static_cast<double>(k)), ly = std::log(mean_power[k]);
    sx += lx, sy += ly, sxx += lx * lx, sxy += lx * ly, n += 1;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

TEST(PowerLawNoise, ItsPeriodogramFallsAsOneOverFToTheExponent) {
  // 64 series of 1024: the mean periodogram's log has a standard error of ~0.13 per bin
  // over 125 bins, so the fitted slope is within ~0.02 of -alpha; bound 0.08.
  for (const double alpha : {0.5, 1.0, 2.0}) {
    const double slope = periodogram_slope(alpha, 1024, 64);
    std::printf("alpha %.1f: periodogram slope %.4f\n", alpha, slope);
    EXPECT_NEAR(slope, -alpha, 0.08) << "alpha " << alpha;
  }
}

TEST(PowerLawNoise, ItHasZeroMeanAndUnitVariance) {
  RandomEngine engine = random_stream(3, 0, StreamKind::noise, 1);
  const std::vector<double> x = power_law_noise(1000, 1.0, engine);
  const double mean = std::accumulate(x.begin(), x.end(), 0.0) / 1000.0;
  double variance = 0.0;
  for (double v : x) variance += (v - mean) * (v - mean);
  EXPECT_NEAR(mean, 0.0, 1e-12);
  EXPECT_NEAR(variance / 1000.0, 1.0, 1e-12);
}

TEST(FirstOrderLowpass, ItsResponseToARampThenAStepIsTheClosedForm) {
  // x: 0 at t = 0, a ramp to 1 over one step h, then 1. For t >= h the exact solution of
  // y' = lambda (x - y) is y = 1 - (e^{lambda h} - 1)/(lambda h) e^{-lambda t}.
  const double fs = 100e6, fc = 3e6, h = 1.0 / fs, lambda = 2.0 * PI * fc;
  std::vector<double> x(200, 1.0);
  x[0] = 0.0;
  const std::vector<double> y = first_order_lowpass(x, fs, fc);
  double worst = 0.0;
  for (std::size_t j = 1; j < x.size(); ++j) {
    const double t = static_cast<double>(j) * h;
    const double exact = 1.0 - std::expm1(lambda * h) / (lambda * h) * std::exp(-lambda * t);
    worst = std::max(worst, std::abs(y[j] - exact));
  }
  EXPECT_LT(worst, 1e-14);
}

TEST(FirstOrderLowpass, ASineAtTheCornerComesOutAtOneOverRootTwo) {
  // |H(f_c)| = 1/sqrt 2; the linear interpolation between samples adds ~(2 pi f h)^2/12.
  const double fs = 200e6, fc = 1e6;
  std::vector<double> x(40000);
  for (std::size_t j = 0; j < x.size(); ++j) x[j] = std::sin(2.0 * PI * fc * static_cast<double>(j) / fs);
  const std::vector<double> y = first_order_lowpass(x, fs, fc);
  double peak = 0.0;
  for (std::size_t j = x.size() / 2; j < x.size(); ++j) peak = std::max(peak, std::abs(y[j]));
  EXPECT_NEAR(peak, 1.0 / std::sqrt(2.0), 1e-4);
}

std::vector<double> test_signal(std::size_t n) {
  std::vector<double> v(n);
  for (std::size_t j = 0; j < n; ++j) v[j] = 0.3 + std::sin(0.05 * static_cast<double>(j)) + 0.5 * std::cos(0.31 * static_cast<double>(j));
  return v;
}

TEST(MeasureVoltage, WhiteNoiseAloneIsDrawnAsItAlwaysWas) {
  const std::vector<double> clean = test_signal(5000);
  RandomEngine white = random_stream(5, 2, StreamKind::noise), coloured = random_stream(5, 2, StreamKind::noise, 1);
  const NoisyVoltage noisy = measure_voltage(clean, 0, clean.size(), 1e8, NoiseSettings{.snr_db = 20.0}, white, coloured);
  // One Boost normal draw per sample, in order, of sd sigma: the draws of every earlier file.
  RandomEngine reference = random_stream(5, 2, StreamKind::noise);
  boost::random::normal_distribution<double> normal(0.0, noisy.sigma_v);
  for (std::size_t j = 0; j < clean.size(); ++j) ASSERT_EQ(noisy.voltage_v[j], clean[j] + normal(reference)) << j;
}

TEST(MeasureVoltage, TheNoisePowerIsWhatTheSnrSaysWhateverItsColourAndTheOffsetIsAdded) {
  const std::vector<double> clean = test_signal(20000);
  double mean = std::accumulate(clean.begin(), clean.end(), 0.0) / 20000.0, power = 0.0;
  for (double v : clean) power += (v - mean) * (v - mean);
  power /= 20000.0;
  for (const double share : {0.0, 0.5, 1.0}) {
    NoiseSettings settings{.snr_db = 10.0, .coloured_share = share, .coloured_exponent = 1.0, .offset_v = 0.25};
    RandomEngine white = random_stream(9, 0, StreamKind::noise), coloured = random_stream(9, 0, StreamKind::noise, 1);
    const NoisyVoltage noisy = measure_voltage(clean, 0, clean.size(), 1e8, settings, white, coloured);
    std::vector<double> noise(clean.size());
    for (std::size_t j = 0; j < clean.size(); ++j) noise[j] = noisy.voltage_v[j] - settings.offset_v - clean[j];
    const double noise_mean = std::accumulate(noise.begin(), noise.end(), 0.0) / 20000.0;
    double variance = 0.0;
    for (double v : noise) variance += (v - noise_mean) * (v - noise_mean);
    variance /= 20000.0;
    // sigma^2 = P / 10; the white part's sample variance is within ~2 % (sd sqrt(2/N) = 1 %),
    // the coloured part's is exact by construction; the two are independent.
    EXPECT_NEAR(noisy.sigma_v * noisy.sigma_v, power / 10.0, 1e-12 * power);
    EXPECT_NEAR(variance / (power / 10.0), 1.0, 0.05) << "share " << share;
    // The offset: the mean moves by it (the noise's own mean is ~sigma/sqrt(N) for white,
    // and the coloured part has zero mean over the record).
    EXPECT_NEAR(noise_mean, 0.0, 0.05 * noisy.sigma_v) << "share " << share;
  }
}

TEST(MeasureVoltage, ARecordWithNothingSlidingTakesItsNoiseLevelFromTheReference) {
  // V = 0 has no power to refer an SNR to: sigma = reference_rms_v / 10^(snr/20) exactly,
  // and without a reference no noise at all (only the offset).
  const std::vector<double> silent(4000, 0.0);
  RandomEngine white = random_stream(3, 1, StreamKind::noise), coloured = random_stream(3, 1, StreamKind::noise, 1);
  const NoiseSettings with_reference{.snr_db = 20.0, .coloured_share = 0.5, .offset_v = 0.1, .reference_rms_v = 2e-3};
  const NoisyVoltage noisy = measure_voltage(silent, 0, silent.size(), 1e8, with_reference, white, coloured);
  EXPECT_NEAR(noisy.sigma_v, 2e-4, 1e-18);
  double mean = 0.0, variance = 0.0;
  for (double v : noisy.voltage_v) mean += v / 4000.0;
  for (double v : noisy.voltage_v) variance += (v - mean) * (v - mean) / 4000.0;
  // The white half's sample variance is within 3 sd (sqrt(2/N) = 2.2 %) of its own, the
  // coloured half's exact: 7 % of the total covers both.
  EXPECT_NEAR(variance / (2e-4 * 2e-4), 1.0, 0.07);
  EXPECT_NEAR(mean, 0.1, 0.1 * 2e-4);
  const NoisyVoltage bare = measure_voltage(silent, 0, silent.size(), 1e8, NoiseSettings{.snr_db = 20.0, .offset_v = 0.1},
                                            white, coloured);
  EXPECT_EQ(bare.sigma_v, 0.0);
  for (double v : bare.voltage_v) ASSERT_EQ(v, 0.1);
}

TEST(NoiseSettings, EachKeyOutsideItsRangeIsRefusedNamingIt) {
  const std::vector<std::pair<std::string, std::string>> bad{
      {"coloured_share = 1.5", "coloured_share"}, {"coloured_share = -0.1", "coloured_share"},
      {"coloured_exponent = 3", "coloured_exponent"}, {"coloured_exponent = 0.1", "coloured_exponent"},
      {"offset_v = nan", "offset_v"}, {"offset_v = 1e300", "offset_v"}, {"bandwidth_hz = -1", "bandwidth_hz"},
      {"bandwidth_hz = inf", "bandwidth_hz"}, {"reference_rms_v = -1", "reference_rms_v"},
      {"reference_rms_v = nan", "reference_rms_v"}};
  for (const auto& [line, key] : bad) {
    auto document = TomlDocument::from_string("[noise]\nsnr_db = 20\n" + line + "\n", "s.toml");
    auto noise = document->root().table("noise");
    try {
      read_noise_settings(*noise);
      ADD_FAILURE() << line << " accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("s.toml:3"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace stengmc
