// The calibrated population intervals of calibrate_estimate (docs/inverse.md, "Calibration"):
// split-conformal, ln median +- q s. A small bank's quantile q can be the score of a bank
// record that claimed a tiny error and missed (~1e9 and more); the interval then overflowed
// to infinity and `invert` refused to write the whole batch. Checked against the closed forms
// the docs give: the interval is exp(+-q s) about the median while it stays inside the prior's
// support, and the support (the sd's bound: half its width in ln k x sqrt 2) beyond it.
#include <gtest/gtest.h>

#include <cmath>

#include "inverse/calibration_maps.hpp"
#include "inverse/calibration_run.hpp"
#include "pipeline/study.hpp"
#include "support/inverse_device.hpp"

namespace stengmc {
namespace {

//! Maps with the identity confusion and the given score quantiles in every bin and class.
CalibrationMaps maps_with_quantile(const InversePrior& prior, double quantile) {
  CalibrationMaps maps;
  maps.count_min = prior.count_min;
  maps.count_max = prior.count_max;
  const std::size_t counts = prior.count_max - prior.count_min + 1;
  const std::size_t bins = (counts + POPULATION_BIN_COUNTS - 1) / POPULATION_BIN_COUNTS;
  for (ClassMaps& c : maps.classes) {
    c.confusion.assign(counts, std::vector<double>(counts, 0.0));
    for (std::size_t i = 0; i < counts; ++i) c.confusion[i][i] = 1.0;
    c.median_score_quantile.assign(bins, quantile);
    c.sd_score_quantile.assign(bins, quantile);
  }
  return maps;
}

//! Three lines of 50, 60, 70 N/m with standard errors 1e-3 in ln k, counted 3 for certain.
RecordEstimate three_lines() {
  RecordEstimate e;
  e.noise.sigma_v = e.residual_sigma_v = 1e-3;
  e.posterior.counts = {3};
  e.posterior.probability = {1.0};
  e.count = 3;
  for (const double k : {50.0, 60.0, 70.0}) {
    EstimatedLine line;
    line.stiffness_n_per_m = k;
    line.log_stiffness_se = 1e-3;
    e.lines.push_back(line);
  }
  e.median_stiffness_n_per_m = 60.0;
  const double mean = (std::log(50.0) + std::log(60.0) + std::log(70.0)) / 3.0;
  double var = 0.0;
  for (const double k : {50.0, 60.0, 70.0}) var += (std::log(k) - mean) * (std::log(k) - mean) / 2.0;
  e.sd_log_stiffness = std::sqrt(var);
  return e;
}

InversePrior quick_prior() {
  const Study study = parse_study(testing::known_device_study("20e-6", testing::quick_prior()), "device.toml", std::nullopt);
  return inverse_setup(study).prior;
}

TEST(CalibratedIntervals, MedianIntervalIsTheConformalOneInsideThePriorsSupport) {
  const InversePrior prior = quick_prior();
  const CalibrationMaps maps = maps_with_quantile(prior, 2.0);
  const CalibratedEstimate c = calibrate_estimate(three_lines(), &maps, prior);
  ASSERT_TRUE(c.population_intervals);
  // s = the middle line's error, 1e-3: the interval is 60 exp(+-2e-3).
  EXPECT_NEAR(c.median_low, 60.0 * std::exp(-2e-3), 1e-12);
  EXPECT_NEAR(c.median_high, 60.0 * std::exp(2e-3), 1e-12);
}

TEST(CalibratedIntervals, AHugeBankQuantileGivesThePriorsSupportNotInfinity) {
  const InversePrior prior = quick_prior();
  const auto [k_low, k_high] = prior.support();
  for (const double quantile : {1e6, 1e12, 1e300}) {
    const CalibrationMaps maps = maps_with_quantile(prior, quantile);
    const CalibratedEstimate c = calibrate_estimate(three_lines(), &maps, prior);
    ASSERT_TRUE(std::isfinite(c.median_low) && std::isfinite(c.median_high)) << quantile;
    ASSERT_TRUE(std::isfinite(c.sd_log_low) && std::isfinite(c.sd_log_high)) << quantile;
    EXPECT_NEAR(c.median_low / k_low, 1.0, 1e-12) << quantile;
    EXPECT_NEAR(c.median_high / k_high, 1.0, 1e-12) << quantile;
    EXPECT_EQ(c.sd_log_low, 0.0);
    EXPECT_NEAR(c.sd_log_high, 0.5 * std::log(k_high / k_low) * std::sqrt(2.0), 1e-12) << quantile;
  }
}

}  // namespace
}  // namespace stengmc
