// The work estimate (pipeline/work_estimate) must bound what a run really does, or a
// limit would let through what it is meant to stop: each test runs a computation and
// compares the estimate with what it counted or measured.
//  - events: the estimate is >= the events Model 1 and Model 2 actually produced, over
//    drive frequencies below, near and above the natural frequency;
//  - Model 2 steps: >= the integrator's accepted + rejected steps (/asperity/solver_steps)
//    at two belt speeds and two tolerances;
//  - memory: >= the peak resident memory of the real `stengmc run` (getrusage of the child)
//    and not wildly above it (<= 3 x), so a limit refuses only what would not fit.
#include <gtest/gtest.h>

#include <string>

#include "core/format.hpp"
#include "pipeline/study.hpp"
#include "pipeline/run_study.hpp"
#include "pipeline/work_estimate.hpp"
#include "support/cli_runner.hpp"
#include "support/peak_memory.hpp"

namespace stengmc {
namespace {

std::string model1_study(double drive_hz, double duration_s) {
  return "duration_s = " + std::to_string(duration_s) + "\nsample_rate_hz = 20e6\n[model]\nkind = \"model1\"\n" +
         "drive_frequency_hz = " + std::to_string(drive_hz) + "\ndrive_amplitude_m = 20e-6\n" +
         "[surface]\n[surface.defaults]\nlength_m = 1\n[[surface.asperity]]\nstiffness_n_per_m = 155\n"
         "[[surface.asperity]]\nstiffness_n_per_m = 25\nnormal_load_n = 1e-4\n";
}

TEST(WorkEstimate, Model1EventsBoundTheEventsOfARun) {
  // Natural frequencies 1.98 and 0.8 MHz; drives from 10 kHz to 3 MHz.
  for (const double drive_hz : {1e4, 3e5, 1e6, 3e6}) {
    SCOPED_TRACE(drive_hz);
    const Study study = parse_study(model1_study(drive_hz, 100e-6), "events.toml");
    const RunResult result = run_study(study, RunOptions{.show_progress = false});
    ASSERT_GT(result.events.size(), 0u);
    EXPECT_GE(estimate_run(study).events, static_cast<double>(result.events.size()));
  }
}

TEST(WorkEstimate, Model2StepsAndEventsBoundTheIntegrators) {
  for (const double belt : {1.0, 10.0})
    for (const double tolerance : {1e-8, 1e-10}) {
      SCOPED_TRACE(std::to_string(belt) + " m/s, tol " + std::to_string(tolerance));
      const std::string text = "duration_s = 50e-6\nsample_rate_hz = 100e6\n[model]\nkind = \"model2\"\n"
                               "belt_velocity_m_per_s = " + std::to_string(belt) +
                               "\nrelative_tolerance = " + format_number(tolerance) +
                               "\n[surface]\nfile = \"" + std::string(STENGMC_SOURCE_DIR) +
                               "/surfaces/paper_four_stiffnesses_l50.toml\"\n";
      const Study study = parse_study(text, std::string(STENGMC_SOURCE_DIR) + "/studies/paper/steps.toml");
      const RunResult result = run_study(study, RunOptions{.show_progress = false});
      double steps = 0.0;
      for (const Trajectory& t : result.trajectories) steps += static_cast<double>(t.solver_steps);
      const WorkEstimate estimate = estimate_run(study);
      double model2_steps = 0.0;
      for (const WorkPart& part : estimate.work)
        if (part.what.rfind("Model 2", 0) == 0) model2_steps += part.amount;
      EXPECT_GE(model2_steps, steps);
      EXPECT_GE(estimate.events, static_cast<double>(result.events.size()));
    }
}


TEST(WorkEstimate, MemoryBoundsThePeakOfARealRunWithinAFactorOfThree) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "AddressSanitizer's shadow memory and redzones are not what the estimate is of";
#endif
  testing::ScratchDir scratch("work-memory");
  // ~2e6 asperity-samples with every trace written: ~300 MB, so the program's own
  // footprint does not dominate.
  const std::string text = "duration_s = 5e-3\nsample_rate_hz = 100e6\n[model]\nkind = \"model1\"\n"
                           "[surface]\n[[surface.asperity]]\nstiffness_n_per_m = 155\ncount = 4\n";
  const std::string study = scratch.write("memory.toml", text);
  const double measured = testing::peak_memory_of("run " + study + " -o " + scratch.file("out.h5"));
  const double estimated = estimate_run(parse_study(text, study)).memory_bytes;
  EXPECT_GE(estimated, measured);
  EXPECT_LE(estimated, 3.0 * measured);
  RecordProperty("measured_bytes", std::to_string(measured));
  RecordProperty("estimated_bytes", std::to_string(estimated));
}

}  // namespace
}  // namespace stengmc
