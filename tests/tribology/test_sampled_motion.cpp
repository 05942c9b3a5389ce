// Interpolants through displacement samples (MODEL.md §2) against closed forms.
#include <gtest/gtest.h>

#include <cmath>

#include "tribology/sampled_motion.hpp"

namespace stengmc {
namespace {

std::vector<double> grid(double end, std::size_t n) {
  std::vector<double> t(n);
  for (std::size_t j = 0; j < n; ++j) t[j] = end * static_cast<double>(j) / static_cast<double>(n - 1);
  return t;
}

TEST(SampledMotionSpline, ReproducesACubicExactly) {
  // A not-a-knot spline reproduces any cubic (de Boor): the error is rounding only.
  // Non-uniform samples exercise the general system.
  const std::vector<double> t{0.0, 0.7, 1.1, 2.0, 2.3, 3.5, 4.0};
  auto cubic = [](double s) { return 0.3 - 1.2 * s + 0.5 * s * s + 0.25 * s * s * s; };
  auto slope = [](double s) { return -1.2 + 1.0 * s + 0.75 * s * s; };
  std::vector<double> x;
  for (double s : t) x.push_back(cubic(s));
  const SampledMotion motion(t, x, Interpolation::spline);
  for (double s = 0.0; s <= 4.0; s += 0.013) {
    EXPECT_NEAR(motion.at(s).x_m, cubic(s), 1e-12);
    EXPECT_NEAR(motion.at(s).v_m_per_s, slope(s), 1e-11);
  }
}

TEST(SampledMotionSpline, ConvergesAtFourthOrderOnASine) {
  // Cubic spline interpolation error is O(h^4) in x for smooth data.
  std::vector<double> errors;
  for (std::size_t n : {21, 41, 81}) {
    const auto t = grid(3.0, n);
    std::vector<double> x;
    for (double s : t) x.push_back(std::sin(2.0 * s));
    const SampledMotion motion(t, x, Interpolation::spline);
    double worst = 0.0;
    for (double s = 0.0; s <= 3.0; s += 0.0011) worst = std::max(worst, std::abs(motion.at(s).x_m - std::sin(2.0 * s)));
    errors.push_back(worst);
  }
  for (std::size_t k = 1; k < errors.size(); ++k) EXPECT_NEAR(std::log2(errors[k - 1] / errors[k]), 4.0, 0.4);
}

TEST(SampledMotionLinear, HasSegmentSlopesAndBreakpointsWithOneSidedLimits) {
  const std::vector<double> t{0.0, 1.0, 2.0, 4.0};
  const std::vector<double> x{0.0, 2.0, 1.0, 5.0};
  const SampledMotion motion(t, x, Interpolation::linear);
  EXPECT_DOUBLE_EQ(motion.at(0.5).x_m, 1.0);
  EXPECT_DOUBLE_EQ(motion.at(1.0, Side::left).v_m_per_s, 2.0);
  EXPECT_DOUBLE_EQ(motion.at(1.0, Side::right).v_m_per_s, -1.0);
  EXPECT_DOUBLE_EQ(motion.at(3.0).v_m_per_s, 2.0);
  EXPECT_EQ(motion.breakpoints(), (std::vector<double>{1.0, 2.0}));
}

TEST(SampledMotion, RejectsTooFewOrUnorderedSamples) {
  EXPECT_THROW(SampledMotion({0.0, 1.0, 2.0}, {0.0, 1.0, 2.0}, Interpolation::spline), std::exception);
  EXPECT_THROW(SampledMotion({0.0, 2.0, 1.0}, {0.0, 1.0, 2.0}, Interpolation::linear), std::exception);
}

}  // namespace
}  // namespace stengmc
