#pragma once
//! What a calibration bank learns about the estimator on simulations of the prior, and how
//! it turns a raw estimate into a calibrated one (docs/inverse.md, "calibration").
//!
//! - Two fit classes (below): every map is learnt apart for the records whose fit explains
//!   them to their noise and for those it does not.
//! - The count: P(true n = n | n-hat = m), the estimator's confusion on the bank, with the
//!   offsets n - m pooled over neighbouring m until at least 60 records (the confusion
//!   changes slowly with m) and a Jeffreys prior (1/2 per offset in -3..3; larger offsets only
//!   as observed: a record the model misfits can be counted far off). The calibrated
//!   P(n | y) = sum_m P_raw(m | y) P(n | m): the raw posterior's doubts, when it has any, are
//!   carried through the empirical confusion. The 90 % interval is the shortest run of
//!   counts around the mode holding >= 0.9.
//! - The median and sd(ln k) of the sliding asperities: split-conformal intervals with
//!   normalised scores (Vovk, Gammerman & Shafer 2005; Lei, G'Sell, Rinaldo, Tibshirani &
//!   Wasserman 2018, "Distribution-free predictive inference for regression", JASA 113, 1094,
//!   §5.2 "locally weighted"), Mondrian by bins of 4 counts of n-hat (Vovk et al. §4.5): in
//!   each bin the ceil(0.9 (N + 1))-th smallest bank score |ln median-hat - ln median| / s
//!   (|sd-hat - sd| / s), with s the estimate's own standard error from its lines' errors, is
//!   q; the interval +-q s covers a new record of the prior whose n-hat falls in that bin with
//!   probability >= 0.9 (exchangeability within the bin). Bins with fewer than 20 bank
//!   records take all records.
//! - Each line: its Gauss–Newton standard error, scaled so 90 % of the bank's lines (records
//!   counted exactly, lines paired in order of k) lie within +-1.645 scaled errors.
//! - The naive FFT count: the prominence threshold whose count has the smallest RMSE.
#include <array>
#include <cstddef>
#include <vector>

#include "inverse/calibration_sample.hpp"
#include "inverse/inverse_prior.hpp"
#include "inverse/record_estimator.hpp"

namespace stengmc {

inline constexpr double INTERVAL_LEVEL = 0.9;

//! A record fits its noise when the fit's residual rms is at most `misfit_ratio` x the noise
//! measured above the lines. Records that do not are those where the atoms miss part of the
//! physics (a departure they do not describe, or one at the prior's edge); their counts are
//! wrong far more often (the small broadened bank of test_inverse_broadened: 86 % of the wrong
//! counts, 18 % of the right ones below the prior's top count). Every map is learnt apart for the two classes (a Mondrian
//! taxonomy, Vovk et al. 2005 §4.5), so a record that fits gets the narrow intervals records
//! like it earn and one that does not the wide ones records like it need.
enum class FitClass : std::size_t { fits = 0, misfits = 1 };
inline constexpr std::size_t FIT_CLASSES = 2;
//! Without a bank, and the least ratio a bank may set: a residual within 10 % of the noise is
//! a fit whatever the bank's records say (on the ideal device they hold the ratio to ~1 %).
inline constexpr double DEFAULT_MISFIT_RATIO = 1.1;
//! The bank sets the ratio at this quantile of its records counted right (below the prior's
//! largest count; calibration_maps.cpp): a warning on ~15 % of such right answers, by
//! construction.
inline constexpr double MISFIT_QUANTILE = 0.85;

//! A record also falls in the second class when one of its lines is not pinned: its standard
//! error in ln k exceeds `line_se_bound`. A line the record holds is pinned by the record's
//! whole duration (a sinusoid's frequency error falls as T^{-3/2}, Rife & Boorstyn 1974): on
//! the broadened test bank the right counts' lines stay within 5e-4, while an atom the search
//! adds to absorb what the model does not describe trades against the others and is known to
//! 0.15-11 %. Such a record can fit its noise (the extra atom is what makes it fit), so the
//! residual alone misses it. The bank sets the bound at this quantile of the worst line of
//! its records counted right that fit (calibration_maps.cpp): a warning on at most ~5 % more
//! of them, by construction.
inline constexpr double LINE_SE_QUANTILE = 0.95;
//! Without a bank, and the least bound a bank may set: a line known to 0.1 % (1 sigma) is
//! pinned whatever the bank's records say.
inline constexpr double DEFAULT_LINE_SE_BOUND = 1e-3;

//! The residual's rms over the noise's (1 where no noise was measured above the lines).
double noise_misfit(double residual_sigma_v, double noise_sigma_v);
//! The largest standard error in ln k among the lines that stand apart from every other by
//! more than that error (0 without such lines). A line within its own error of another is one
//! of a pair the record cannot tell apart — two asperities of one k give one line of twice the
//! amplitude, counted right, whose atoms trade k freely (errors ~0.5 in the ideal family) — so
//! its own error says nothing of whether the record pins the pair. The atoms the search adds to
//! patch a misfit stood 1.4-700 of their errors from the nearest line (errors 0.03-0.26 %, the
//! wrong counts of 20 records each of the loads and onset families).
double worst_line_se(const std::vector<double>& stiffness, const std::vector<double>& log_stiffness_se);

//! The class of a record of `misfit` (noise_misfit) and worst line error `worst_se`
//! (worst_line_se) for the boundaries `misfit_ratio` and `line_se_bound`.
inline FitClass fit_class_of(double misfit, double worst_se, double misfit_ratio, double line_se_bound) {
  return misfit > misfit_ratio || worst_se > line_se_bound ? FitClass::misfits : FitClass::fits;
}

//! The maps of one fit class.
struct ClassMaps {
  //! confusion[m - count_min][n - count_min] = P(n | n-hat = m)
  std::vector<std::vector<double>> confusion;
  //! per bin of n-hat (bin j: count_min + 4j .. count_min + 4j + 3): conformal quantiles of
  //! the normalised scores of ln median and of sd(ln k)
  std::vector<double> median_score_quantile;
  std::vector<double> sd_score_quantile;
  double line_error_scale = 1.0;  //!< standard errors x this: 90 % of the class's lines within 1.645
  std::size_t records = 0;        //!< bank records of this class
  bool pooled = false;            //!< too few records of its own: learnt from all the bank's
};

struct CalibrationMaps {
  std::size_t count_min = 1, count_max = 16;
  double misfit_ratio = DEFAULT_MISFIT_RATIO;  //!< the fit classes' boundary (noise_misfit)
  double line_se_bound = DEFAULT_LINE_SE_BOUND;  //!< and on the worst line's ln k error (worst_line_se)
  std::array<ClassMaps, FIT_CLASSES> classes;  //!< [FitClass]
  std::size_t naive_threshold_index = 0;
  double naive_threshold = 0.0;         //!< x the local noise floor
  std::size_t records = 0;              //!< valid bank records the maps were fitted on

  //! Bank figures (in-sample: optimistic), for the calibrate summary.
  double bank_count_rmse = 0.0, bank_exact_rate = 0.0, bank_naive_rmse = 0.0, bank_naive_exact_rate = 0.0;

  [[nodiscard]] FitClass fit_class(double misfit, double worst_se) const {
    return fit_class_of(misfit, worst_se, misfit_ratio, line_se_bound);
  }
  [[nodiscard]] const ClassMaps& of(FitClass c) const { return classes[static_cast<std::size_t>(c)]; }
};

CalibrationMaps fit_calibration_maps(const std::vector<CalibrationSample>& samples, const InversePrior& prior);

//! Counts of n-hat per bin of the population intervals.
inline constexpr std::size_t POPULATION_BIN_COUNTS = 4;

//! Standard error of ln(median k) from the lines' standard errors in ln k (the middle line's,
//! or half the root-sum-square of the middle two), floored at 1e-12.
double median_log_scale(std::vector<double> stiffness, std::vector<double> log_stiffness_se);
//! Standard error of the sample sd of ln k by first-order propagation of the lines' errors,
//! floored at 1e-12 (0 below two lines).
double sd_log_scale(const std::vector<double>& stiffness, const std::vector<double>& log_stiffness_se);

struct CalibratedEstimate {
  bool calibrated = false;                //!< false: no bank (raw posterior, no population intervals)
  std::vector<std::size_t> counts;        //!< count_min .. count_max
  std::vector<double> probability;        //!< P(n) for each
  std::size_t count = 0;                  //!< the most probable
  std::size_t interval_low = 0, interval_high = 0;  //!< 90 % interval of n
  double median = 0.0, median_low = 0.0, median_high = 0.0;  //!< realised median k and its 90 % interval [N/m]
  double sd_log = 0.0, sd_log_low = 0.0, sd_log_high = 0.0;  //!< realised sd(ln k) and its 90 % interval [-]
  bool population_intervals = false;      //!< the two intervals above are calibrated ones
  FitClass fit_class = FitClass::fits;    //!< which class's maps calibrated it
  double misfit = 1.0;                    //!< its noise_misfit
  double worst_line_se = 0.0;             //!< its worst_line_se
  bool sd_known = false;                  //!< sd(ln k) needs two lines
  std::vector<double> line_low, line_high;  //!< 90 % interval of each line's k [N/m]
};

//! The calibrated estimate; without maps (nullptr), the raw posterior and Laplace intervals.
CalibratedEstimate calibrate_estimate(const RecordEstimate& estimate, const CalibrationMaps* maps, const InversePrior& prior);

}  // namespace stengmc
