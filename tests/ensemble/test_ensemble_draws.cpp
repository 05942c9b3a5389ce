// Ensembles over a prior ([[ensemble.draw]]), noisy traces kept, and a caller's reduction of
// each realisation (RealisationHook): what the inverse calibration is built on. Each test
// compares against an independent statement: draws inside their laws and seen by the
// realisation, bitwise equality across threads and re-runs, the noise's variance, the
// journal's round trip.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "core/error.hpp"
#include "ensemble/ensemble_runner.hpp"
#include "ensemble/journal.hpp"
#include "ensemble/study_file.hpp"
#include "support/cli_runner.hpp"
#include "support/table1_study.hpp"

namespace stengmc {
namespace {

using testing::ScratchDir;

// Model 2 asperities of a random surface whose summit count and stiffness median are drawn
// per realisation, with white noise at a drawn SNR; 2 us at 100 MHz keeps it quick.
std::string drawn_study(const std::string& extra = "") {
  return R"(seed = 9
duration_s = 2e-6
sample_rate_hz = 100e6
[model]
kind = "model2"
belt_velocity_m_per_s = 10
)" + testing::table1_random_surface(1, "80", "0.3") + R"(
[noise]
snr_db = 30
[ensemble]
realisations = 12
trace_all = true
[[ensemble.draw]]
parameter = "surface.summits.count"
kind = "integer"
min = 1
max = 5
[[ensemble.draw]]
parameter = "surface.stiffness.median"
kind = "uniform"
min = 40
max = 120
[[ensemble.draw]]
parameter = "noise.snr_db"
kind = "choice"
values = [20, 40]
)" + extra;
}

double drawn(const RealisationRecord& r, const std::string& parameter) { return r.extra("draw:" + parameter)->values.at(0); }

TEST(EnsembleDraws, EachRealisationDrawsItsOwnParametersAndUsesThem) {
  ScratchDir scratch("ensemble-draws");
  const StudyFile study = parse_study_file(drawn_study(), scratch.file("study.toml"), std::nullopt);
  const EnsembleRun run = run_ensemble(study, scratch.file("a.journal"), {.threads = 1, .show_progress = false});
  ASSERT_EQ(run.records.size(), 12u);
  bool counts_vary = false;
  for (const RealisationRecord& r : run.records) {
    ASSERT_TRUE(r.valid) << r.failure;
    const double count = drawn(r, "surface.summits.count");
    EXPECT_EQ(count, std::floor(count));
    EXPECT_GE(count, 1.0);
    EXPECT_LE(count, 5.0);
    // The realisation simulated exactly the drawn number of asperities.
    EXPECT_EQ(static_cast<double>(r.asperity_count()), count);
    counts_vary = counts_vary || count != drawn(run.records.front(), "surface.summits.count");
    const double median = drawn(r, "surface.stiffness.median");
    EXPECT_GE(median, 40.0);
    EXPECT_LT(median, 120.0);
    const double snr = drawn(r, "noise.snr_db");
    EXPECT_TRUE(snr == 20.0 || snr == 40.0);
    // The kept noisy voltage carries noise of the drawn SNR: sigma^2 = var(V) / 10^(snr/10)
    // (measurement_noise.hpp). With 201 samples the sample variance of the noise is within
    // ~30 % of sigma^2 (3 sd of a chi^2 with 200 degrees of freedom).
    ASSERT_EQ(r.measured_voltage_v.size(), r.voltage_v.size());
    double mean = 0.0, var = 0.0, noise = 0.0;
    const auto n = static_cast<double>(r.voltage_v.size());
    for (double v : r.voltage_v) mean += v / n;
    for (double v : r.voltage_v) var += (v - mean) * (v - mean) / n;
    for (std::size_t m = 0; m < r.voltage_v.size(); ++m)
      noise += (r.measured_voltage_v[m] - r.voltage_v[m]) * (r.measured_voltage_v[m] - r.voltage_v[m]) / n;
    EXPECT_NEAR(noise / (var / std::pow(10.0, snr / 10.0)), 1.0, 0.3);
  }
  EXPECT_TRUE(counts_vary) << "12 realisations all drew the same count";
}

TEST(EnsembleDraws, BitwiseTheSameOnOneAndTwoThreadsAndAlone) {
  ScratchDir scratch("ensemble-draws-threads");
  const StudyFile study = parse_study_file(drawn_study(), scratch.file("study.toml"), std::nullopt);
  const EnsembleRun one = run_ensemble(study, scratch.file("one.journal"), {.threads = 1, .show_progress = false});
  const EnsembleRun two = run_ensemble(study, scratch.file("two.journal"), {.threads = 2, .show_progress = false});
  const EnsembleRun alone = run_ensemble(study, "", {.only = 5, .show_progress = false});
  ASSERT_EQ(one.records.size(), two.records.size());
  for (std::size_t i = 0; i < one.records.size(); ++i) {
    const RealisationRecord &a = one.records[i], &b = two.records[i];
    EXPECT_EQ(a.scalars, b.scalars);
    EXPECT_EQ(a.asperities, b.asperities);
    EXPECT_EQ(a.measured_voltage_v, b.measured_voltage_v);
    ASSERT_EQ(a.extras.size(), b.extras.size());
    for (std::size_t j = 0; j < a.extras.size(); ++j) EXPECT_EQ(a.extras[j].values, b.extras[j].values);
  }
  ASSERT_EQ(alone.records.size(), 1u);
  EXPECT_EQ(alone.records[0].measured_voltage_v, one.records[5].measured_voltage_v);
  EXPECT_EQ(alone.records[0].asperities, one.records[5].asperities);
}

// The counterface's modulation (docs/model.md §1.4) is drawn from a stream of (seed,
// realisation, asperity): with it and a drawn correlation length, 1 and 2 threads and a
// realisation run alone agree bit for bit, and the draw lies in its law.
TEST(EnsembleDraws, CounterfaceModulationIsBitwiseTheSameOnOneAndTwoThreadsAndAlone) {
  ScratchDir scratch("ensemble-draws-counterface");
  const StudyFile study = parse_study_file(drawn_study(R"([counterface]
friction_modulation_rms = 0.01
correlation_length_m = 0.5e-6
[[ensemble.draw]]
parameter = "counterface.correlation_length_m"
kind = "uniform"
min = 0.2e-6
max = 1e-6
)"),
                                           scratch.file("study.toml"), std::nullopt);
  const EnsembleRun one = run_ensemble(study, scratch.file("one.journal"), {.threads = 1, .show_progress = false});
  const EnsembleRun two = run_ensemble(study, scratch.file("two.journal"), {.threads = 2, .show_progress = false});
  const EnsembleRun alone = run_ensemble(study, "", {.only = 7, .show_progress = false});
  ASSERT_EQ(one.records.size(), two.records.size());
  for (std::size_t i = 0; i < one.records.size(); ++i) {
    EXPECT_EQ(one.records[i].scalars, two.records[i].scalars);
    EXPECT_EQ(one.records[i].measured_voltage_v, two.records[i].measured_voltage_v);
    const double lambda = drawn(one.records[i], "counterface.correlation_length_m");
    EXPECT_TRUE(lambda >= 0.2e-6 && lambda < 1e-6) << lambda;
  }
  ASSERT_EQ(alone.records.size(), 1u);
  EXPECT_EQ(alone.records[0].measured_voltage_v, one.records[7].measured_voltage_v);
}

TEST(EnsembleDraws, HookReducesEachRecordAndIsPartOfTheJournalsIdentity) {
  ScratchDir scratch("ensemble-hook");
  const StudyFile study = parse_study_file(drawn_study(), scratch.file("study.toml"), std::nullopt);
  RealisationHook hook;
  hook.needs_traces = true;
  hook.identity = "peak v1";
  hook.apply = [](RealisationRecord& r) {
    double peak = 0.0;
    for (double v : r.measured_voltage_v) peak = std::max(peak, std::abs(v));
    r.extras.push_back({"peak", {peak}});
    r.time_s.clear(), r.voltage_v.clear(), r.charge_c.clear(), r.measured_voltage_v.clear();
  };
  const std::string journal = scratch.file("hook.journal");
  // A run that stops after the journal holds records: the hook's output is journalled...
  {
    Journal writer(journal, {fnv1a64("peak v1", ensemble_identity_hash(study)), "test"});
    RealisationRecord r;
    r.realisation = 0;
    r.extras.push_back({"draw:surface.summits.count", {2.0}});
    r.extras.push_back({"peak", {0.5}});
    r.measured_voltage_v = {1.0, -2.0};
    for (auto& column : r.asperities) column.clear();
    writer.append(r);
  }
  {
    // ... and comes back bitwise (extras and the measured trace are part of the format).
    Journal reader(journal, {fnv1a64("peak v1", ensemble_identity_hash(study)), "test"});
    ASSERT_EQ(reader.recovered().size(), 1u);
    EXPECT_EQ(reader.recovered()[0].extra("peak")->values, std::vector<double>{0.5});
    EXPECT_EQ(reader.recovered()[0].measured_voltage_v, (std::vector<double>{1.0, -2.0}));
  }
  // A resume under another hook identity is refused (its records reduce differently).
  RealisationHook other = hook;
  other.identity = "peak v2";
  EXPECT_THROW(run_ensemble(study, journal, {.threads = 2, .show_progress = false}, other), InputError);
  std::filesystem::remove(journal);
  const EnsembleRun run = run_ensemble(study, journal, {.threads = 2, .show_progress = false}, hook);
  for (const RealisationRecord& r : run.records) {
    ASSERT_NE(r.extra("peak"), nullptr);
    EXPECT_GT(r.extra("peak")->values[0], 0.0);
    EXPECT_TRUE(r.measured_voltage_v.empty());
  }
}

TEST(EnsembleDraws, BadDrawsAreRefused) {
  auto refused = [](const std::string& text, const std::string& expected) {
    try {
      parse_study_file(text, "bad.toml", std::nullopt);
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
      return;
    }
    ADD_FAILURE() << "accepted: expected '" << expected << "'";
  };
  refused(drawn_study("[[ensemble.draw]]\nparameter = \"noise.snr_db\"\nmin = 1\nmax = 2\n"), "is drawn twice");
  refused(drawn_study("[[ensemble.draw]]\nparameter = \"model.belt_velocity_m_per_s\"\nmin = 5\nmax = 1\n"), "must be >= min");
  refused(drawn_study("[[ensemble.draw]]\nparameter = \"model.belt_velocity_m_per_s\"\nkind = \"integer\"\nmin = 1.5\nmax = 3\n"),
          "whole numbers");
  refused(drawn_study("[[ensemble.sweep]]\nparameter = \"noise.snr_db\"\nvalues = [10]\n"), "both swept and drawn");
  refused(drawn_study("[[ensemble.draw]]\nparameter = \"ensemble.realisations\"\nmin = 1\nmax = 2\n"), "cannot be drawn");
}

// The study is read in two layers (issue 10): the pipeline's reader leaves [ensemble] to the
// ensemble layer, which reads it and rejects what it does not know. A typo there must still
// stop the ensemble, and a run of one realisation must not need the ensemble's keys.
TEST(StudyFile, TheEnsembleLayerChecksItsTableAndThePipelineLeavesItAlone) {
  std::string text = drawn_study();
  const std::string key = "realisations = 12\n";
  text.replace(text.find(key), key.size(), key + "realisatons = 5\n");
  try {
    parse_study_file(text, "typo.toml", std::nullopt);
    ADD_FAILURE() << "the misspelt [ensemble] key was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("unknown key 'ensemble.realisatons'"), std::string::npos) << e.what();
  }
  const Study run = parse_study(text, "typo.toml", 0);
  EXPECT_EQ(run.asperities.size(), 1u);  // count = 1 in the file; the draws are the ensemble's
  const StudyFile ensemble = parse_study_file(drawn_study(), "good.toml", std::nullopt);
  ASSERT_TRUE(ensemble.ensemble.has_value());
  EXPECT_EQ(ensemble.ensemble->realisations, 12u);
}

}  // namespace
}  // namespace stengmc
