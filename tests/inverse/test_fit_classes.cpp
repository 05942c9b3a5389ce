// The fit classes' rule on lines (docs/inverse.md, "Calibration"; inverse/calibration_maps.hpp):
// a record misfits when a line stands apart from every other by more than its own ln k error
// and that error exceeds line_se_bound; the bank sets the bound at the 95th percentile of the
// worst such error over its right counts that fit, at least 1e-3. Checked against the rule
// worked by hand on small cases, and the bound against the order statistic it must be.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "inverse/calibration_maps.hpp"

namespace stengmc {
namespace {

TEST(FitClasses, ALineWithinItsErrorOfAnotherIsLeftOutAndALineApartIsNot) {
  // Two asperities of one k (ln k apart by 1e-6, errors 0.5: the pair the record cannot tell
  // apart) and a pinned line: only the pinned line's error counts.
  EXPECT_DOUBLE_EQ(worst_line_se({50.0, 50.0 * (1.0 + 1e-6), 80.0}, {0.5, 0.5, 2e-4}), 2e-4);
  // ln(50.2 / 50) = 3.99e-3: a line of error 3e-3 stands apart, one of 5e-3 does not (its
  // neighbour of error 1e-3 stands apart from it either way).
  EXPECT_DOUBLE_EQ(worst_line_se({50.0, 50.2, 80.0}, {1e-3, 3e-3, 2e-4}), 3e-3);
  EXPECT_DOUBLE_EQ(worst_line_se({50.0, 50.2, 80.0}, {1e-3, 5e-3, 2e-4}), 1e-3);
  EXPECT_DOUBLE_EQ(worst_line_se({}, {}), 0.0);
  EXPECT_DOUBLE_EQ(worst_line_se({70.0}, {0.2}), 0.2);  // one line has no neighbour to blend with
}

//! A record counted 2 for certain whose residual fits its noise exactly, with two lines of
//! 50 and 80 N/m, the second of ln k error `second_se`.
RecordEstimate two_lines(double second_se) {
  RecordEstimate e;
  e.noise.sigma_v = e.residual_sigma_v = 1e-3;
  e.posterior.counts = {2};
  e.posterior.probability = {1.0};
  e.count = 2;
  for (const auto& [k, se] : {std::pair{50.0, 1e-4}, std::pair{80.0, second_se}}) {
    EstimatedLine line;
    line.stiffness_n_per_m = k;
    line.log_stiffness_se = se;
    e.lines.push_back(line);
  }
  e.median_stiffness_n_per_m = std::sqrt(50.0 * 80.0);
  return e;
}

TEST(FitClasses, ARecordThatFitsItsNoiseButDoesNotPinALineMisfits) {
  InversePrior prior;
  prior.count_min = 0;
  prior.count_max = 5;
  // Without a bank the bound is 1e-3.
  const CalibratedEstimate pinned = calibrate_estimate(two_lines(5e-4), nullptr, prior);
  EXPECT_EQ(pinned.fit_class, FitClass::fits);
  const CalibratedEstimate unpinned = calibrate_estimate(two_lines(5e-3), nullptr, prior);
  EXPECT_DOUBLE_EQ(unpinned.misfit, 1.0);
  EXPECT_DOUBLE_EQ(unpinned.worst_line_se, 5e-3);
  EXPECT_EQ(unpinned.fit_class, FitClass::misfits);
  // A bank whose right answers' lines reach 1e-2 sets the bound there.
  CalibrationMaps maps;
  maps.line_se_bound = 1e-2;
  EXPECT_EQ(maps.fit_class(1.0, 5e-3), FitClass::fits);
  EXPECT_EQ(maps.fit_class(1.0, 2e-2), FitClass::misfits);
  EXPECT_EQ(maps.fit_class(maps.misfit_ratio * 1.01, 0.0), FitClass::misfits);
}

//! A valid bank record of one sliding asperity counted right, whose line has error `se` and
//! whose residual is `misfit` x its noise.
CalibrationSample one_line_record(double se, double misfit) {
  CalibrationSample s;
  s.valid = true;
  s.true_stiffness = {60.0};
  s.count = 1;
  s.counts = {1.0};
  s.log_evidence = {0.0};
  s.stiffness = {60.0};
  s.log_stiffness_se = {se};
  s.median = 60.0;
  s.noise_sigma_v = 1e-3;
  s.residual_sigma_v = misfit * 1e-3;
  s.naive_counts = {1.0};
  return s;
}

TEST(FitClasses, TheBankSetsTheBoundAtThe95thPercentileOfItsRightCountsThatFit) {
  InversePrior prior;
  prior.count_min = 0;
  prior.count_max = 5;
  // Right counts that fit, with worst errors 1e-4 .. 1e-2 (i x 1e-4, i = 1..100): the 95th
  // percentile is the 95th smallest, 9.5e-3. Ten right counts whose residual misfits (3 x the
  // noise, beyond the misfit ratio the bank sets: 1.1, as they are fewer than 15 % of its right
  // counts) are left out however unpinned their lines (they are warned about already), and so
  // are ten wrong counts.
  std::vector<CalibrationSample> bank;
  for (int i = 1; i <= 100; ++i) bank.push_back(one_line_record(i * 1e-4, 1.0));
  for (int i = 0; i < 10; ++i) bank.push_back(one_line_record(0.5, 3.0));
  for (int i = 0; i < 10; ++i) {
    bank.push_back(one_line_record(0.5, 1.0));
    bank.back().true_stiffness = {60.0, 90.0};
  }
  EXPECT_DOUBLE_EQ(fit_calibration_maps(bank, prior).line_se_bound, 95 * 1e-4);
  // Lines all pinned to 1e-5: the bound stays at its floor, 1e-3.
  std::vector<CalibrationSample> pinned(100, one_line_record(1e-5, 1.0));
  EXPECT_DOUBLE_EQ(fit_calibration_maps(pinned, prior).line_se_bound, DEFAULT_LINE_SE_BOUND);
}

}  // namespace
}  // namespace stengmc
