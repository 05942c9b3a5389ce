// Ensemble statistics (stats/ensemble_statistics): each interval covers a known truth at
// close to its nominal 95 % over independent replicates (the "must show"), matches
// closed forms on hand data (t interval, Wilson, order-statistic coverage), is bitwise
// reproducible, and degenerate or invalid input gives flagged finite results or errors.
//
// Coverage tolerances: a count of c covers in R = 400 replicates has binomial standard
// error sqrt(π(1 − π)/R) ≈ 0.011 at π = 0.95, so the band [0.90, 0.99] is > 3.5 SE from
// nominal on both sides; each test states its method's expected coverage, measured with
// 2000 replicates while writing it. Replicate r draws its data from
// random_stream(SEED, r, noise) and resamples with random_stream(SEED, r, bootstrap):
// independent per replicate, and the whole file is deterministic.
#include <gtest/gtest.h>

#include <bit>
#include <boost/math/distributions/binomial.hpp>
#include <boost/math/distributions/students_t.hpp>
#include <boost/random/bernoulli_distribution.hpp>
#include <boost/random/binomial_distribution.hpp>
#include <boost/random/exponential_distribution.hpp>
#include <boost/random/normal_distribution.hpp>
#include <boost/random/uniform_int_distribution.hpp>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "core/random_stream.hpp"
#include "stats/ensemble_statistics.hpp"

namespace stengmc {
namespace {

constexpr std::uint64_t SEED = 20250101;
constexpr std::size_t REPLICATES = 400;

RandomEngine data_engine(std::uint64_t r) { return random_stream(SEED, r, StreamKind::noise); }
RandomEngine resampling_engine(std::uint64_t r) { return random_stream(SEED, r, StreamKind::bootstrap); }

std::vector<double> normal_sample(std::size_t n, double mean, double sd, RandomEngine& engine) {
  boost::random::normal_distribution<double> law(mean, sd);
  std::vector<double> x(n);
  for (double& v : x) v = law(engine);
  return x;
}

std::vector<double> exponential_sample(std::size_t n, double mean, RandomEngine& engine) {
  boost::random::exponential_distribution<double> law(1.0 / mean);
  std::vector<double> x(n);
  for (double& v : x) v = law(engine);
  return x;
}

bool covers(const Interval& i, double truth) { return i.low <= truth && truth <= i.high; }

void expect_finite(const Interval& i) {
  EXPECT_TRUE(std::isfinite(i.estimate) && std::isfinite(i.low) && std::isfinite(i.high))
      << i.method << ": " << i.estimate << " [" << i.low << ", " << i.high << "]";
}

void expect_finite(const ScalarSummary& s) {
  for (const Interval* i : {&s.mean, &s.standard_deviation, &s.median, &s.p05, &s.p95}) expect_finite(*i);
  EXPECT_TRUE(std::isfinite(s.min) && std::isfinite(s.max));
}

// Bitwise equality of two intervals (== would also accept −0 for +0).
void expect_identical(const Interval& a, const Interval& b) {
  EXPECT_EQ(std::bit_cast<std::uint64_t>(a.estimate), std::bit_cast<std::uint64_t>(b.estimate));
  EXPECT_EQ(std::bit_cast<std::uint64_t>(a.low), std::bit_cast<std::uint64_t>(b.low));
  EXPECT_EQ(std::bit_cast<std::uint64_t>(a.high), std::bit_cast<std::uint64_t>(b.high));
  EXPECT_EQ(a.known, b.known);
  EXPECT_EQ(a.method, b.method);
}

void expect_coverage_between(double coverage, double low, double high, const char* what) {
  std::printf("  %-44s coverage %.4f over %zu replicates\n", what, coverage, REPLICATES);
  EXPECT_GE(coverage, low) << what;
  EXPECT_LE(coverage, high) << what;
}

std::string error_of(auto&& call) {
  try {
    call();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

// ---------------------------------------------------------------- coverage of the mean

TEST(MeanInterval, StudentTCoversTheTrueMeanOfNormalData) {
  // N(3, 2²), n = 50: the CLT rule admits |G1| < 0.94 and G1's SE is 0.34, so nearly every
  // replicate takes the t path, whose coverage is exactly 95 % for normal data.
  std::size_t hits = 0, t_path = 0;
  for (std::size_t r = 0; r < REPLICATES; ++r) {
    RandomEngine data = data_engine(r), resampling = resampling_engine(r);
    const Interval m = mean_interval(normal_sample(50, 3.0, 2.0, data), resampling);
    hits += covers(m, 3.0);
    t_path += m.method == METHOD_STUDENT_T;
    EXPECT_TRUE(m.known);
  }
  expect_coverage_between(double(hits) / REPLICATES, 0.90, 0.99, "normal n = 50 (Student t)");
  EXPECT_GE(double(t_path) / REPLICATES, 0.97);  // P(|G1| > 0.94) ≈ 0.5 %
}

TEST(MeanInterval, BcaCoversTheTrueMeanOfSkewedData) {
  // Exponential with mean 2.5, n = 20 < 30: every replicate takes the BCa path. Measured
  // coverage 0.93–0.935 (expanded BCa, two sets of 2000; 0.916 without Hesterberg's
  // expansion, 0.920 for t).
  std::size_t hits = 0;
  for (std::size_t r = 0; r < REPLICATES; ++r) {
    RandomEngine data = data_engine(r), resampling = resampling_engine(r);
    const Interval m = mean_interval(exponential_sample(20, 2.5, data), resampling);
    ASSERT_EQ(m.method, METHOD_BCA);
    EXPECT_TRUE(m.known);
    hits += covers(m, 2.5);
  }
  expect_coverage_between(double(hits) / REPLICATES, 0.90, 0.99, "exponential n = 20 (BCa bootstrap)");
}

TEST(ProportionInterval, WilsonCoversTheTrueProportion) {
  // Bernoulli(0.3), 50 trials: Wilson's coverage oscillates with n but stays near 95 % at
  // moderate p (Brown, Cai & DasGupta 2001, fig. 4).
  std::size_t hits = 0;
  for (std::size_t r = 0; r < REPLICATES; ++r) {
    RandomEngine data = data_engine(r);
    boost::random::bernoulli_distribution<double> trial(0.3);
    std::size_t successes = 0;
    for (int i = 0; i < 50; ++i) successes += trial(data);
    hits += covers(proportion_interval(successes, 50), 0.3);
  }
  expect_coverage_between(double(hits) / REPLICATES, 0.90, 0.99, "Bernoulli(0.3), 50 trials (Wilson)");
}

TEST(RatioOfSumsInterval, CoversThePooledProportion) {
  // 30 realisations; realisation i has k_i ~ U{1..40} trials (the "sliding time") and
  // Binomial(k_i, 0.3) successes (the "identifiable time"): the ratio of sums estimates
  // 0.3. Pairs are resampled together; measured coverage 0.936 (2000 replicates).
  std::size_t hits = 0;
  for (std::size_t r = 0; r < REPLICATES; ++r) {
    RandomEngine data = data_engine(r), resampling = resampling_engine(r);
    boost::random::uniform_int_distribution<int> trials(1, 40);
    std::vector<double> top, bottom;
    for (int i = 0; i < 30; ++i) {
      const int k = trials(data);
      boost::random::binomial_distribution<int> successes(k, 0.3);
      bottom.push_back(k);
      top.push_back(successes(data));
    }
    const Interval ratio = ratio_of_sums_interval(top, bottom, resampling);
    EXPECT_EQ(ratio.method, METHOD_BCA);
    EXPECT_TRUE(ratio.known);
    hits += covers(ratio, 0.3);
  }
  expect_coverage_between(double(hits) / REPLICATES, 0.90, 0.99, "ratio of sums, 30 realisations (BCa)");
}

// ---------------------------------------------------------------- quantile intervals

// The exact coverage of the equal-tailed order-statistic interval for a continuous law,
// found by a linear scan of the binomial cdf (the library uses a bisection): P(l <= K < u)
// with K ~ Binomial(n, p) (Hahn & Meeker 1991, §5.2).
double exact_quantile_coverage(std::size_t n, double p) {
  const boost::math::binomial law(double(n), p);
  std::size_t l = 0, u = n + 1;
  for (std::size_t k = 0; k <= n; ++k)
    if (boost::math::cdf(law, double(k)) <= 0.025) l = k + 1;
  for (std::size_t k = n + 1; k-- > 0;)
    if (boost::math::cdf(law, double(k)) >= 0.975) u = k + 1;
  const double below_l = l == 0 ? 0.0 : boost::math::cdf(law, double(l - 1));
  return boost::math::cdf(law, double(u - 1)) - below_l;
}

TEST(QuantileInterval, CoversTheTrueQuantilesOfAnExponentialLaw) {
  // Exponential(1), n = 100: the true p-quantile is −ln(1 − p). For a continuous law the
  // interval's coverage is exactly the binomial sum above (>= 95 % by construction:
  // 0.983 at p = 0.05 and 0.95, 0.965 at the median); the measured rate must be >= 0.93
  // and within 4 binomial SE of it.
  for (const double p : {0.05, 0.5, 0.95}) {
    SCOPED_TRACE(p);
    const double truth = -std::log1p(-p), exact = exact_quantile_coverage(100, p);
    ASSERT_GE(exact, 0.95);
    std::size_t hits = 0;
    for (std::size_t r = 0; r < REPLICATES; ++r) {
      RandomEngine data = data_engine(r);
      const Interval q = quantile_interval(exponential_sample(100, 1.0, data), p);
      ASSERT_TRUE(q.known);
      ASSERT_LE(q.low, q.estimate);
      ASSERT_LE(q.estimate, q.high);
      hits += covers(q, truth);
    }
    const double coverage = double(hits) / REPLICATES;
    std::printf("  quantile p = %.2f: coverage %.4f, exact %.4f\n", p, coverage, exact);
    EXPECT_GE(coverage, 0.93);
    EXPECT_LE(std::abs(coverage - exact), 4.0 * std::sqrt(exact * (1.0 - exact) / REPLICATES));
  }
}

TEST(QuantileInterval, OrderStatisticsOnHandData) {
  // x = 1..20. Median: type-7 estimate 10.5; Binomial(20, 0.5) has F(5) = 0.0207 <= 0.025
  // < F(6) = 0.0577, so l = 6; F(14) = 0.9793 >= 0.975 > F(13) = 0.9423, so u = 15:
  // [X(6), X(15)] = [6, 15], coverage F(14) − F(5) = 0.9586.
  std::vector<double> x;
  for (int i = 20; i >= 1; --i) x.push_back(i);  // unsorted on purpose
  const Interval median = quantile_interval(x, 0.5);
  EXPECT_EQ(median.estimate, 10.5);
  EXPECT_EQ(median.low, 6.0);
  EXPECT_EQ(median.high, 15.0);
  EXPECT_TRUE(median.known);
  // p05 at n = 20: P(K = 0) = 0.95^20 = 0.358 > 0.025, no lower order statistic reaches:
  // the low end falls back to the sample minimum and the interval is not known.
  const Interval p05 = quantile_interval(x, 0.05);
  EXPECT_FALSE(p05.known);
  EXPECT_EQ(p05.low, 1.0);
  EXPECT_NEAR(p05.estimate, 1.95, 1e-12);  // 1 + 0.95 · (2 − 1)
}

// ---------------------------------------------------------------- closed forms

TEST(MeanInterval, StudentTMatchesTheTextbookFormula) {
  // x = 1..30: mean 15.5, s² = n(n + 1)/12 = 77.5 (sum of squares of 1..n), skewness 0 so
  // the CLT rule holds; t_{29, 0.975} = 2.0452 (t tables; Boost gives 2.045229642). Half
  // width t · s/√n = 3.287247 (computed by hand from these numbers).
  std::vector<double> x;
  for (int i = 1; i <= 30; ++i) x.push_back(i);
  RandomEngine engine = resampling_engine(0);
  const RandomEngine before = engine;
  const Interval m = mean_interval(x, engine);
  EXPECT_EQ(m.method, METHOD_STUDENT_T);
  EXPECT_EQ(engine, before);  // the t path draws nothing
  const double t = boost::math::quantile(boost::math::students_t(29.0), 0.975);
  EXPECT_NEAR(t, 2.0452, 5e-5);
  EXPECT_DOUBLE_EQ(m.estimate, 15.5);
  EXPECT_NEAR(m.half_width(), t * std::sqrt(77.5 / 30.0), 1e-12);
  EXPECT_NEAR(m.half_width(), 3.287247, 1e-6);
  EXPECT_NEAR(m.low + m.high, 31.0, 1e-12);
}

TEST(MeanInterval, BcaReducesToStudentTOnASymmetricSample) {
  // x = 1..20 (G1 = 0; n < 30 so BCa): z0 ≈ 0, a = 0, and with Hesterberg's expansion
  // the endpoints are the bootstrap law's Φ(±sqrt(n/(n−1)) t) quantiles, i.e. mean ±
  // t s/√n up to that law's non-normality (excess kurtosis −1.2/n: a 0.2 % shift,
  // Cornish–Fisher) and Monte Carlo error (0.06 SE · sqrt(2000/B) ≈ 1 % of the half width
  // at B = 20000). 3 % tolerance.
  std::vector<double> x;
  for (int i = 1; i <= 20; ++i) x.push_back(i);
  StatisticsOptions options;
  options.bootstrap_resamples = 20000;
  RandomEngine engine = resampling_engine(1);
  const Interval bca = mean_interval(x, engine, options);
  ASSERT_EQ(bca.method, METHOD_BCA);
  const double t_half = boost::math::quantile(boost::math::students_t(19.0), 0.975) * std::sqrt(35.0 / 20.0);
  std::printf("  BCa [%.4f, %.4f] vs t [%.4f, %.4f]\n", bca.low, bca.high, 10.5 - t_half, 10.5 + t_half);
  EXPECT_NEAR(bca.high - 10.5, t_half, 0.03 * t_half);
  EXPECT_NEAR(10.5 - bca.low, t_half, 0.03 * t_half);
}

TEST(MeanInterval, CltRuleFollowsSugdenSmithJones) {
  // 0/1 data with a share q of ones have g1 = (1 − 2q)/sqrt(q(1 − q)) exactly, and
  // G1 = g1 · sqrt(n(n − 1))/(n − 2). q = 0.3: at n = 40, G1 = 0.907 and 28 + 25 G1² =
  // 48.6 > 40 → BCa; at n = 100, G1 = 0.886, 28 + 25 G1² = 47.6 < 100 → t. Below
  // bootstrap_min_count (n = 9) t is used whatever the skewness.
  auto zeros_and_ones = [](std::size_t n, std::size_t ones) {
    std::vector<double> x(n, 0.0);
    for (std::size_t i = 0; i < ones; ++i) x[i * n / ones] = 1.0;
    return x;
  };
  RandomEngine engine = resampling_engine(2);
  EXPECT_EQ(mean_interval(zeros_and_ones(40, 12), engine).method, METHOD_BCA);
  EXPECT_EQ(mean_interval(zeros_and_ones(100, 30), engine).method, METHOD_STUDENT_T);
  EXPECT_EQ(mean_interval(zeros_and_ones(40, 20), engine).method, METHOD_STUDENT_T);  // G1 = 0
  EXPECT_EQ(mean_interval(zeros_and_ones(9, 1), engine).method, METHOD_STUDENT_T);
}

TEST(ProportionInterval, WilsonMatchesNewcombesTable) {
  // Newcombe (1998), Stat. Med. 17, 857, table II, method 3 (score, no continuity
  // correction), 4 decimals: tolerance half a unit in the last digit.
  struct Case {
    std::size_t s, n;
    double low, high;
  };
  for (const Case c : {Case{81, 263, 0.2553, 0.3662}, Case{15, 148, 0.0624, 0.1605}, Case{0, 20, 0.0, 0.1611},
                       Case{1, 29, 0.0061, 0.1718}}) {
    const Interval i = proportion_interval(c.s, c.n);
    EXPECT_NEAR(i.low, c.low, 5e-5) << c.s << "/" << c.n;
    EXPECT_NEAR(i.high, c.high, 5e-5) << c.s << "/" << c.n;
    EXPECT_EQ(i.method, METHOD_WILSON);
  }
  // Closed forms at the edges: 0/n → [0, z²/(n + z²)], n/n → [n/(n + z²), 1].
  const double z2 = 1.959963984540054 * 1.959963984540054;
  EXPECT_EQ(proportion_interval(0, 10).low, 0.0);
  EXPECT_NEAR(proportion_interval(0, 10).high, z2 / (10 + z2), 1e-14);
  EXPECT_NEAR(proportion_interval(10, 10).low, 10 / (10 + z2), 1e-14);
  EXPECT_EQ(proportion_interval(10, 10).high, 1.0);
}

// ---------------------------------------------------------------- determinism

TEST(Summarise, SameInputsGiveBitwiseIdenticalResults) {
  RandomEngine data = data_engine(1000);
  const std::vector<double> skewed = exponential_sample(40, 1.0, data);  // BCa mean
  const std::vector<double> normal = normal_sample(50, 0.0, 1.0, data);  // t mean
  for (const auto* x : {&skewed, &normal}) {
    RandomEngine e1 = resampling_engine(7), e2 = resampling_engine(7), e3 = resampling_engine(7);
    const ScalarSummary a = summarise(*x, e1), b = summarise(*x, e2);
    EXPECT_EQ(a.count, b.count);
    for (auto m : {&ScalarSummary::mean, &ScalarSummary::standard_deviation, &ScalarSummary::median,
                   &ScalarSummary::p05, &ScalarSummary::p95})
      expect_identical(a.*m, b.*m);
    EXPECT_EQ(e1, e2);  // and the engines advanced alike
    // summarise's mean is mean_interval's (shared resamples).
    expect_identical(a.mean, mean_interval(*x, e3));
  }
  // Ratio of sums: the same.
  const std::vector<double> denominators = exponential_sample(40, 5.0, data);
  RandomEngine e1 = resampling_engine(8), e2 = resampling_engine(8);
  expect_identical(ratio_of_sums_interval(skewed, denominators, e1), ratio_of_sums_interval(skewed, denominators, e2));
}

TEST(Summarise, AnotherEngineChangesOnlyTheBootstrapIntervals) {
  RandomEngine data = data_engine(1002);
  const std::vector<double> skewed = exponential_sample(40, 1.0, data);
  const std::vector<double> normal = normal_sample(50, 0.0, 1.0, data);
  RandomEngine e1 = resampling_engine(1), e2 = resampling_engine(2);
  const ScalarSummary a = summarise(skewed, e1), b = summarise(skewed, e2);
  ASSERT_EQ(a.mean.method, METHOD_BCA);
  EXPECT_EQ(a.mean.estimate, b.mean.estimate);
  EXPECT_NE(a.mean.low, b.mean.low);
  EXPECT_EQ(a.standard_deviation.estimate, b.standard_deviation.estimate);
  EXPECT_NE(a.standard_deviation.high, b.standard_deviation.high);
  expect_identical(a.median, b.median);
  expect_identical(a.p05, b.p05);
  expect_identical(a.p95, b.p95);
  EXPECT_EQ(a.min, b.min);
  EXPECT_EQ(a.max, b.max);
  // The t path does not depend on the engine at all.
  const ScalarSummary c = summarise(normal, e1), d = summarise(normal, e2);
  ASSERT_EQ(c.mean.method, METHOD_STUDENT_T);
  expect_identical(c.mean, d.mean);
  EXPECT_NE(c.standard_deviation.low, d.standard_deviation.low);
}

// ---------------------------------------------------------------- degenerate and bad input

TEST(Summarise, DegenerateInputsGiveFlaggedFiniteResults) {
  RandomEngine engine = resampling_engine(3);
  // No values: everything 0, nothing known.
  const ScalarSummary none = summarise(std::vector<double>{}, engine);
  expect_finite(none);
  EXPECT_EQ(none.count, 0u);
  for (const Interval* i : {&none.mean, &none.standard_deviation, &none.median, &none.p05, &none.p95}) {
    EXPECT_FALSE(i->known);
    EXPECT_EQ(i->low, i->high);
  }
  // One value: the point, not known (documented: low = high = estimate).
  const ScalarSummary one = summarise(std::vector<double>{4.2}, engine);
  expect_finite(one);
  EXPECT_FALSE(one.mean.known);
  EXPECT_EQ(one.mean.estimate, 4.2);
  EXPECT_EQ(one.mean.low, 4.2);
  EXPECT_EQ(one.mean.high, 4.2);
  EXPECT_EQ(one.min, 4.2);
  EXPECT_EQ(one.max, 4.2);
  EXPECT_FALSE(one.standard_deviation.known);
  // Two values: the mean is a t interval (n < bootstrap_min_count) and known; the
  // standard deviation is a bootstrap from 2 values, flagged; the median cannot be bounded.
  const ScalarSummary two = summarise(std::vector<double>{1.0, 3.0}, engine);
  expect_finite(two);
  EXPECT_TRUE(two.mean.known);
  EXPECT_EQ(two.mean.method, METHOD_STUDENT_T);
  EXPECT_NEAR(two.mean.half_width(), boost::math::quantile(boost::math::students_t(1.0), 0.975), 1e-12);  // s/√2 = 1
  EXPECT_FALSE(two.standard_deviation.known);
  EXPECT_FALSE(two.median.known);
  EXPECT_EQ(two.median.low, 1.0);
  EXPECT_EQ(two.median.high, 3.0);
  // All equal (0.1 does not sum exactly): zero width at exactly the value, known.
  for (std::size_t n : {7u, 50u}) {
    SCOPED_TRACE(n);
    const std::vector<double> same(n, 0.1);
    const RandomEngine before = engine;
    const ScalarSummary s = summarise(same, engine);
    expect_finite(s);
    EXPECT_EQ(engine, before);  // nothing to resample
    EXPECT_EQ(s.mean.estimate, 0.1);
    EXPECT_EQ(s.mean.low, 0.1);
    EXPECT_EQ(s.mean.high, 0.1);
    EXPECT_TRUE(s.mean.known);
    EXPECT_EQ(s.mean.method, METHOD_CONSTANT);
    EXPECT_EQ(s.standard_deviation.estimate, 0.0);
    EXPECT_EQ(s.standard_deviation.half_width(), 0.0);
    EXPECT_EQ(s.median.low, 0.1);
    EXPECT_EQ(s.median.high, 0.1);
    EXPECT_EQ(s.p95.half_width(), 0.0);
  }
  // Small-n bootstrap: known = false below bootstrap_min_count, finite throughout.
  RandomEngine data = data_engine(2000);
  const ScalarSummary small = summarise(exponential_sample(5, 1.0, data), engine);
  expect_finite(small);
  EXPECT_FALSE(small.standard_deviation.known);
  EXPECT_TRUE(small.mean.known);
}

TEST(Summarise, NonFiniteValuesAreRejectedNamingTheIndex) {
  RandomEngine engine = resampling_engine(4);
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  const std::string m1 = error_of([&] { summarise(std::vector<double>{1, 2, 3, nan, 5}, engine); });
  EXPECT_NE(m1.find("summarise: value 3 is nan"), std::string::npos) << m1;
  const std::string m2 = error_of([&] { mean_interval(std::vector<double>{inf, 2}, engine); });
  EXPECT_NE(m2.find("mean_interval: value 0 is inf"), std::string::npos) << m2;
  const std::string m3 = error_of([&] { quantile_interval(std::vector<double>{1, -inf}, 0.5); });
  EXPECT_NE(m3.find("value 1 is -inf"), std::string::npos) << m3;
  std::printf("  %s\n  %s\n  %s\n", m1.c_str(), m2.c_str(), m3.c_str());
}

TEST(Statistics, BadArgumentsAreRejected) {
  RandomEngine engine = resampling_engine(5);
  const std::vector<double> x = {1, 2, 3};
  StatisticsOptions bad;
  bad.confidence = 1.0;
  EXPECT_NE(error_of([&] { summarise(x, engine, bad); }).find("confidence = 1 must lie in (0, 1)"), std::string::npos);
  bad = {};
  bad.bootstrap_resamples = 0;
  EXPECT_NE(error_of([&] { mean_interval(x, engine, bad); }).find("bootstrap_resamples"), std::string::npos);
  EXPECT_NE(error_of([&] { quantile_interval(x, 1.0); }).find("p = 1 must lie in (0, 1)"), std::string::npos);
  EXPECT_NE(error_of([&] { proportion_interval(4, 3); }).find("successes = 4 exceed trials = 3"), std::string::npos);
  EXPECT_NE(error_of([&] { ratio_of_sums_interval(x, std::vector<double>{1, 2}, engine); })
                .find("3 numerators but 2 denominators"),
            std::string::npos);
  EXPECT_NE(error_of([&] { ratio_of_sums_interval(x, std::vector<double>{1, -2, 1}, engine); })
                .find("denominator 1 = -2 must be >= 0"),
            std::string::npos);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(error_of([&] { ratio_of_sums_interval(x, std::vector<double>{1, 1, nan}, engine); })
                .find("denominators: value 2 is nan"),
            std::string::npos);
}

TEST(RatioOfSumsInterval, DegenerateInputs) {
  RandomEngine engine = resampling_engine(6);
  // No trials at all: 0 with known = false (and finite).
  const Interval zero = ratio_of_sums_interval(std::vector<double>{0, 0}, std::vector<double>{0, 0}, engine);
  expect_finite(zero);
  EXPECT_FALSE(zero.known);
  // One realisation: its ratio, not known.
  const Interval one = ratio_of_sums_interval(std::vector<double>{1}, std::vector<double>{4}, engine);
  EXPECT_EQ(one.estimate, 0.25);
  EXPECT_FALSE(one.known);
  // Every realisation at the same ratio (zero-denominator ones contributing nothing):
  // every resample's ratio is the same, so the interval has zero width.
  const Interval same = ratio_of_sums_interval(std::vector<double>{1, 2, 0, 3}, std::vector<double>{4, 8, 0, 12}, engine);
  EXPECT_EQ(same.estimate, 0.25);
  EXPECT_EQ(same.half_width(), 0.0);
  EXPECT_EQ(same.method, METHOD_CONSTANT);
  // Many zero denominators: resamples of only those are left out; still finite.
  std::vector<double> top(12, 0.0), bottom(12, 0.0);
  top[0] = 1, bottom[0] = 2, top[1] = 1, bottom[1] = 5;
  const Interval sparse = ratio_of_sums_interval(top, bottom, engine);
  expect_finite(sparse);
  EXPECT_NEAR(sparse.estimate, 2.0 / 7.0, 1e-15);
  EXPECT_LE(sparse.low, sparse.high);
  // The Wilson interval of zero trials: [0, 1], not known.
  const Interval none = proportion_interval(0, 0);
  EXPECT_FALSE(none.known);
  EXPECT_EQ(none.low, 0.0);
  EXPECT_EQ(none.high, 1.0);
}

}  // namespace
}  // namespace stengmc
