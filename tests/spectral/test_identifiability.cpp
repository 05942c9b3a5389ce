// Optimal assignment (Hungarian method) against brute force, and the identifiability rule of
// MODEL.md §3 on hand-made cases whose answer follows from the rule's wording.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>
#include <vector>

#include "core/error.hpp"
#include "spectral/assignment.hpp"
#include "spectral/identifiability.hpp"

namespace stengmc {
namespace {

constexpr double INF = std::numeric_limits<double>::infinity();

//! What an assignment achieves: first the number of allowed (finite) pairs, to maximise,
//! then their total cost, to minimise.
struct Score {
  int pairs = 0;
  double cost = 0.0;
};

//! Brute force over every injective map of the shorter side into the longer one.
Score best_by_enumeration(const Eigen::MatrixXd& cost) {
  const bool transposed = cost.rows() > cost.cols();
  const Eigen::MatrixXd a = transposed ? Eigen::MatrixXd(cost.transpose()) : cost;
  std::vector<int> perm(static_cast<std::size_t>(a.cols()));
  std::iota(perm.begin(), perm.end(), 0);
  Score best{-1, 0.0};
  do {
    Score s;
    for (Eigen::Index r = 0; r < a.rows(); ++r) {
      const double c = a(r, perm[static_cast<std::size_t>(r)]);
      if (std::isinf(c)) continue;
      ++s.pairs;
      s.cost += c;
    }
    if (s.pairs > best.pairs || (s.pairs == best.pairs && s.cost < best.cost)) best = s;
  } while (std::next_permutation(perm.begin(), perm.end()));
  return best;
}

//! Scores the Hungarian answer and checks that it is a valid partial assignment.
Score score_of(const Eigen::MatrixXd& cost, const std::vector<int>& assigned) {
  EXPECT_EQ(assigned.size(), static_cast<std::size_t>(cost.rows()));
  std::vector<bool> taken(static_cast<std::size_t>(cost.cols()), false);
  Score s;
  for (std::size_t r = 0; r < assigned.size(); ++r) {
    const int c = assigned[r];
    if (c < 0) continue;
    EXPECT_LT(c, cost.cols());
    EXPECT_FALSE(taken[static_cast<std::size_t>(c)]) << "column " << c << " used twice";
    taken[static_cast<std::size_t>(c)] = true;
    EXPECT_FALSE(std::isinf(cost(static_cast<Eigen::Index>(r), c))) << "forbidden pair reported";
    ++s.pairs;
    s.cost += cost(static_cast<Eigen::Index>(r), c);
  }
  return s;
}

void check_against_brute_force(double forbidden_probability, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<int> size(1, 7);
  std::uniform_real_distribution<double> value(-5.0, 10.0);
  std::bernoulli_distribution forbidden(forbidden_probability);
  for (int trial = 0; trial < 400; ++trial) {
    // Up to 6 x 7 and 7 x 6: both orientations of the rectangular case.
    int rows = size(rng), cols = size(rng);
    if (rows == 7 && cols == 7) cols = 6;
    Eigen::MatrixXd cost(rows, cols);
    for (int i = 0; i < rows; ++i)
      for (int j = 0; j < cols; ++j) cost(i, j) = forbidden(rng) ? INF : value(rng);
    const Score expected = best_by_enumeration(cost);
    const Score got = score_of(cost, hungarian_assignment(cost));
    ASSERT_EQ(got.pairs, expected.pairs) << rows << "x" << cols << " trial " << trial << "\n" << cost;
    // Sums of <= 7 numbers of size ~10 in a different order: rounding ~1e-14.
    ASSERT_NEAR(got.cost, expected.cost, 1e-10) << rows << "x" << cols << " trial " << trial << "\n" << cost;
  }
}

TEST(Hungarian, MatchesBruteForceOnRandomMatrices) { check_against_brute_force(0.0, 1); }

TEST(Hungarian, MatchesBruteForceWithForbiddenPairs) {
  check_against_brute_force(0.3, 2);
  check_against_brute_force(0.7, 3);
}

TEST(Hungarian, BeatsGreedyAndReportsForbiddenRowsAsUnassigned) {
  // Greedy would give row 0 column 0 (cost 1), forcing row 1 onto 100; the optimum is 2 + 3.
  Eigen::MatrixXd cost(2, 2);
  cost << 1, 2, 3, 100;
  EXPECT_EQ(hungarian_assignment(cost), (std::vector<int>{1, 0}));
  // Row 1 can only take column 0; row 0 must then take column 1 although column 0 is cheaper.
  cost << 1, 2, 3, INF;
  EXPECT_EQ(hungarian_assignment(cost), (std::vector<int>{1, 0}));
  // Both rows want only column 0: one gets it, the other is -1.
  cost << 1, INF, 2, INF;
  EXPECT_EQ(hungarian_assignment(cost), (std::vector<int>{0, -1}));
  cost.setConstant(INF);
  EXPECT_EQ(hungarian_assignment(cost), (std::vector<int>{-1, -1}));
  EXPECT_TRUE(hungarian_assignment(Eigen::MatrixXd(3, 0)) == std::vector<int>(3, -1));
  cost << 1, std::numeric_limits<double>::quiet_NaN(), 1, 1;
  EXPECT_THROW(hungarian_assignment(cost), InputError);
}

// --- identifiability ---------------------------------------------------------------------

const std::vector<double> FIG6 = {0.796e6, 1.125e6, 1.592e6, 1.981e6};  // Table 1 lines [Hz]

Identifiability assess(const std::vector<double>& expected, const std::vector<bool>& sliding,
                       const std::vector<double>& detected) {
  const std::vector<double> amplitude(detected.size(), 1.0);
  return assess_identifiability(expected, sliding, detected, amplitude, IdentifiabilityOptions{});
}

TEST(Identifiability, AllLinesPresentAllIdentified) {
  // Detected lines 0.3 % off (inside the 2 % tolerance), listed out of order.
  const std::vector<double> detected = {1.981e6 * 1.003, 0.796e6 * 0.997, 1.592e6, 1.125e6 * 1.003};
  const std::vector<double> amplitude = {4.0, 1.0, 3.0, 2.0};
  const auto r = assess_identifiability(FIG6, std::vector<bool>(4, true), detected, amplitude, IdentifiabilityOptions{});
  EXPECT_EQ(r.n_sliding, 4u);
  EXPECT_EQ(r.n_detected, 4u);
  EXPECT_EQ(r.n_identifiable, 4u);
  EXPECT_DOUBLE_EQ(r.ratio, 1.0);
  EXPECT_EQ(r.matched_line, (std::vector<int>{1, 3, 2, 0}));
  EXPECT_NEAR(r.frequency_error_hz[0], -0.003 * 0.796e6, 1e-6);
  EXPECT_NEAR(r.frequency_error_hz[2], 0.0, 1e-9);
  EXPECT_EQ(r.amplitude, (std::vector<double>{1.0, 2.0, 3.0, 4.0}));
}

TEST(Identifiability, MissingLineLeavesItsAsperityUnidentified) {
  const auto r = assess(FIG6, std::vector<bool>(4, true), {0.796e6, 1.592e6, 1.981e6});
  EXPECT_EQ(r.n_identifiable, 3u);
  EXPECT_DOUBLE_EQ(r.ratio, 0.75);
  EXPECT_FALSE(r.identified[1]);
  EXPECT_EQ(r.matched_line[1], -1);
  EXPECT_EQ(r.frequency_error_hz[1], 0.0);
  EXPECT_EQ(r.amplitude[1], 0.0);
  // A line just outside the tolerance (2.1 % off) is no line for that asperity.
  const auto outside = assess(FIG6, std::vector<bool>(4, true), {0.796e6, 1.125e6 * 1.021, 1.592e6, 1.981e6});
  EXPECT_FALSE(outside.identified[1]);
  EXPECT_EQ(outside.n_identifiable, 3u);
}

TEST(Identifiability, TwoAsperitiesOnOneLineCountOnce) {
  // Both have exactly one line within tolerance; the one-to-one matching gives it to one of
  // them, which MODEL.md §3 then counts ("matched to no other asperity"); the other is not.
  const auto r = assess({1.0e6, 1.0e6, 2.0e6}, std::vector<bool>(3, true), {1.001e6, 2.0e6});
  EXPECT_EQ(r.n_identifiable, 2u);
  EXPECT_TRUE(r.identified[0] != r.identified[1]);
  EXPECT_TRUE(r.identified[2]);
  EXPECT_EQ(r.matched_line[0] + r.matched_line[1], -1);  // one has line 0, the other none
}

TEST(Identifiability, SpuriousSecondLineWithinToleranceMakesItAmbiguous) {
  // Two lines within 2 % of 1.125 MHz: the assignment takes the closer one, but the
  // spectrum alone cannot say which is the asperity's, so it is not identified.
  const auto r = assess(FIG6, std::vector<bool>(4, true), {0.796e6, 1.120e6, 1.126e6, 1.592e6, 1.981e6});
  EXPECT_EQ(r.n_detected, 5u);
  EXPECT_FALSE(r.identified[1]);
  EXPECT_EQ(r.matched_line[1], 2);  // the closer line, reported though not identified
  EXPECT_EQ(r.n_identifiable, 3u);
}

TEST(Identifiability, StickingAsperitiesAreExcluded) {
  // Asperity 0 sticks: no line expected, excluded from n_sliding, never identified, even
  // with a line at its frequency.
  const auto r = assess(FIG6, {false, true, true, true}, {0.796e6, 1.125e6, 1.592e6});
  EXPECT_EQ(r.n_sliding, 3u);
  EXPECT_FALSE(r.identified[0]);
  EXPECT_EQ(r.matched_line[0], -1);
  EXPECT_EQ(r.n_identifiable, 2u);
  EXPECT_DOUBLE_EQ(r.ratio, 2.0 / 3.0);
  const auto none = assess(FIG6, std::vector<bool>(4, false), {0.796e6});
  EXPECT_EQ(none.n_sliding, 0u);
  EXPECT_EQ(none.ratio, 0.0);
}

TEST(Identifiability, RejectsInconsistentInput) {
  const std::vector<double> one = {1.0e6};
  EXPECT_THROW(assess(FIG6, std::vector<bool>(3, true), one), InputError);
  EXPECT_THROW(assess_identifiability(FIG6, std::vector<bool>(4, true), one, {}, IdentifiabilityOptions{}), InputError);
  EXPECT_THROW(assess({-1.0}, {true}, one), InputError);
  EXPECT_THROW(assess_identifiability(one, {true}, one, one, IdentifiabilityOptions{0.0}), InputError);
}

}  // namespace
}  // namespace stengmc
