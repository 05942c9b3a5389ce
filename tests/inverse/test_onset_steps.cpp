// Contact onsets read as the steps they make (inverse/onset_steps.hpp), on records simulated by
// the project's forward model (Model 2 and the shared circuit, Table 1-2 asperities at
// v_b = 10 m/s, 100 MHz) against the onsets written into them. The closed form checked: every
// onset raises U = R sigma w v_b sum u_i by one unit within the ramp m v_b / F (36 ns), whatever
// the asperity's stiffness, so the step's height is 1 per asperity and it sits at the onset.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "core/format.hpp"
#include "inverse/onset_steps.hpp"
#include "support/simulated_device_record.hpp"
#include "support/table1_study.hpp"

namespace stengmc {
namespace {

//! The prior's stiffest line the detector is told of [N/m] (the test's asperities stay below).
constexpr double STIFFEST_N_PER_M = 300.0;

using testing::Simulated;

//! Asperities of stiffness k[i] from onset[i], 30 us at 100 MHz on a belt at 10 m/s, plus white
//! noise of SNR `snr_db` over the mean-removed clean voltage (seeded).
Simulated simulate(const std::vector<double>& k, const std::vector<double>& onset_s, double snr_db = 30.0,
                   const std::string& load_capacitance = "0") {
  std::string text = "duration_s = 30e-6\nseed = 5\nsample_rate_hz = 100e6\n" +
                     testing::table1_device_keys({.belt_velocity_m_per_s = "10"});
  const std::string zero_load = "load_capacitance_f = 0";
  text.replace(text.find(zero_load), zero_load.size(), "load_capacitance_f = " + load_capacitance);
  for (std::size_t i = 0; i < k.size(); ++i)
    text += "[[surface.asperity]]\nstiffness_n_per_m = " + format_number(k[i]) + "\nonset_s = " + format_number(onset_s[i]) + "\n";
  return testing::simulate(text, snr_db, 7);
}

std::vector<OnsetStep> steps_of(const Simulated& s) {
  return onset_steps(s.device, STIFFEST_N_PER_M, s.noise_sigma_v, s.grid, s.voltage);
}

TEST(OnsetSteps, EachOnsetIsAOneUnitStepAtItsTime) {
  const std::vector<double> onsets{3.0e-6, 7.5e-6, 12.25e-6, 16.0e-6, 21.7e-6};
  const Simulated s = simulate({40, 70, 110, 160, 55}, onsets);
  const std::vector<OnsetStep> found = steps_of(s);
  ASSERT_EQ(found.size(), onsets.size());
  for (std::size_t i = 0; i < onsets.size(); ++i) {
    EXPECT_NEAR(found[i].onset_s, onsets[i], 2.0 * s.grid.step_s) << "step " << i;
    EXPECT_NEAR(found[i].units, 1.0, 0.3) << "step " << i;
  }
}

TEST(OnsetSteps, TwoAsperitiesAtOnceMakeAStepOfTwoUnits) {
  const Simulated s = simulate({45, 90, 130}, {5.0e-6, 5.0e-6, 10.0e-6});
  const std::vector<OnsetStep> found = steps_of(s);
  ASSERT_EQ(found.size(), 2u);
  EXPECT_NEAR(found[0].onset_s, 5.0e-6, 2.0 * s.grid.step_s);
  EXPECT_EQ(std::lround(found[0].units), 2);
  EXPECT_NEAR(found[1].onset_s, 10.0e-6, 2.0 * s.grid.step_s);
  EXPECT_EQ(std::lround(found[1].units), 1);
}

// Every asperity in contact from t = 0: their breakaways (kinks) and oscillations, six lines
// beating, are no steps, and the start's ramp is left to the start plateau.
TEST(OnsetSteps, NoStepWhereEveryAsperityStartsWithTheRecord) {
  const Simulated s = simulate({30, 48, 66, 95, 130, 170}, {0, 0, 0, 0, 0, 0});
  EXPECT_TRUE(steps_of(s).empty());
}

TEST(OnsetSteps, NoStepInPureNoise) {
  const Simulated s = simulate({60}, {2.0e-6});
  std::vector<double> noise(s.voltage.size());
  std::mt19937_64 rng(11);
  std::normal_distribution<double> normal(0.0, s.noise_sigma_v);
  for (double& v : noise) v = normal(rng);
  EXPECT_TRUE(onset_steps(s.device, STIFFEST_N_PER_M, s.noise_sigma_v, s.grid, noise).empty());
}

// A load capacitance whose R C_L (100 ns) is slower than the ramp rounds every step into the
// load's exponential: the record cannot show the ramps, and the detector says so (none) rather
// than read them with the wrong shape.
TEST(OnsetSteps, NoneReadThroughALoadSlowerThanTheRamp) {
  const Simulated s = simulate({60, 100}, {4.0e-6, 9.0e-6}, 30.0, "100e-15");
  EXPECT_TRUE(steps_of(s).empty());
}

}  // namespace
}  // namespace stengmc
