// first_domain_exit (MODEL.md §2, validity: x reaching l) against closed-form crossing
// times, including maxima that fall between samples.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <string>

#include "core/error.hpp"
#include "support/analytic_motion.hpp"
#include "tribology/domain_check.hpp"
#include "tribology/sampled_motion.hpp"

namespace stengmc {
namespace {

using testing::SineMotion;
using testing::UniformMotion;

constexpr double pi = std::numbers::pi;
constexpr double element_length = 80e-6;  // l [m], the order of Table 2's element length

std::vector<double> uniform_times(double step_s, std::size_t count) {
  std::vector<double> t(count);
  for (std::size_t j = 0; j < count; ++j) t[j] = step_s * static_cast<double>(j);
  return t;
}

std::vector<double> sample(const Motion& motion, const std::vector<double>& times) {
  std::vector<double> x;
  for (double t : times) x.push_back(motion.at(t).x_m);
  return x;
}

//! For RecordProperty: errors of order 1e-16 must not print as 0.
std::string sci(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", value);
  return text;
}

double max_of(const std::vector<double>& x) {
  double m = -INFINITY;
  for (double v : x) m = std::max(m, v);
  return m;
}

//! Largest x on a fine scan of [t0, t1] (n + 1 points).
double scan_max(const Motion& motion, double t0, double t1, int n) {
  double m = -INFINITY;
  for (int i = 0; i <= n; ++i) m = std::max(m, motion.at(t0 + (t1 - t0) * i / n).x_m);
  return m;
}

//! Passes another motion through, counting evaluations.
class CountingMotion final : public Motion {
 public:
  explicit CountingMotion(const Motion& inner) : inner_(inner) {}
  PhasePoint at(double t, Side side) const override {
    ++count;
    return inner_.at(t, side);
  }
  const std::vector<double>& breakpoints() const override { return inner_.breakpoints(); }
  mutable long count = 0;

 private:
  const Motion& inner_;
};

//! Another motion, but x = NaN on the open window (from, to).
class NanWindowMotion final : public Motion {
 public:
  NanWindowMotion(const Motion& inner, double from_s, double to_s) : inner_(inner), from_(from_s), to_(to_s) {}
  PhasePoint at(double t, Side side) const override {
    PhasePoint p = inner_.at(t, side);
    if (t > from_ && t < to_) p.x_m = std::numeric_limits<double>::quiet_NaN();
    return p;
  }
  const std::vector<double>& breakpoints() const override { return inner_.breakpoints(); }

 private:
  const Motion& inner_;
  double from_, to_;
};

//! Model 1-like stick-slip pulse: stuck at 0 until t1, a half-cosine slip up to `top`
//! (x' = 0 at both ends), stuck at `top` on [t1 + pi/omega, t3], a half-cosine slip back
//! down, stuck at 0. x' is exactly 0 during the sticks, as in Model 1.
class StickSlipMotion final : public Motion {
 public:
  StickSlipMotion(double top_m, double omega, double t1_s, double t3_s)
      : top_(top_m), omega_(omega), t1_(t1_s), t2_(t1_s + pi / omega), t3_(t3_s), t4_(t3_s + pi / omega),
        breakpoints_{t1_, t2_, t3_, t4_} {}
  PhasePoint at(double t, Side) const override {
    if (t < t1_) return {0.0, 0.0};
    if (t < t2_) return {0.5 * top_ * (1.0 - std::cos(omega_ * (t - t1_))), 0.5 * top_ * omega_ * std::sin(omega_ * (t - t1_))};
    if (t < t3_) return {top_, 0.0};
    if (t < t4_) return {0.5 * top_ * (1.0 + std::cos(omega_ * (t - t3_))), -0.5 * top_ * omega_ * std::sin(omega_ * (t - t3_))};
    return {0.0, 0.0};
  }
  const std::vector<double>& breakpoints() const override { return breakpoints_; }
  //! First time x = level on the slip up [s].
  double rise_crossing(double level_m) const { return t1_ + std::acos(1.0 - 2.0 * level_m / top_) / omega_; }

 private:
  double top_, omega_, t1_, t2_, t3_, t4_;
  std::vector<double> breakpoints_;
};

//! The previous implementation's bisection (x(lo) < l <= x(hi)), the reference for exits
//! at a sample: the new code must return the same double there.
double reference_bisection(const Motion& motion, double lo, double hi, double l) {
  for (int i = 0; i < 200 && std::nextafter(lo, hi) < hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    (motion.at(mid).x_m < l ? lo : hi) = mid;
  }
  return hi;
}

// --- 1. a sine whose peak lies between samples ---------------------------------------

TEST(DomainExit, SinePeakBetweenSamplesIsFoundAtTheAnalyticCrossing) {
  // A = 1.001 l; exactly 31 samples per period, phase chosen so that every peak is
  // mid-interval: the nearest samples are 0.101 rad from it, at x = 0.995 A < l.
  // Reference asin(l/A)/omega-type closed form. Tolerance: bisection ends on adjacent
  // doubles; x rounds at ~eps A and its slope there is A omega cos(theta*) with
  // cos(theta*) = 0.045, so dt ~ eps/(0.045 omega) ~ 3e-15 of t*; asin is as well
  // conditioned (1/cos(theta*) = 22). 1e-12 leaves three orders of margin.
  const double amplitude = 1.001 * element_length;
  const double omega = 2.0 * pi * 2e6;
  const double step = 2.0 * pi / (31.0 * omega);
  const double phase = pi / 2 - 7.5 * omega * step;
  const SineMotion motion(0.0, amplitude, omega, phase);
  const auto t = uniform_times(step, 100);
  const auto x = sample(motion, t);
  ASSERT_LT(max_of(x), element_length) << "the test needs every sample below l";

  const auto exit = first_domain_exit(motion, t, x, element_length);
  ASSERT_TRUE(exit.has_value());
  const double expected = (std::asin(element_length / amplitude) - phase) / omega;
  EXPECT_NEAR(*exit, expected, 1e-12 * expected);
  EXPECT_GT(*exit, t[7]);
  EXPECT_LT(*exit, t[8]);
  RecordProperty("relative_error", sci(std::abs(*exit - expected) / expected));
}

TEST(DomainExit, OscillationNearNyquistFindsTheFirstPeak) {
  // Model 2-like: a 1.9 MHz oscillation sampled at 4 MHz (0.95 rad short of Nyquist),
  // A = 1.05 l, first peak mid-interval so both its samples sit at x = A cos(1.49) = 0.08 A.
  // Later peaks may have samples above l; the first exit is in interval 0 all the same.
  // Reference and tolerance as above (cos(theta*) = 0.30 here, better conditioned).
  const double amplitude = 1.05 * element_length;
  const double omega = 2.0 * pi * 1.9e6;
  const double step = 0.25e-6;
  const double phase = pi / 2 - 0.5 * omega * step;
  const SineMotion motion(0.0, amplitude, omega, phase);
  const auto t = uniform_times(step, 40);
  const auto x = sample(motion, t);
  ASSERT_LT(std::max(x[0], x[1]), element_length);

  const auto exit = first_domain_exit(motion, t, x, element_length);
  ASSERT_TRUE(exit.has_value());
  const double expected = (std::asin(element_length / amplitude) - phase) / omega;
  EXPECT_NEAR(*exit, expected, 1e-12 * expected);
  EXPECT_LT(*exit, t[1]);
  RecordProperty("relative_error", sci(std::abs(*exit - expected) / expected));
}

TEST(DomainExit, CostStaysNearTwoEvaluationsPerSampleWithAPeakInEveryOtherInterval) {
  // The same 1.9 MHz oscillation at 4 MHz, 1e5 samples, peaks at 0.95 l: a maximum
  // between samples in about every other interval, none reaching l. Two evaluations per
  // interval plus a short peak bisection (stopped by the tangent bound); the bound of 8
  // per sample is what the early stop buys (bisecting each peak to adjacent doubles
  // would cost ~2 + 55/2.1 = 28).
  const double omega = 2.0 * pi * 1.9e6;
  const double step = 0.25e-6;
  const SineMotion sine(0.0, 0.95 * element_length, omega, 0.3);
  const auto t = uniform_times(step, 100'000);
  const auto x = sample(sine, t);
  const CountingMotion motion(sine);
  EXPECT_FALSE(first_domain_exit(motion, t, x, element_length).has_value());
  const double per_sample = static_cast<double>(motion.count) / static_cast<double>(t.size());
  EXPECT_LT(per_sample, 8.0);
  RecordProperty("evaluations_per_sample", sci(per_sample));
}

// --- 2. a not-a-knot spline overshooting l between samples ---------------------------

struct Overshoot {
  std::vector<double> t, x;
  double sample_max, spline_max;
};

//! A smoothed step: the not-a-knot spline through it overshoots the top plateau.
Overshoot step_samples() {
  Overshoot o;
  o.t = uniform_times(0.25e-6, 10);
  const double top = 0.9 * element_length;
  o.x = {0.0, 0.0, 0.0, 0.0, 0.5 * top, top, top, top, top, top};
  const SampledMotion spline(o.t, o.x, Interpolation::spline);
  o.sample_max = max_of(o.x);
  o.spline_max = scan_max(spline, o.t.front(), o.t.back(), 90'000);
  return o;
}

TEST(DomainExit, SplineOvershootBetweenSamplesIsFoundAtItsFirstCrossing) {
  // l halfway between the top sample and the spline's maximum (both verified): the old
  // check saw no sample at l. Reference: x(t_exit) = l on the dense output, and x < l at
  // the double before t_exit and on a fine scan before it (the first crossing).
  // Tolerance 1e-12 relative on x: bisection leaves |x(t_exit) - l| <= |x'| ulp(t) +
  // rounding ~ 1e-16 relative.
  const Overshoot o = step_samples();
  ASSERT_GT(o.spline_max, o.sample_max * (1 + 1e-3)) << "the spline must overshoot the samples";
  const double l = 0.5 * (o.sample_max + o.spline_max);
  ASSERT_LT(o.sample_max, l);
  const SampledMotion spline(o.t, o.x, Interpolation::spline);

  const auto exit = first_domain_exit(spline, o.t, o.x, l);
  ASSERT_TRUE(exit.has_value());
  EXPECT_NEAR(spline.at(*exit).x_m, l, 1e-12 * l);
  EXPECT_GE(spline.at(*exit).x_m, l);
  EXPECT_LT(spline.at(std::nextafter(*exit, 0.0)).x_m, l);
  EXPECT_LT(scan_max(spline, o.t.front(), std::nextafter(*exit, 0.0), 50'000), l);
  RecordProperty("relative_error_x", sci(std::abs(spline.at(*exit).x_m - l) / l));
}

// --- 3. a sample reaching l --------------------------------------------------------

TEST(DomainExit, SampleReachingLGivesTheBisectedCrossing) {
  // x = v t: the first sample >= l is found and the crossing bisected as before. Compared
  // with the previous implementation's bisection (the same double, exactly) and with
  // l / v (1e-14 relative: x = v t rounds at eps, the bisection ends on adjacent doubles).
  const double speed = 1.0;
  const double l = 80.3e-6;
  const UniformMotion motion(0.0, speed);
  const auto t = uniform_times(1e-6, 200);
  const auto x = sample(motion, t);
  const auto exit = first_domain_exit(motion, t, x, l);
  ASSERT_TRUE(exit.has_value());
  EXPECT_EQ(*exit, reference_bisection(motion, t[80], t[81], l));
  EXPECT_NEAR(*exit, l / speed, 1e-14 * l / speed);
}

TEST(DomainExit, SampleAboveLAfterAnInteriorPeakGivesTheFirstCrossing) {
  // The interval holds a peak above l and ends above l (x' > 0 at its start, < 0 at its
  // end): the one crossing is on the way up, at the analytic sine crossing (tolerance
  // as in the first test).
  const double amplitude = 1.2 * element_length;
  const double omega = 2.0 * pi * 1e6;
  const double step = 0.3 / omega;
  const double phase = pi / 2 - 10.4 * omega * step;  // peak at 0.4 of interval 10
  const SineMotion motion(0.0, amplitude, omega, phase);
  const auto t = uniform_times(step, 30);
  const auto x = sample(motion, t);
  const auto exit = first_domain_exit(motion, t, x, element_length);
  ASSERT_TRUE(exit.has_value());
  const double expected = (std::asin(element_length / amplitude) - phase) / omega;
  EXPECT_NEAR(*exit, expected, 1e-12 * expected);
}

TEST(DomainExit, FirstSampleAtOrAboveLIsTheExit) {
  const UniformMotion motion(element_length, 1.0);
  const auto t = uniform_times(1e-6, 10);
  const auto x = sample(motion, t);
  EXPECT_EQ(first_domain_exit(motion, t, x, element_length), t[0]);
}

// --- 4. nothing reaches l ----------------------------------------------------------

TEST(DomainExit, SineBelowLHasNoExit) {
  // A = 0.999 l with peaks between samples: every peak is examined, none reaches l.
  const double omega = 2.0 * pi * 2e6;
  const double step = 0.2 / omega;
  const SineMotion motion(0.0, 0.999 * element_length, omega, pi / 2 - 7.5 * omega * step);
  const auto t = uniform_times(step, 500);
  EXPECT_FALSE(first_domain_exit(motion, t, sample(motion, t), element_length).has_value());
}

TEST(DomainExit, SplineOvershootStayingBelowLHasNoExit) {
  // The same overshooting spline with l just above its maximum (by 1e-6 relative, far
  // above the scan's resolution error of ~(1e-5)^2 relative).
  const Overshoot o = step_samples();
  const SampledMotion spline(o.t, o.x, Interpolation::spline);
  EXPECT_FALSE(first_domain_exit(spline, o.t, o.x, o.spline_max * (1 + 1e-6)).has_value());
}

TEST(DomainExit, StickSlipPlateauBelowLHasNoExit) {
  // x' = 0 exactly on stick plateaus inside the interval (Model 1): the peak search walks
  // through them; the top plateau at 0.99 l stays below l.
  const double omega = 2.0 * pi * 1e6;
  const StickSlipMotion motion(0.99 * element_length, omega, 1.0e-6, 2.0e-6);
  const std::vector<double> t{0.0, 1.2e-6, 2.3e-6, 5e-6};  // x' > 0 at 1.2 us, < 0 at 2.3 us
  EXPECT_FALSE(first_domain_exit(motion, t, sample(motion, t), element_length).has_value());
  const std::vector<double> wide{0.0, 2.3e-6, 5e-6};  // x' = 0 at 0 (stuck), < 0 at 2.3 us
  EXPECT_FALSE(first_domain_exit(motion, wide, sample(motion, wide), element_length).has_value());
}

TEST(DomainExit, StickSlipPlateauAboveLIsFoundOnTheWayUp) {
  // As above with the top plateau at 1.01 l, samples below l on both sides of it, with
  // a moving or a stuck start. Reference: the half-cosine crossing t1 + acos(1 - 2l/top)
  // / omega (tolerance as in the first test; the slope there is larger).
  const double omega = 2.0 * pi * 1e6;
  const StickSlipMotion motion(1.01 * element_length, omega, 1.0e-6, 2.0e-6);
  const double expected = motion.rise_crossing(element_length);
  for (const std::vector<double>& t : {std::vector<double>{0.0, 1.2e-6, 2.4e-6, 5e-6},
                                       std::vector<double>{0.0, 2.4e-6, 5e-6}}) {
    const auto x = sample(motion, t);
    ASSERT_LT(max_of(x), element_length);
    const auto exit = first_domain_exit(motion, t, x, element_length);
    ASSERT_TRUE(exit.has_value());
    EXPECT_NEAR(*exit, expected, 1e-12 * expected);
  }
}

// --- 5. non-finite displacements ---------------------------------------------------

TEST(DomainExit, NonFiniteSampleIsAModelErrorNamingTheTime) {
  // Previously NaN < l was false and read as an exit.
  const UniformMotion motion(0.0, 1.0);
  const auto t = uniform_times(1e-6, 10);
  for (double bad : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    auto x = sample(motion, t);
    x[4] = bad;
    try {
      (void)first_domain_exit(motion, t, x, element_length);
      ADD_FAILURE() << "expected ModelError";
    } catch (const ModelError& e) {
      EXPECT_NE(std::string(e.what()).find("displacement is not finite at t = 4e-06 s"), std::string::npos) << e.what();
    }
  }
  // A NaN after an exit is still reported: the caller would write it out.
  auto x = sample(motion, t);
  x[9] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW((void)first_domain_exit(motion, t, x, 2.5e-6), ModelError);
}

TEST(DomainExit, NonFiniteDenseOutputIsAModelError) {
  // Finite samples, NaN on the dense output where it is evaluated: near the interior
  // peak of the first test, in the crossing bisection of a sample at l, at a sample.
  const double omega = 2.0 * pi * 2e6;
  const double step = 0.2 / omega;
  const SineMotion sine(0.0, 0.999 * element_length, omega, pi / 2 - 7.5 * omega * step);
  const auto t = uniform_times(step, 100);
  const auto x = sample(sine, t);
  const NanWindowMotion near_peak(sine, t[7] + 0.4 * step, t[7] + 0.6 * step);
  EXPECT_THROW((void)first_domain_exit(near_peak, t, x, element_length), ModelError);
  const NanWindowMotion at_sample(sine, t[3] - 1e-3 * step, t[3] + 1e-3 * step);
  EXPECT_THROW((void)first_domain_exit(at_sample, t, x, element_length), ModelError);

  const UniformMotion line(0.0, 1.0);
  const auto tl = uniform_times(1e-6, 10);
  const NanWindowMotion in_crossing(line, 4e-6, 5e-6);
  EXPECT_THROW((void)first_domain_exit(in_crossing, tl, sample(line, tl), 4.5e-6), ModelError);
}

// --- 6. piecewise-linear interpolation ---------------------------------------------

TEST(DomainExit, LinearInterpolationMaximumAtASample) {
  // x' jumps at the samples and is constant between them, so no interior maximum exists:
  // below l nothing, above l the crossing on the rising segment into the top sample,
  // t1 + (l - x1) / (x2 - x1) h (1e-14 relative: linear interpolation rounds at eps).
  const auto t = uniform_times(1e-6, 5);
  const double l = element_length;
  const std::vector<double> below{0.0, 0.5 * l, 0.999 * l, 0.6 * l, 0.2 * l};
  const SampledMotion below_motion(t, below, Interpolation::linear);
  EXPECT_FALSE(first_domain_exit(below_motion, t, below, l).has_value());

  const std::vector<double> above{0.0, 0.5 * l, 1.2 * l, 0.6 * l, 0.2 * l};
  const SampledMotion above_motion(t, above, Interpolation::linear);
  const auto exit = first_domain_exit(above_motion, t, above, l);
  ASSERT_TRUE(exit.has_value());
  const double expected = t[1] + (l - above[1]) / (above[2] - above[1]) * (t[2] - t[1]);
  EXPECT_NEAR(*exit, expected, 1e-14 * expected);
}

}  // namespace
}  // namespace stengmc
