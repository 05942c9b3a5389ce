#pragma once
//! Statistics of per-realisation scalars (V_rms [V], final charge [C], identifiability
//! ratio [-], ...) over an ensemble, each with a confidence interval, for the ensemble
//! runner's reports and its stopping rules. Unit-agnostic: an interval is in the unit of
//! the values.
//!
//! Methods (each function says which it used in Interval::method):
//!   mean                 Student t when the central limit theorem is credible for the
//!                        sample (the rule below) or count < bootstrap_min_count,
//!                        otherwise the BCa bootstrap
//!   standard deviation   BCa bootstrap
//!   quantiles            distribution-free order-statistic interval (binomial)
//!   proportion           Wilson score interval
//!   ratio of sums        BCa bootstrap over realisations (pairs resampled together)
//!
//! CLT rule: the t interval is used when count >= clt_min_count (30) and
//! count > 28 + 25 G1², G1 the adjusted sample skewness: Sugden, Smith & Jones (2000),
//! "Cochran's rule for simple random sampling", J. R. Stat. Soc. B 62, 787, who derive
//! it from an Edgeworth expansion as a refinement of Cochran's n > 25 G1² (Cochran 1977,
//! Sampling Techniques, 3rd ed., §2.15: a rule meant to keep a nominal 95 % statement
//! wrong at most about 6 % of the time for positively skewed populations). At n = 50 it
//! admits |G1| < 0.94, at n = 128 |G1| < 2. Sample G1 is a noisy plug-in for the
//! population's; the test suite measures the coverage that results.
//!
//! Bootstrap: BCa (Efron 1987, J. Am. Stat. Assoc. 82, 171; Efron & Tibshirani 1993, An
//! Introduction to the Bootstrap, ch. 14), acceleration from the jackknife, with
//! Hesterberg's (2015) small-sample expansion of its normal score (ensemble_statistics.cpp,
//! bootstrap_score): it lifts the coverage of the mean of exponential data at n = 20 from
//! 0.92 to 0.93–0.94, and makes BCa agree with t on symmetric samples.
//!
//! Determinism: every result is a pure function of (values in order, options, engine
//! state). Resample indices come from boost::random::uniform_int_distribution (a fixed
//! algorithm), sums run in index order, no threads; the same inputs give bitwise-identical
//! outputs. Draw the engine from random_stream(seed, id, StreamKind::bootstrap).
//!
//! Never NaN or infinity (results go to HDF5): where no interval can be stated,
//! Interval::known is false and low/high are finite stand-ins (see Interval).
//! Non-finite input values throw Error naming the index: filter invalid realisations first.
#include <cstddef>
#include <span>
#include <string>

#include "core/random_stream.hpp"

namespace stengmc {

//! Interval::method values.
inline constexpr const char* METHOD_STUDENT_T = "student-t";
inline constexpr const char* METHOD_BCA = "bca-bootstrap";
inline constexpr const char* METHOD_ORDER_STATISTICS = "order-statistics";
inline constexpr const char* METHOD_WILSON = "wilson-score";
//! All values equal: the interval is the value itself (zero width).
inline constexpr const char* METHOD_CONSTANT = "constant";
//! Too few values for any interval (known == false).
inline constexpr const char* METHOD_NONE = "none";

//! A point estimate with a two-sided confidence interval, in the unit of the values.
struct Interval {
  double estimate = 0.0;
  double low = 0.0;
  double high = 0.0;
  //! True when [low, high] is a confidence interval at the requested level by `method`.
  //! False when the data cannot give one: then low and high are finite stand-ins, never
  //! ±inf (HDF5 refuses non-finite values):
  //!  - count < 2: low = high = estimate (0 when count == 0), method "none";
  //!  - a quantile bound beyond the sample's reach (e.g. p05 with n < 72): that side is
  //!    the sample minimum or maximum;
  //!  - a bootstrap interval from fewer than bootstrap_min_count values: the BCa interval
  //!    itself, which cannot reach past the sample's range and undercovers badly there;
  //!  - a proportion of zero trials: [0, 1].
  bool known = false;
  //! How it was computed: one of the METHOD_* names.
  std::string method = METHOD_NONE;

  //! (high − low) / 2: what a stopping rule compares with its target.
  [[nodiscard]] double half_width() const { return 0.5 * (high - low); }
};

//! Summary of one per-realisation scalar.
struct ScalarSummary {
  std::size_t count = 0;  //!< number of values used
  Interval mean;          //!< t or BCa (see the file comment); as mean_interval
  //! Sample standard deviation (divisor n − 1); BCa bootstrap, because the sampling law
  //! of s is skewed, which the percentile interval ignores and BCa corrects to second
  //! order (Efron 1987). Reliable for near-normal data only: its coverage falls with the
  //! kurtosis, as for every bootstrap interval of a spread (Schenker 1985, "Qualms about
  //! bootstrap confidence intervals", J. Am. Stat. Assoc. 80, 360). Measured coverage
  //! (2000 samples): normal n = 20, 0.91–0.92; n = 50, 0.93–0.94; exponential n = 20,
  //! 0.80; n = 50, 0.85. One value: estimate 0, not known.
  Interval standard_deviation;
  Interval median;  //!< quantile_interval(values, 0.5)
  Interval p05;     //!< quantile_interval(values, 0.05)
  Interval p95;     //!< quantile_interval(values, 0.95)
  double min = 0.0;  //!< smallest value (0 when count == 0)
  double max = 0.0;  //!< largest value (0 when count == 0)
};

struct StatisticsOptions {
  double confidence = 0.95;  //!< two-sided confidence level, in (0, 1)
  //! Bootstrap resamples B (>= 1). Efron & Tibshirani (1993) ask B >= 1000 for percentile
  //! and BCa endpoints; at 2000 the Monte Carlo error of a 2.5 % endpoint is about 0.06
  //! standard errors (sqrt(0.025·0.975/B) / φ(1.96), normal approximation).
  std::size_t bootstrap_resamples = 2000;
  //! CLT rule (file comment): t interval when count >= clt_min_count and
  //! count > clt_skewness_offset + clt_skewness_factor · G1².
  std::size_t clt_min_count = 30;
  double clt_skewness_offset = 28.0;  //!< Sugden, Smith & Jones (2000)
  double clt_skewness_factor = 25.0;  //!< Cochran (1977)
  //! Below this count the mean uses Student t whatever the CLT rule says, and bootstrap
  //! intervals are flagged known = false: a resample never leaves the sample's range, so
  //! at n = 3–5 a 95 % (expanded) BCa interval of the mean covers 69–92 % of the time,
  //! where t covers 87–95 % (normal and exponential data, 2000 samples); at n = 10 BCa
  //! matches or beats t (0.94/0.93 vs 0.95/0.90). The default sits where they cross;
  //! cf. Hesterberg (2015) on small-sample bootstrap intervals.
  std::size_t bootstrap_min_count = 10;
};

//! Everything in ScalarSummary. The engine is advanced by the bootstrap (run for the
//! standard deviation unless count < 2 or all values are equal); the mean's bootstrap,
//! when used, shares those resamples, so summary.mean equals mean_interval(values, e) for
//! an engine e in the same initial state.
//! Throws Error on a non-finite value (naming its index) or bad options.
ScalarSummary summarise(std::span<const double> values, RandomEngine& bootstrap_engine, const StatisticsOptions& options = {});

//! The mean and its interval — what stopping rules use. Student t or BCa by the CLT rule
//! (file comment); the engine is advanced only when the bootstrap is used. count < 2:
//! known == false. All values equal: a zero-width interval, method "constant".
Interval mean_interval(std::span<const double> values, RandomEngine& bootstrap_engine, const StatisticsOptions& options = {});

//! The p-quantile (0 < p < 1; Hyndman & Fan 1996 type 7, linear interpolation) with a
//! distribution-free interval [X(l), X(u)] between order statistics, coverage
//! P(l <= K < u) >= confidence for K ~ Binomial(n, p) (Hahn & Meeker 1991, Statistical
//! Intervals, §5.2; exact for continuous laws, conservative under ties). No engine.
Interval quantile_interval(std::span<const double> values, double p, double confidence = 0.95);

//! successes / trials with the Wilson (1927) score interval, J. Am. Stat. Assoc. 22, 209:
//! near-nominal coverage even at small n or extreme p, where the Wald interval fails
//! (Brown, Cai & DasGupta 2001, Stat. Sci. 16, 101). trials == 0: known == false, [0, 1].
Interval proportion_interval(std::size_t successes, std::size_t trials, double confidence = 0.95);

//! Σ numerators / Σ denominators (e.g. pooled identifiable time / sliding time) with a
//! BCa bootstrap over realisations: pairs (numerator_i, denominator_i) are resampled
//! together, so the correlation between them is kept (Davison & Hinkley 1997, Bootstrap
//! Methods and their Application, ch. 2, city-population ratio example). Denominators must be >= 0 (counts,
//! durations); resamples whose denominators sum to 0 are left out. Σ denominators == 0 or
//! count < 2: known == false. Throws Error on unequal lengths, a non-finite value or a
//! negative denominator (naming the index).
Interval ratio_of_sums_interval(std::span<const double> numerators, std::span<const double> denominators,
                                RandomEngine& bootstrap_engine, const StatisticsOptions& options = {});

}  // namespace stengmc
