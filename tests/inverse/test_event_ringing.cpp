// The ringing an event starts (inverse/event_ringing.hpp): the closed forms for an onset, a
// stiffness step and a release against the forward model's simulated voltage of one asperity
// (no noise), its ringing after each event fitted by least squares and extrapolated back to the
// event time along e^{-gamma t}.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "inverse/event_ringing.hpp"
#include "inverse/known_device.hpp"
#include "pipeline/run_study.hpp"
#include "pipeline/study.hpp"
#include "support/table1_study.hpp"

namespace stengmc {
namespace {

//! One asperity of Table 1-2 values (belt at `belt` m/s, load 1 mN, R = 1 MOhm, C_L = 0):
//! onset at 20 us, a step k -> 1.1 k at 120 us, released at 220 us.
std::string study_text(double k, double belt) {
  return "duration_s = 300e-6\nsample_rate_hz = 100e6\nseed = 1\n" +
         testing::table1_device_keys({.belt_velocity_m_per_s = std::to_string(belt)}) + R"(
[[surface.asperity]]
stiffness_n_per_m = )" + std::to_string(k) + R"(
onset_s = 20e-6
release_s = 220e-6
stiffness_steps = [[120e-6, 1.1]]
)";
}

//! Amplitude at `event_s` of the ringing at stiffness k in [event + 2 us, event + 22 us]: least
//! squares on e^{-gamma tau} cos(omega tau), e^{-gamma tau} sin(omega tau) and a level (the
//! equilibrium), tau = t - event_s, omega the device's damped frequency of k [V].
double ringing_at(const KnownDevice& d, const RunResult& run, double event_s, double k) {
  const double gamma = d.damping_rate_per_s(), omega = d.angular_frequency(k);
  std::vector<std::size_t> rows;
  for (std::size_t i = 0; i < run.times_s.size(); ++i)
    if (run.times_s[i] >= event_s + 2e-6 && run.times_s[i] < event_s + 22e-6) rows.push_back(i);
  Eigen::MatrixXd a(static_cast<Eigen::Index>(rows.size()), 3);
  Eigen::VectorXd y(static_cast<Eigen::Index>(rows.size()));
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const double tau = run.times_s[rows[r]] - event_s;
    const auto i = static_cast<Eigen::Index>(r);
    a(i, 0) = std::exp(-gamma * tau) * std::cos(omega * tau);
    a(i, 1) = std::exp(-gamma * tau) * std::sin(omega * tau);
    a(i, 2) = 1.0;
    y(i) = run.circuit.voltage_v[rows[r]];
  }
  const Eigen::VectorXd c = a.colPivHouseholderQr().solve(y);
  return std::hypot(c(0), c(1));
}

// Each closed form within 10 % of the simulated ringing. Why 10 %: the friction's slope in
// the sliding speed adds damping the closed form leaves out (dF/dv_r = mu N (2/pi) / (s v_r^2)
// ~ 7e-9 N s/m at v_r = 5 m/s, 7 % of c, so a few % over the fitted 20 us), and an onset
// rings from its breakaway, F / (k v_b) ~ 0.5-2 us after the contact starts (e^{gamma t}:
// 2.5-10 % high when extrapolated back to the onset itself). Seen: 0-6 % off (the step at
// k = 30 N/m, near the belt's limit, 6 % low). And the three
// kinds must be told apart: a release rings 2-12 x louder than an onset in the validation's
// prior, a 10 % step about 0.5-1 x.
TEST(EventRinging, ClosedFormsMatchTheSimulatedRingingOfOneAsperity) {
  for (const double belt : {5.0, 10.0})
    for (const double k : {30.0, 60.0, 140.0}) {
      const Study study = parse_study(study_text(k, belt), "event_ringing.toml");
      RunOptions options;
      options.show_progress = false;
      options.keep_traces = false;
      const RunResult run = run_study(study, options);
      const KnownDevice d = known_device_from_study(study);
      const double onset = onset_ringing_v(d, k), step = step_ringing_v(d, k, 1.1 * k), release = release_ringing_v(d, 1.1 * k);
      const double onset_sim = ringing_at(d, run, 20e-6, k), step_sim = ringing_at(d, run, 120e-6, 1.1 * k),
                   release_sim = ringing_at(d, run, 220e-6, 1.1 * k);
      SCOPED_TRACE("k = " + std::to_string(k) + " N/m, v_b = " + std::to_string(belt) + " m/s: onset " + std::to_string(onset_sim) +
                   " V (closed form " + std::to_string(onset) + "), step " + std::to_string(step_sim) + " (" + std::to_string(step) +
                   "), release " + std::to_string(release_sim) + " (" + std::to_string(release) + ")");
      std::printf("  k %5.1f N/m v_b %4.1f m/s: onset %.4g V (closed form %.4g), step %.4g (%.4g), release %.4g (%.4g)\n", k, belt,
                  onset_sim, onset, step_sim, step, release_sim, release);
      EXPECT_NEAR(onset_sim / onset, 1.0, 0.10);
      EXPECT_NEAR(step_sim / step, 1.0, 0.10);
      EXPECT_NEAR(release_sim / release, 1.0, 0.10);
      EXPECT_GT(release, 2.0 * onset);
    }
}

// The closed forms' own limits, exactly: an onset is R sigma w v_b whatever k (the belt cuts the
// swing), a step's ringing grows with the jump and is cut at the same limit, a release falls as
// 1 / sqrt(k).
TEST(EventRinging, OnsetIsTheBeltLimitAndAStepGrowsWithItsJumpUpToIt) {
  const Study study = parse_study(study_text(60.0, 5.0), "event_ringing.toml");
  const KnownDevice d = known_device_from_study(study);
  const double limit = 1e6 * 80e-6 * 10e-6 * 5.0;
  EXPECT_NEAR(onset_ringing_v(d, 20.0), limit, 1e-12);
  EXPECT_NEAR(onset_ringing_v(d, 160.0), limit, 1e-12);
  EXPECT_NEAR(release_ringing_v(d, 40.0) / release_ringing_v(d, 160.0), 2.0, 1e-12);
  EXPECT_LT(step_ringing_v(d, 60.0, 61.0), step_ringing_v(d, 60.0, 63.0));
  EXPECT_NEAR(step_ringing_v(d, 60.0, 600.0), limit, 1e-12);
  EXPECT_DOUBLE_EQ(step_ringing_v(d, 60.0, 60.0), 0.0);
}

}  // namespace
}  // namespace stengmc
