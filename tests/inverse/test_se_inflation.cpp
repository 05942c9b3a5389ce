// The ln k error's inflation by the other atoms (inverse/se_inflation.hpp) against closed
// forms of small Gaussian posteriors: for two parameters of correlation r the joint variance
// is the conditional one over 1 - r^2; a correlation with a shared parameter, which stays free
// in both, inflates nothing; an atom's own block (its load) stays free too.
#include <gtest/gtest.h>

#include <cmath>

#include "inverse/se_inflation.hpp"

namespace stengmc {
namespace {

TEST(SeInflation, IndependentAtomsAreNotInflated) {
  Eigen::MatrixXd h = Eigen::MatrixXd::Zero(2, 2);
  h(0, 0) = 4.0e6, h(1, 1) = 9.0e4;
  EXPECT_DOUBLE_EQ(se_inflation(h, 0, 1, 0, h.inverse()(0, 0)), 1.0);
  EXPECT_DOUBLE_EQ(se_inflation(h, 1, 1, 0, h.inverse()(1, 1)), 1.0);
}

TEST(SeInflation, TwoCorrelatedAtomsGiveOneOverTheRootOfOneMinusRSquared) {
  for (double r : {0.3, 0.6, 0.99}) {
    // A curvature of unit diagonal and off-diagonal r, scaled unequally: the ratio of errors
    // does not depend on the scales.
    Eigen::MatrixXd h(2, 2);
    h << 1.0, r, r, 1.0;
    const Eigen::Vector2d scale(1e3, 2e-2);
    h = scale.asDiagonal() * h * scale.asDiagonal();
    EXPECT_NEAR(se_inflation(h, 0, 1, 0, h.inverse()(0, 0)), 1.0 / std::sqrt(1.0 - r * r), 1e-9) << "r = " << r;
    EXPECT_NEAR(se_inflation(h, 1, 1, 0, h.inverse()(1, 1)), 1.0 / std::sqrt(1.0 - r * r), 1e-9) << "r = " << r;
  }
}

TEST(SeInflation, SharedParametersAndTheAtomsOwnLoadStayFree) {
  // Atoms of (ln k, ln N) each, then one shared parameter (the damping), unit diagonal. Atom 0's
  // ln k correlates with its own load (0.6) and with the shared parameter (0.4) only: no other
  // atom takes part, so the error is not inflated.
  Eigen::MatrixXd h = Eigen::MatrixXd::Identity(5, 5);
  h(0, 1) = h(1, 0) = 0.6;
  h(0, 4) = h(4, 0) = 0.4;
  EXPECT_NEAR(se_inflation(h, 0, 2, 1, h.inverse()(0, 0)), 1.0, 1e-12);
  // Atom 1's load trades with atom 0's stiffness (0.4). In this star (only ln k_0 correlates,
  // with parameters of unit variance) the precision of ln k_0 is 1 - sum of r^2: jointly
  // 1 - 0.36 - 0.16 - 0.16, with atom 1 known 1 - 0.36 - 0.16.
  h(0, 3) = h(3, 0) = 0.4;
  EXPECT_NEAR(se_inflation(h, 0, 2, 1, h.inverse()(0, 0)), std::sqrt(0.48 / 0.32), 1e-12);
}

TEST(SeInflation, ACurvatureThatIsNotPositiveDefiniteGivesOneNotNaN) {
  Eigen::MatrixXd h(2, 2);
  h << 1.0, 2.0, 2.0, 1.0;
  EXPECT_DOUBLE_EQ(se_inflation(h, 0, 1, 0, h.inverse()(0, 0)), 1.0);
}

}  // namespace
}  // namespace stengmc
