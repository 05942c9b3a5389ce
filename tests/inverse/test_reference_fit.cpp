// The estimator's reference fit (the oracle: a given population refined in full beside the
// estimate), on a record simulated by the forward model end to end, whose truth it is given.
#include <gtest/gtest.h>

#include <boost/random/normal_distribution.hpp>
#include <cmath>
#include <cstdio>
#include <vector>

#include "core/random_stream.hpp"
#include "inverse/calibration_run.hpp"
#include "inverse/record_estimator.hpp"
#include "inverse/simulated_record.hpp"
#include "pipeline/study.hpp"
#include "support/must_show_record.hpp"

namespace stengmc {
namespace {

TEST(ReferenceFit, TheTruthRefinedFitsToTheNoiseWhereTheSearchFoundItAndChangesNoAnswer) {
  // Four asperities of unequal loads and onsets (the must-show record), white noise.
  // Closed form: at the truth's optimum the RSS is chi^2 with ~M degrees of freedom, so its
  // misfit (RSS / M sigma^2) is 1 within sqrt(2/M) = 0.014 per sd at M = 10^4, plus the
  // estimator's own error on sigma (~0.02-0.03): at most 1.07, ~2 sd of both together. Below 1
  // by the model's floor the estimator adds to sigma (a relative accuracy of the signal), far
  // below only if it misjudged the noise. The search finds these four (test_inverse_broadened),
  // so its fit of n = 4 is the same optimum: within 1 in chi^2 (the loads' prior term with it),
  // the harness's own line between "the search fails" and not.
  const InverseSetup setup = inverse_setup(testing::unequal_loads_and_onsets_study());
  const std::unique_ptr<AtomLibrary> library = build_atom_library(setup);
  const std::vector<SimulatedAsperity> truth = testing::four_unequal_loads_and_onsets(setup.device.asperity.normal_load_n);
  std::vector<double> record = simulate_record(setup.device, truth, setup.grid);
  double mean = 0.0, power = 0.0;
  for (double v : record) mean += v / static_cast<double>(record.size());
  for (double v : record) power += (v - mean) * (v - mean) / static_cast<double>(record.size());
  // 40 dB below the record's rms, the prior's highest SNR.
  RandomEngine engine = random_stream(3, 0, StreamKind::noise);
  boost::random::normal_distribution<double> noise(0.0, 1e-2 * std::sqrt(power));
  for (double& v : record) v += noise(engine);

  RecordEstimator estimator(*library, setup.prior);
  FitState reference;
  reference.damping_rate_per_s = estimator.layout().nominal_damping_rate;
  for (const SimulatedAsperity& a : truth) reference.atoms.push_back({a.stiffness_n_per_m, a.normal_load_n, a.onset_s});
  const RecordEstimate with = estimator.estimate(record, &reference);
  ASSERT_TRUE(with.reference.has_value());
  const ReferenceFit& r = *with.reference;
  std::printf("reference: start %.4f, refined %.4f (penalty %.2f) in %zu steps; the search's n = 4: %.4f (penalty %.2f)\n",
              r.start_misfit, r.misfit, r.penalty, r.iterations, r.found_misfit, r.found_penalty);
  EXPECT_LE(r.misfit, 1.0 + 5.0 * std::sqrt(2.0 / static_cast<double>(record.size())));
  EXPECT_GT(r.misfit, 0.5);
  EXPECT_LE(r.misfit, r.start_misfit);
  ASSERT_GE(r.found_misfit, 0.0);
  const double m = static_cast<double>(record.size());
  EXPECT_NEAR(r.found_misfit * m + r.found_penalty, r.misfit * m + r.penalty, 1.0) << "the search's four atoms are not the truth's optimum";

  const RecordEstimate without = estimator.estimate(record);
  EXPECT_FALSE(without.reference.has_value());
  ASSERT_EQ(with.count, without.count);
  ASSERT_EQ(with.lines.size(), without.lines.size());
  for (std::size_t i = 0; i < with.lines.size(); ++i) {
    EXPECT_EQ(with.lines[i].stiffness_n_per_m, without.lines[i].stiffness_n_per_m) << "line " << i;
    EXPECT_EQ(with.lines[i].log_stiffness_se, without.lines[i].log_stiffness_se) << "line " << i;
  }
  EXPECT_EQ(with.posterior.probability, without.posterior.probability);
  EXPECT_EQ(with.checks.misfit, without.checks.misfit);
}

}  // namespace
}  // namespace stengmc
