// The evolving contact read from a study (docs/study-files.md: [counterface], release_s,
// wear_rate_per_ms, stiffness_steps) and run: its keys, their errors, and reproducibility.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/error.hpp"
#include "pipeline/run_study.hpp"
#include "pipeline/study.hpp"
#include "pipeline/study_realisation.hpp"
#include "support/support_files.hpp"

namespace stengmc {
namespace {

// The evolving contact of tests/support/evolving_contact.toml (shared with io/test_netcdf_outputs.py).
const std::string EVOLVING = testing::support_file_text("evolving_contact.toml");  // read before any test runs

std::string error_of(std::string text, const std::string& from, const std::string& to) {
  text.replace(text.find(from), from.size(), to);
  try {
    parse_study(text, "s.toml");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(EvolvingStudy, KeysAreRead) {
  const Study s = parse_study(EVOLVING, "s.toml");
  EXPECT_EQ(s.model2.counterface.friction_modulation_rms, 0.01);
  EXPECT_EQ(s.model2.counterface.correlation_length_m, 0.5e-6);
  const Asperity& a = s.asperities.at(0);
  EXPECT_EQ(a.wear_rate_per_ms, 0.2);
  ASSERT_EQ(a.stiffness_steps.size(), 2u);
  EXPECT_EQ(a.stiffness_steps[1].time_s, 12e-6);
  EXPECT_EQ(a.stiffness_steps[1].factor, 0.95);
  EXPECT_TRUE(std::isinf(a.release_s));
  EXPECT_EQ(s.asperities.at(1).release_s, 10e-6);
}

// Every rejected value names the file, the key and what was expected.
TEST(EvolvingStudy, BadValuesAreRejectedWithTheirKey) {
  auto expect = [](const std::string& message, const std::string& key, const std::string& what) {
    EXPECT_NE(message.find("s.toml"), std::string::npos) << message;
    EXPECT_NE(message.find(key), std::string::npos) << message;
    EXPECT_NE(message.find(what), std::string::npos) << message;
  };
  expect(error_of(EVOLVING, "friction_modulation_rms = 0.01", "friction_modulation_rms = 0.3"), "friction_modulation_rms",
         "must be <= 0.25");
  expect(error_of(EVOLVING, "friction_modulation_rms = 0.01", "friction_modulation_rms = -0.1"), "friction_modulation_rms",
         ">= 0");
  expect(error_of(EVOLVING, "correlation_length_m = 0.5e-6", "correlation_length_m = 0"), "correlation_length_m", "> 0");
  expect(error_of(EVOLVING, "correlation_length_m = 0.5e-6\n", ""), "correlation_length_m", "is missing");
  expect(error_of(EVOLVING, "belt_velocity_m_per_s = 10", "belt_velocity_m_per_s = 0"), "friction_modulation_rms",
         "moving belt");
  expect(error_of(EVOLVING, "release_s = 10e-6", "release_s = 1e-6"), "release_s", "must be a finite time > onset_s");
  expect(error_of(EVOLVING, "wear_rate_per_ms = 0.2", "wear_rate_per_ms = -0.2"), "wear_rate_per_ms", ">= 0");
  expect(error_of(EVOLVING, "[[5e-6, 1.1], [12e-6, 0.95]]", "[[5e-6, 1.1], [4e-6, 0.95]]"), "stiffness_steps",
         "increasing time");
  expect(error_of(EVOLVING, "[[5e-6, 1.1], [12e-6, 0.95]]", "[[5e-6, 0]]"), "stiffness_steps", "must be > 0");
  expect(error_of(EVOLVING, "[[5e-6, 1.1], [12e-6, 0.95]]", "[5e-6, 1.1]"), "stiffness_steps", "expected an array of [2 numbers]");
  expect(error_of(EVOLVING, "[[5e-6, 1.1], [12e-6, 0.95]]", "[[5e-6, 1.1, 3]]"), "stiffness_steps", "of 3 entries");
  // A step that lifts the line above Nyquist: k = 100 N/m x 4 rings at 3.18 MHz, beyond 5 MHz / 2.
  std::string slow = EVOLVING;
  slow.replace(slow.find("sample_rate_hz = 100e6"), 22, "sample_rate_hz = 5e6");
  expect(error_of(slow, "[[5e-6, 1.1], [12e-6, 0.95]]", "[[5e-6, 4]]"), "sample_rate_hz", "below twice the highest natural frequency");
  std::string model1 = EVOLVING;
  auto remove = [&model1](const std::string& what, const std::string& by = "") {
    model1.replace(model1.find(what), what.size(), by);
  };
  remove("[counterface]\nfriction_modulation_rms = 0.01\ncorrelation_length_m = 0.5e-6\n");
  remove("\"model2\"", "\"model1\"");
  remove("belt_velocity_m_per_s = 10\n");
  remove("onset_s = 2e-6\n");
  expect(error_of(model1, "seed = 5", "seed = 5"), "kind", "evolving contact is a Model 2 key");
}

// A run is a function of (study, seed, realisation): the same twice bit for bit, another
// realisation another modulation (MODEL.md §5); friction is 0 after the release.
TEST(EvolvingStudy, RunsAreReproducibleAndReleaseRemovesFriction) {
  const Study base = parse_study(EVOLVING, "s.toml");
  RunOptions options;
  options.show_progress = false;
  const RunResult a = run_study(base, options);
  const RunResult b = run_study(base, options);
  ASSERT_EQ(a.circuit.voltage_v.size(), b.circuit.voltage_v.size());
  for (std::size_t j = 0; j < a.circuit.voltage_v.size(); ++j) ASSERT_EQ(a.circuit.voltage_v[j], b.circuit.voltage_v[j]);
  const RunResult other = run_study(study_for_realisation(base, 1), options);
  EXPECT_NE(other.circuit.voltage_v.back(), a.circuit.voltage_v.back());
  const std::vector<double>& friction = a.trajectories.at(1).friction_n;
  ASSERT_EQ(friction.size(), a.times_s.size());
  for (std::size_t j = 0; j < friction.size(); ++j) {
    if (a.times_s[j] < 2e-6 || a.times_s[j] > 10e-6) {
      EXPECT_EQ(friction[j], 0.0) << a.times_s[j];
    } else if (a.times_s[j] > 2.1e-6) {
      EXPECT_GT(friction[j], 0.0) << a.times_s[j];
    }
  }
}

}  // namespace
}  // namespace stengmc
