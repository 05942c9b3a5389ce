// The load spread (MODEL.md §4.4): the excess-height moments M_p(δ) = E[(Z − δ)^p | Z > δ]
// against their closed forms at whole p, the CV's two limits, the separation solved for a
// target CV, and the sampled loads' mean and CV against the law's (a Monte Carlo check
// with a tolerance from the sampling error).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "core/random_stream.hpp"
#include "core/standard_normal.hpp"
#include "surface/load_spread.hpp"

namespace stengmc {
namespace {

// Closed forms by integration by parts, with λ = φ(δ)/Q(δ) the inverse Mills ratio:
// E[Z | Z > δ] = λ, E[Z² | Z > δ] = 1 + δλ, E[Z³ | Z > δ] = (2 + δ²)λ, expanded in (Z − δ).
double mills(double d) { return phi_pdf(d) / phi_cdf(-d); }
double moment1(double d) { return mills(d) - d; }
double moment2(double d) { return 1.0 - d * mills(d) + d * d; }
double moment3(double d) { return (2.0 + d * d) * mills(d) - 3.0 * d - d * d * d; }

TEST(LoadSpread, ExcessMomentsMatchTheirClosedForms) {
  // The quadrature is adaptive to 1e-14. The closed forms are differences of terms up to
  // ~(2 + δ²)λ + |δ|³ that nearly cancel (at δ = 6, 234 − 234 = 0.01): each (λ from erfc and
  // exp, a few ulps each, times δ³) is trusted to 1e-14 of its largest term, and the
  // comparison allows 1e-12 plus that.
  for (double d : {-6.0, -3.0, -1.0, 0.0, 0.5, 1.0, 3.0, 6.0}) {
    const double l = mills(d), a = std::abs(d);
    auto tolerance = [](double largest_term, double value) { return 1e-12 + 1e-14 * largest_term / value; };
    EXPECT_NEAR(excess_height_moment(1.0, d) / moment1(d), 1.0, tolerance(l + a, moment1(d))) << "delta " << d;
    EXPECT_NEAR(excess_height_moment(2.0, d) / moment2(d), 1.0, tolerance(1.0 + a * l + d * d, moment2(d))) << "delta " << d;
    EXPECT_NEAR(excess_height_moment(3.0, d) / moment3(d), 1.0, tolerance((2.0 + d * d) * l + 3.0 * a + a * a * a, moment3(d)))
        << "delta " << d;
  }
}

TEST(LoadSpread, TheCoefficientOfVariationRunsBetweenItsLimits) {
  // δ → ∞: Z − δ given Z > δ tends to an exponential of rate δ, and N ∝ E^{3/2} has
  // CV² = Γ(4)/Γ(5/2)² − 1. At δ = 30 the remaining correction is O(1/δ²) ~ 1e-3.
  const double limit = std::sqrt(6.0 / std::pow(std::tgamma(2.5), 2) - 1.0);
  EXPECT_NEAR(limit, 1.5477, 1e-4);
  EXPECT_NEAR(load_cv_at_separation(30.0), limit, 3e-3);
  // δ → −∞: Z − δ ≈ |δ| (1 + Z/|δ|), so N ∝ 1 + (3/2) Z/|δ| and CV → (3/2)/|δ|, with a
  // relative correction O(1/δ²) (1e-4 at δ = −100).
  EXPECT_NEAR(load_cv_at_separation(-100.0) / 0.015, 1.0, 1e-3);
  // Monotone in between (the solve relies on it).
  double previous = 0.0;
  for (double d = -20.0; d <= 8.0; d += 0.25) {
    const double cv = load_cv_at_separation(d);
    EXPECT_GT(cv, previous) << "delta " << d;
    previous = cv;
  }
}

TEST(LoadSpread, TheSeparationGivesTheAskedCv) {
  for (double cv : {0.01, 0.2, 0.4, 0.6, 1.0, 1.4})
    EXPECT_NEAR(load_cv_at_separation(separation_for_load_cv(cv)), cv, 1e-12 * std::max(1.0, cv)) << "cv " << cv;
}

TEST(LoadSpread, SampledLoadsHaveTheLawsMeanAndCv) {
  // 4e5 draws: the sample mean's relative standard error is CV/√n ≤ 1e-3 and the sample
  // CV's is below ~3e-3 for these laws (their kurtosis is moderate); 5 standard errors
  // each way keeps a correct sampler from failing by chance.
  constexpr std::size_t DRAWS = 400'000;
  for (double cv : {0.0, 0.2, 0.6}) {
    const LoadSpread spread(1e-3, cv);
    RandomEngine engine = random_stream(7, 0, StreamKind::heights);
    double sum = 0.0, squares = 0.0;
    bool above = true;
    for (std::size_t i = 0; i < DRAWS; ++i) {
      const LoadedSummit s = spread.draw(engine);
      sum += s.load_n;
      squares += s.load_n * s.load_n;
      above = above && s.height_score > spread.separation() && s.load_n > 0.0;
    }
    const double mean = sum / DRAWS;
    const double sample_cv = std::sqrt(std::max(0.0, squares / DRAWS - mean * mean)) / mean;
    EXPECT_TRUE(above) << "a summit in contact below the separation, or without load";
    // cv = 0: every load is N̄ exactly; the moments' round-off (~1e-6 of CV from
    // E[N²] − E[N]², and ~4e-11 of the mean from summing 4e5 terms) is all that is left.
    EXPECT_NEAR(mean / 1e-3, 1.0, 5.0 * cv / std::sqrt(DRAWS) + 1e-10) << "cv " << cv;
    EXPECT_NEAR(sample_cv, cv, 0.015 * cv + 1e-5) << "cv " << cv;
  }
}

}  // namespace
}  // namespace stengmc
