// voltage_response (pipeline/voltage_response.hpp), the cheap single-asperity path: it
// must give exactly what the full pipeline gives for the same device (it is the same
// solvers; the chain's accuracy is tested against an independent reference in
// test_chain_reference), the same on every reuse of its workspace, and refuse x >= l.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/error.hpp"
#include "pipeline/study.hpp"
#include "pipeline/run_study.hpp"
#include "pipeline/voltage_response.hpp"

namespace stengmc {
namespace {

// The issue-11 use: one asperity of a known device, stiffness varied, 100 MHz, l = 50 um.
Study single_asperity_study(double stiffness, double belt_velocity) {
  const std::string text = "duration_s = 20e-6\nsample_rate_hz = 100e6\n[model]\nkind = \"model2\"\n"
                           "belt_velocity_m_per_s = " + std::to_string(belt_velocity) +
                           "\n[surface]\n[[surface.asperity]]\nstiffness_n_per_m = " + std::to_string(stiffness) +
                           "\nlength_m = 50e-6\n[circuit]\nload_resistance_ohm = 1e6\n";
  return parse_study(text, "single.toml");
}

TEST(VoltageResponse, EqualsTheFullPipelineBitForBitAndOnEveryReuse) {
  VoltageWorkspace workspace;
  for (int repeat = 0; repeat < 2; ++repeat) {
    for (const double stiffness : {30.0, 75.0, 150.0}) {
      for (const double belt_velocity : {5.0, 10.0}) {
        const Study study = single_asperity_study(stiffness, belt_velocity);
        const RunResult run = run_study(study, RunOptions{.show_progress = false, .keep_traces = false});
        const VoltageResponse response =
            voltage_response(study.asperities, study.model2, study.circuit, study.grid(), workspace);
        ASSERT_EQ(response.voltage_v.size(), run.circuit.voltage_v.size());
        EXPECT_TRUE(std::equal(response.voltage_v.begin(), response.voltage_v.end(), run.circuit.voltage_v.begin()))
            << "k = " << stiffness << ", v_b = " << belt_velocity;
        EXPECT_TRUE(std::equal(response.charge_c.begin(), response.charge_c.end(), run.circuit.charge_c.begin()));
        EXPECT_EQ(response.time_s.back(), run.times_s.back());
      }
    }
  }
}

TEST(VoltageResponse, SeveralAsperitiesAndOtherGridsReuseOneWorkspace) {
  // The paper's four asperities through the same workspace after single-asperity calls.
  Study four = read_study(std::string(STENGMC_SOURCE_DIR) + "/studies/paper/fig6_vb10_l50.toml");
  four.spectrum.reset();
  const RunResult run = run_study(four, RunOptions{.show_progress = false, .keep_traces = false});
  VoltageWorkspace workspace;
  const Study one = single_asperity_study(50.0, 10.0);
  (void)voltage_response(one.asperities, one.model2, one.circuit, one.grid(), workspace);
  const VoltageResponse response = voltage_response(four.asperities, four.model2, four.circuit, four.grid(), workspace);
  ASSERT_EQ(response.voltage_v.size(), run.circuit.voltage_v.size());
  EXPECT_TRUE(std::equal(response.voltage_v.begin(), response.voltage_v.end(), run.circuit.voltage_v.begin()));
}

TEST(VoltageResponse, ReachingTheElementLengthIsAModelErrorNamingTheAsperity) {
  // The paper's l = 10 um: the k = 25 N/m asperity settles near mu N / k ~ 11 um (MODEL.md §1).
  Study study = single_asperity_study(25.0, 10.0);
  study.asperities[0].element.length_m = 10e-6;
  VoltageWorkspace workspace;
  try {
    (void)voltage_response(study.asperities, study.model2, study.circuit, study.grid(), workspace);
    FAIL() << "expected ModelError";
  } catch (const ModelError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("asperity 1 (k = 25 N/m): x reaches l = 10 um"), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace stengmc
