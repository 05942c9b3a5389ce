// The pipeline's policies and inputs: `flag` cuts the circuit at the first x = l,
// `imposed` drives the elements with x0(t), and the "never slips" note.
#include <gtest/gtest.h>

#include <cmath>

#include "core/constants.hpp"
#include "pipeline/study.hpp"
#include "pipeline/run_study.hpp"

namespace stengmc {
namespace {

// The paper's four asperities with l = 10 um at v_b = 10 m/s: the k = 25 N/m one passes l
// (it settles near mu N / k ~ 11 um, MODEL.md §1).
const char* FLAGGED = R"(duration_s = 5e-6
sample_rate_hz = 100e6
[model]
kind = "model2"
belt_velocity_m_per_s = 10
[surface]
[[surface.asperity]]
stiffness_n_per_m = 25
[[surface.asperity]]
stiffness_n_per_m = 155
[domain]
policy = "flag"
)";

TEST(RunStudy, FlagPolicyCutsTheCircuitAtTheFirstExitAndMarksTheRunInvalid) {
  const Study study = parse_study(FLAGGED, "flag.toml");
  const RunResult result = run_study(study);
  EXPECT_FALSE(result.valid);
  ASSERT_EQ(result.events.size(), 1u);
  const Event& exit = result.events.front();
  EXPECT_EQ(exit.kind, EventKind::domain_exit);
  EXPECT_EQ(exit.asperity, 0u);
  // The exit is located on the dense output: x(t_exit) = l to rounding (bisection to
  // adjacent doubles; x' ~ 10 m/s x 1 ulp of 1e-6 s ~ 2e-21 m).
  EXPECT_NEAR(result.trajectories[0].motion->at(exit.time_s).x_m, 10e-6, 1e-15);
  // The circuit covers exactly the samples before the exit.
  ASSERT_GT(result.circuit_samples, 1u);
  EXPECT_LT(result.circuit_samples, result.times_s.size());
  EXPECT_LT(result.times_s[result.circuit_samples - 1], exit.time_s);
  EXPECT_GE(result.times_s[result.circuit_samples], exit.time_s);
  EXPECT_EQ(result.circuit.voltage_v.size(), result.circuit_samples);
  EXPECT_EQ(result.circuit.current_a.at(1).size(), result.circuit_samples);
  // The tribology itself is complete.
  EXPECT_EQ(result.trajectories[1].x_m.size(), result.times_s.size());
}

TEST(RunStudy, ASurfaceOfNoSummitsRecordsTheMeasurementChainAlone) {
  // A fixed count of 0 (MODEL.md §4.1): nothing slides, V = Q = 0 exactly, and the measured
  // voltage is the chain's noise at the level its reference gives (sigma = 1e-3 / 10).
  const Study study = parse_study(R"(duration_s = 10e-6
sample_rate_hz = 100e6
[model]
kind = "model2"
belt_velocity_m_per_s = 10
[surface]
kind = "random"
nominal_area_m2 = 1e-6
[surface.summits]
count_rule = "fixed"
count = 0
[surface.heights]
kind = "fixed"
values = [110e-6]
[surface.stiffness]
kind = "uniform"
min = 10
max = 155
[surface.load]
rule = "fixed"
[noise]
snr_db = 20
reference_rms_v = 1e-3
[spectrum]
)", "empty.toml");
  const RunResult result = run_study(study);
  EXPECT_TRUE(result.valid);
  EXPECT_TRUE(study.asperities.empty());
  ASSERT_EQ(result.circuit.voltage_v.size(), result.times_s.size());
  for (std::size_t j = 0; j < result.times_s.size(); ++j) {
    ASSERT_EQ(result.circuit.voltage_v[j], 0.0);
    ASSERT_EQ(result.circuit.charge_c[j], 0.0);
  }
  EXPECT_NEAR(result.noise_sigma_v, 1e-4, 1e-18);
  ASSERT_EQ(result.measured_voltage_v.size(), result.times_s.size());
}

TEST(RunStudy, ImposedInputGivesTheQuasiStaticVoltageOfTheDrive) {
  // Fig. 3c: the element driven by x0 = A sin(omega t). With a small load the voltage is
  // quasi-static, V = R sigma w x0' (MODEL.md §2), here R sigma w A omega cos(omega t);
  // the leading correction is relative ~ omega R C + R eps0 w x'/d0 ~ 1e-9 at R = 1 kOhm,
  // and the start-up transient (R C ~ 2e-14 s) is over by the first sample.
  const Study study = parse_study(R"(duration_s = 100e-6
sample_rate_hz = 20e6
[model]
kind = "model1"
[surface]
[[surface.asperity]]
stiffness_n_per_m = 155
drive_phase_rad = 0.3
[circuit]
load_resistance_ohm = 1e3
input = "imposed"
)", "imposed.toml");
  const RunResult result = run_study(study);
  const Asperity& a = study.asperities[0];
  const double amplitude = study.circuit.load_resistance_ohm * a.element.charge_density_c_per_m2 * a.element.width_m *
                           study.model1.drive_amplitude_m * study.model1.drive_angular_frequency_rad_per_s;
  double worst = 0.0;
  for (std::size_t j = 1; j < result.times_s.size(); ++j) {
    const double expected = amplitude * std::cos(study.model1.drive_angular_frequency_rad_per_s * result.times_s[j] + 0.3);
    worst = std::max(worst, std::abs(result.circuit.voltage_v[j] - expected));
  }
  EXPECT_LT(worst / amplitude, 1e-6);
}

TEST(RunStudy, NeverSlipsNoteOnlyWhenTheAsperityReallyNeverMoves) {
  const std::string base = R"(duration_s = 100e-6
sample_rate_hz = 20e6
[model]
kind = "model1"
[surface]
[[surface.asperity]]
stiffness_n_per_m = 10
)";
  // Table 1: mu_s N / k = 28 um > A = 9 um, so it never slips (MODEL.md §1).
  const RunResult still = run_study(parse_study(base, "k10.toml"));
  ASSERT_EQ(still.notes.size(), 1u);
  EXPECT_NE(still.notes[0].find("never slips"), std::string::npos);
  // Started 25 um off, the spring exceeds static friction at once: it moves, no note.
  const RunResult moved = run_study(parse_study(base + "initial_displacement_m = -25e-6\n", "k10-moved.toml"));
  EXPECT_TRUE(moved.notes.empty()) << moved.notes.front();
}

}  // namespace
}  // namespace stengmc
