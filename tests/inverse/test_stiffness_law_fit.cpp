// Maximum-likelihood fits of the stiffness law against samples of known laws, and the AIC
// comparison that is to tell the families apart.
#include <gtest/gtest.h>

#include <boost/random/gamma_distribution.hpp>
#include <boost/random/lognormal_distribution.hpp>
#include <boost/random/weibull_distribution.hpp>
#include <cmath>
#include <vector>

#include "core/random_stream.hpp"
#include "inverse/stiffness_law_fit.hpp"

namespace stengmc {
namespace {

template <typename Law>
std::vector<double> draws(Law law, std::uint64_t seed, std::size_t n = 4000) {
  RandomEngine engine = random_stream(seed, 0, StreamKind::stiffnesses);
  std::vector<double> out(n);
  for (double& x : out) x = law(engine);
  return out;
}

TEST(StiffnessLawFit, RecoversEachFamilyAndAicPrefersIt) {
  struct Case {
    StiffnessFamily family;
    std::vector<double> k;
    double first, second;
  };
  const std::vector<Case> cases = {
      {StiffnessFamily::lognormal, draws(boost::random::lognormal_distribution<double>(std::log(80.0), 0.4), 1), 80.0, 0.4},
      {StiffnessFamily::gamma, draws(boost::random::gamma_distribution<double>(5.0, 20.0), 2), 5.0, 20.0},
      {StiffnessFamily::weibull, draws(boost::random::weibull_distribution<double>(3.0, 90.0), 3), 3.0, 90.0}};
  for (const Case& c : cases) {
    const LawFit fit = fit_stiffness_law(c.k, c.family);
    ASSERT_TRUE(fit.fitted);
    // The 90 % Wald intervals from the observed information should hold the true parameters
    // (4000 draws: the intervals are ~+-2-3 %); this fails if the MLE or its curvature is wrong.
    EXPECT_LE(fit.interval[0][0], c.first);
    EXPECT_GE(fit.interval[0][1], c.first);
    EXPECT_LE(fit.interval[1][0], c.second);
    EXPECT_GE(fit.interval[1][1], c.second);
    // With 4000 draws the wrong families lose by far more than 10 AIC units (Burnham &
    // Anderson's "essentially no support").
    const std::vector<LawFit> ranked = compare_stiffness_laws(c.k);
    EXPECT_EQ(ranked.front().family, c.family);
    EXPECT_GT(ranked[1].aic - ranked[0].aic, 10.0);
  }
}

TEST(StiffnessLawFit, TooFewDistinctValuesFitNothing) {
  const std::vector<double> two = {50.0, 70.0, 50.0};
  EXPECT_FALSE(fit_stiffness_law(two, StiffnessFamily::lognormal).fitted);
}

}  // namespace
}  // namespace stengmc
