#pragma once
//! What a calibration bank learns about the estimator on simulations of the prior, and how
//! it turns a raw estimate into a calibrated one (README: inverse estimation, "calibration").
//!
//! - The count: P(true n = n | n-hat = m), the estimator's confusion on the bank, with the
//!   offsets n - m pooled over neighbouring m until at least 60 records (the confusion
//!   changes slowly with m) and a Jeffreys prior (1/2 per offset in -3..3). The calibrated
//!   P(n | y) = sum_m P_raw(m | y) P(n | m): the raw posterior's doubts, when it has any, are
//!   carried through the empirical confusion. The 90 % interval is the shortest run of
//!   counts around the mode holding >= 0.9.
//! - The median and sd(ln k) of the sliding asperities: split-conformal intervals (Vovk,
//!   Gammerman & Shafer 2005; Lei, G'Sell, Rinaldo, Tibshirani & Wasserman 2018, "Distribution-
//!   free predictive inference for regression", JASA 113, 1094), Mondrian by n-hat (pooled
//!   over neighbouring n-hat until >= 100 records): the ceil(0.9 (N + 1))-th smallest bank
//!   score |ln median-hat - ln median| (|sd-hat - sd|) is the half-width, which covers a new
//!   record of the prior with probability >= 0.9 (exchangeability).
//! - Each line: its Gauss–Newton standard error, scaled so 90 % of the bank's lines (records
//!   counted exactly, lines paired in order of k) lie within +-1.645 scaled errors.
//! - The naive FFT count: the prominence threshold whose count has the smallest RMSE.
#include <cstddef>
#include <vector>

#include "inverse/calibration_sample.hpp"
#include "inverse/inverse_prior.hpp"
#include "inverse/record_estimator.hpp"

namespace stengmc {

inline constexpr double INTERVAL_LEVEL = 0.9;

struct CalibrationMaps {
  std::size_t count_min = 1, count_max = 16;
  //! confusion[m - count_min][n - count_min] = P(n | n-hat = m)
  std::vector<std::vector<double>> confusion;
  //! per n-hat (index m - count_min): conformal half-widths of ln median and of sd(ln k)
  std::vector<double> median_log_half_width;
  std::vector<double> sd_log_half_width;
  double line_error_scale = 1.0;        //!< standard errors x this: 90 % of bank lines within 1.645
  std::size_t naive_threshold_index = 0;
  double naive_threshold = 0.0;         //!< x the local noise floor
  std::size_t records = 0;              //!< valid bank records the maps were fitted on

  //! Bank figures (in-sample: optimistic), for the calibrate summary.
  double bank_count_rmse = 0.0, bank_exact_rate = 0.0, bank_naive_rmse = 0.0, bank_naive_exact_rate = 0.0;
};

CalibrationMaps fit_calibration_maps(const std::vector<CalibrationSample>& samples, const InversePrior& prior);

struct CalibratedEstimate {
  bool calibrated = false;                //!< false: no bank (raw posterior, no population intervals)
  std::vector<std::size_t> counts;        //!< count_min .. count_max
  std::vector<double> probability;        //!< P(n) for each
  std::size_t count = 0;                  //!< the most probable
  std::size_t interval_low = 0, interval_high = 0;  //!< 90 % interval of n
  double median = 0.0, median_low = 0.0, median_high = 0.0;  //!< realised median k and its 90 % interval [N/m]
  double sd_log = 0.0, sd_log_low = 0.0, sd_log_high = 0.0;  //!< realised sd(ln k) and its 90 % interval [-]
  bool population_intervals = false;      //!< the two intervals above are calibrated ones
  bool sd_known = false;                  //!< sd(ln k) needs two lines
  std::vector<double> line_low, line_high;  //!< 90 % interval of each line's k [N/m]
};

//! The calibrated estimate; without maps (nullptr), the raw posterior and Laplace intervals.
CalibratedEstimate calibrate_estimate(const RecordEstimate& estimate, const CalibrationMaps* maps, const InversePrior& prior);

}  // namespace stengmc
