// The [inverse] prior (docs/inverse.md, "the known device and the prior"): the keys that say
// what the user does not know read and refused by name, the calibration's prior study
// drawing every one of them, realisations of it carrying the drawn values, and the bank
// identity changing with each.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <string>

#include "core/error.hpp"
#include "ensemble/run_realisation.hpp"
#include "ensemble/study_file.hpp"
#include "inverse/bank_identity.hpp"
#include "inverse/calibration_run.hpp"
#include "inverse/device_checks.hpp"
#include "inverse/inverse_prior.hpp"
#include "inverse/prior_study.hpp"
#include "pipeline/study.hpp"
#include "support/inverse_device.hpp"

namespace stengmc {
namespace {

using testing::known_device_study;

const std::string BROAD = "count = [0, 3]\nmedian_n_per_m = [60, 90]\nsigma_log = [0.1, 0.2]\nload_cv = [0.2, 0.6]\n"
                          "onset_s = [0, 20e-6]\nparameter_tolerance = 0.05\nnoise = \"coloured\"\noffset = true\n";

InversePrior prior_of(const std::string& inverse) {
  return inverse_prior_of_study(known_device_study("40e-6", inverse), "prior.toml");
}

std::string error_of(const std::string& inverse) {
  try {
    prior_of(inverse);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(InversePrior, DefaultsAreTheIdealDeviceAndTheNewKeysRead) {
  const InversePrior ideal = prior_of("");
  EXPECT_TRUE(ideal.ideal_device());
  EXPECT_EQ(ideal.count_min, 1u);
  EXPECT_EQ(ideal.largest_load_ratio(), 1.0);
  const InversePrior broad = prior_of(BROAD);
  EXPECT_FALSE(broad.ideal_device());
  EXPECT_EQ(broad.count_min, 0u);
  EXPECT_EQ(broad.load_cv, (std::array<double, 2>{0.2, 0.6}));
  EXPECT_EQ(broad.onset_s, (std::array<double, 2>{0.0, 20e-6}));
  EXPECT_EQ(broad.parameter_tolerance, 0.05);
  EXPECT_EQ(broad.noise, NoiseColour::coloured);
  EXPECT_TRUE(broad.offset);
  // The spread law at CV 0.6 reaches ~3.3 N at its 1 - 1e-4 quantile; times 1.05.
  EXPECT_GT(broad.largest_load_ratio(), 2.0);
  EXPECT_LT(broad.largest_load_ratio(), 6.0);
}

TEST(InversePrior, EachBadValueIsRefusedAtItsKey) {
  const std::vector<std::pair<std::string, std::string>> bad{
      {"count = [-1, 4]", "count"},           {"count = [0, 0]", "count"},
      {"load_cv = [0.2, 1.6]", "load_cv"},    {"load_cv = [-0.1, 0.2]", "load_cv"},
      {"onset_s = [-1e-6, 2e-6]", "onset_s"}, {"parameter_tolerance = 0.7", "parameter_tolerance"},
      {"parameter_tolerance = -0.1", "parameter_tolerance"}, {"noise = \"pink\"", "noise"},
      {"offset = 1", "offset"}};
  for (const auto& [line, key] : bad) {
    const std::string message = error_of(line + "\n");
    EXPECT_NE(message.find("prior.toml:"), std::string::npos) << line << ": " << message;
    EXPECT_NE(message.find(key), std::string::npos) << line << ": " << message;
  }
}

TEST(InversePrior, ThePriorMustFitTheDevice) {
  // mu_s = 0.28, mu_k = 0.22: a tolerance of 0.15 lets 0.238 fall below 0.253.
  auto refusal = [](const std::string& inverse) {
    try {
      inverse_setup(parse_study(known_device_study("40e-6", inverse), "device.toml", std::nullopt));
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("(accepted)");
  };
  EXPECT_NE(refusal("parameter_tolerance = 0.15\n").find("parameter_tolerance"), std::string::npos);
  EXPECT_NE(refusal("onset_s = [0, 40e-6]\n").find("onset_s"), std::string::npos);
  EXPECT_EQ(refusal("parameter_tolerance = 0.05\nonset_s = [0, 20e-6]\n"), "(accepted)");
}

TEST(InversePrior, TheCalibrationDrawsEveryKeyAndItsRecordsCarryTheDraws) {
  const Study known = parse_study(known_device_study("40e-6", BROAD), "device.toml", std::nullopt);
  const InverseSetup setup = inverse_setup(known);
  const std::string text = prior_study_text(setup.device, setup.prior, 40, 9, 0.3e6, 3e6, 1e-3);
  const StudyFile study = parse_study_file(text, "prior", std::nullopt);
  ASSERT_TRUE(study.ensemble);
  std::set<std::string> drawn;
  for (const DrawAxis& d : study.ensemble->draws) drawn.insert(d.parameter);
  for (const char* p : {"surface.summits.count", "surface.stiffness.median", "surface.stiffness.sigma_log", "noise.snr_db",
                        "surface.load.load_cv", "model.static_friction", "model.kinetic_friction", "model.damping_n_s_per_m",
                        "surface.load.mean_load_n", "surface.element.charge_density_c_per_m2",
                        "surface.element.effective_thickness_m", "noise.coloured_share", "noise.coloured_exponent",
                        "noise.offset_v"})
    EXPECT_TRUE(drawn.count(p)) << p << " is not drawn";
  // Realisations: counts over 0..3 (an empty record among them), loads that differ, onsets
  // inside [0, 20 us], parameters within 5 %.
  std::set<std::size_t> counts;
  bool loads_differ = false;
  for (std::uint64_t r = 0; r < 40; ++r) {
    const RealisationRecord record = run_realisation(study, r, true);
    ASSERT_TRUE(record.valid) << record.failure;
    const auto& k = record.asperities[static_cast<std::size_t>(AsperityColumn::stiffness_n_per_m)];
    const auto& n = record.asperities[static_cast<std::size_t>(AsperityColumn::normal_load_n)];
    counts.insert(k.size());
    if (n.size() >= 2 && n[0] != n[1]) loads_differ = true;
    const double mu_s = record.extra("draw:model.static_friction")->values.front();
    EXPECT_NEAR(mu_s / 0.28, 1.0, 0.05 + 1e-12);
    EXPECT_EQ(record.measured_voltage_v.size(), setup.grid.samples);
    if (k.empty()) {
      // Nothing slides: the measured voltage is the offset plus noise at the reference level.
      double mean = 0.0;
      for (double v : record.measured_voltage_v) mean += v / static_cast<double>(record.measured_voltage_v.size());
      EXPECT_NEAR(mean, record.extra("draw:noise.offset_v")->values.front(), 1e-3);
    }
  }
  EXPECT_EQ(counts, (std::set<std::size_t>{0, 1, 2, 3}));
  EXPECT_TRUE(loads_differ);
}

TEST(InversePrior, TheBankIdentityChangesWithEveryKey) {
  const Study known = parse_study(known_device_study("40e-6", ""), "device.toml", std::nullopt);
  const InverseSetup setup = inverse_setup(known);
  for (const char* line : {"count = [0, 16]", "load_cv = [0, 0.3]", "onset_s = [0, 5e-6]", "parameter_tolerance = 0.02",
                           "noise = \"coloured\"", "offset = true"}) {
    const InverseSetup other = inverse_setup(parse_study(known_device_study("40e-6", std::string(line) + "\n"), "device.toml", std::nullopt));
    EXPECT_NE(other.identity.hash, setup.identity.hash) << line;
    EXPECT_NE(other.identity.differences(setup.identity).find("prior"), std::string::npos) << line;
  }
}

}  // namespace
}  // namespace stengmc
