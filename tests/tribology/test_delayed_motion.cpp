// Contact onset (`onset_s`, docs/model.md §1.3): before it the asperity rests at x(0),
// carried by nothing; from it on, the motion from rest at t = 0 shifted (the equation does
// not hold t). Compared against that closed relation on the dense output of an undelayed
// run, and against the circuit's own physics before the onset (no motion: no current).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/error.hpp"
#include "model/delayed_motion.hpp"
#include "pipeline/run_study.hpp"
#include "pipeline/study.hpp"

namespace stengmc {
namespace {

std::string study_text(const std::string& onsets) {
  return "duration_s = 20e-6\nsample_rate_hz = 100e6\n[model]\nkind = \"model2\"\nbelt_velocity_m_per_s = 10\n"
         "[surface]\n[surface.defaults]\nlength_m = 50e-6\n"
         "[[surface.asperity]]\nstiffness_n_per_m = 75\n" + onsets +
         "[[surface.asperity]]\nstiffness_n_per_m = 155\n";
}

TEST(DelayedMotion, AnOnsetShiftsTheMotionAndRestsBeforeIt) {
  // 3.27 us: not a sample time, so the onset falls between samples and midpoints.
  constexpr double ONSET = 3.27e-6;
  const RunResult late = run_study(parse_study(study_text("onset_s = 3.27e-6\n"), "late.toml"), RunOptions{.show_progress = false});
  const RunResult now = run_study(parse_study(study_text(""), "now.toml"), RunOptions{.show_progress = false});
  const Trajectory& delayed = late.trajectories[0];
  const Motion& reference = *now.trajectories[0].motion;
  double worst = 0.0, scale = 0.0;
  for (std::size_t j = 0; j < late.times_s.size(); ++j) {
    const double t = late.times_s[j];
    if (t < ONSET) {
      // At rest and carried by nothing: exactly.
      ASSERT_EQ(delayed.x_m[j], 0.0) << j;
      ASSERT_EQ(delayed.v_m_per_s[j], 0.0) << j;
      ASSERT_EQ(delayed.friction_n[j], 0.0) << j;
      continue;
    }
    // From the onset: the undelayed motion at t - onset. The two integrations take the same
    // steps from the same state (only the last step differs: they end at different times),
    // so the dense outputs agree to rounding, far inside the integrator's 1e-8 tolerance.
    const PhasePoint p = reference.at(t - ONSET);
    worst = std::max(worst, std::abs(delayed.x_m[j] - p.x_m));
    scale = std::max(scale, std::abs(p.x_m));
  }
  std::printf("onset: largest |x - x_0(t - t_on)| = %.3e of max |x| %.3e\n", worst, scale);
  EXPECT_LT(worst, 1e-9 * scale);
  // The k = 155 N/m asperity without an onset is unchanged by the other's.
  EXPECT_EQ(late.trajectories[1].x_m, now.trajectories[1].x_m);
  // Events are shifted too: the first event of the delayed asperity, if any, is after the onset.
  for (const Event& e : late.events)
    if (e.asperity == 0) {
      EXPECT_GE(e.time_s, ONSET);
    }
}

TEST(DelayedMotion, BeforeTheOnsetTheOnlyElementInTheCircuitCarriesNoCurrent) {
  // One asperity, onset at 5 us: nothing moves before it, so V = 0 and Q = 0 exactly there
  // (the circuit's right-hand side is sigma w x' + ... with x' = 0 and V = 0).
  const std::string text = "duration_s = 10e-6\nsample_rate_hz = 100e6\n[model]\nkind = \"model2\"\n"
                           "belt_velocity_m_per_s = 10\n[surface]\n[surface.defaults]\nlength_m = 50e-6\n"
                           "[[surface.asperity]]\nstiffness_n_per_m = 75\nonset_s = 5e-6\n";
  const RunResult result = run_study(parse_study(text, "one.toml"), RunOptions{.show_progress = false});
  double before = 0.0, after = 0.0;
  for (std::size_t j = 0; j < result.times_s.size(); ++j)
    (result.times_s[j] < 5e-6 ? before : after) = std::max(result.times_s[j] < 5e-6 ? before : after, std::abs(result.circuit.voltage_v[j]));
  EXPECT_EQ(before, 0.0);
  EXPECT_GT(after, 1e-3);  // it does slide after its onset (V ~ R sigma w v_b = 8 mV)
}

TEST(DelayedMotion, SamplesAreTheInnerMotionsSamplesShiftedAndRestBeforeTheOnset) {
  // The grid 0, 10 ns, ... with the onset at 3.27 us: the samples from the onset on are the
  // undelayed motion's own sampling at t - 3.27 us (its fast path on a uniform grid), and
  // the midpoint straddling the onset is the motion evaluated there.
  const RunResult late = run_study(parse_study(study_text("onset_s = 3.27e-6\n"), "late.toml"), RunOptions{.show_progress = false});
  const RunResult now = run_study(parse_study(study_text(""), "now.toml"), RunOptions{.show_progress = false});
  const Motion& motion = *late.trajectories[0].motion;
  MotionSamples samples, inner;
  motion.sample(late.times_s, true, samples);
  std::vector<double> shifted;
  std::size_t first = 0;
  while (late.times_s[first] < 3.27e-6) ++first;
  for (std::size_t j = first; j < late.times_s.size(); ++j) shifted.push_back(late.times_s[j] - 3.27e-6);
  now.trajectories[0].motion->sample(shifted, true, inner);
  ASSERT_EQ(samples.x_m.size(), late.times_s.size());
  ASSERT_EQ(samples.mid_x_m.size(), late.times_s.size() - 1);
  int mismatches = 0;
  // The two integrations differ in their last step only (they end at different times):
  // the last 2 us (more than a natural period, the longest step) are left out.
  const std::size_t compared = late.times_s.size() - 200;
  for (std::size_t j = 0; j < compared; ++j) {
    const double x = j < first ? 0.0 : inner.x_m[j - first];
    const double v = j < first ? 0.0 : inner.v_m_per_s[j - first];
    mismatches += samples.x_m[j] != x || samples.v_m_per_s[j] != v;
    const double mid = j + 1 < first ? 0.0 : j + 1 == first ? motion.at(0.5 * (late.times_s[j] + late.times_s[j + 1])).x_m
                                                             : inner.mid_x_m[j - first];
    mismatches += samples.mid_x_m[j] != mid;
  }
  EXPECT_EQ(mismatches, 0);
  ASSERT_FALSE(motion.breakpoints().empty());
  EXPECT_EQ(motion.breakpoints().front(), 3.27e-6);  // the circuit never steps across the onset
}

TEST(DelayedMotion, OnsetIsRefusedWhereItHasNoMeaning) {
  // Model 1's drive acts from t = 0; an asperity at rest until its onset cannot move at t = 0.
  const std::string model1 = "duration_s = 20e-6\nsample_rate_hz = 100e6\n[model]\nkind = \"model1\"\n"
                             "[surface]\n[[surface.asperity]]\nstiffness_n_per_m = 75\nonset_s = 1e-6\n";
  EXPECT_THROW(parse_study(model1, "m1.toml"), InputError);
  EXPECT_THROW(parse_study(study_text("onset_s = 1e-6\ninitial_velocity_m_per_s = 1\n"), "v.toml"), InputError);
  EXPECT_THROW(parse_study(study_text("onset_s = -1e-6\n"), "n.toml"), InputError);
}

}  // namespace
}  // namespace stengmc
