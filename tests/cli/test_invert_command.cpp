// `stengmc calibrate` and `stengmc invert` through the real command line: rejected inputs
// (exit 2, a message naming the problem, no output file), a bank refused for other known
// parameters, a calibration bitwise the same on 1 and 2 threads, a record inverted end to
// end with its figure, and records it used to stop on with a library's text (equal
// stiffnesses, other units, integer voltages, a prior's large smallest count).
#include <gtest/gtest.h>
#include <H5Cpp.h>
#include <sys/stat.h>

#include <algorithm>
#include <boost/random/normal_distribution.hpp>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <type_traits>
#include <vector>

#include "core/random_stream.hpp"
#include "inverse/calibration_run.hpp"
#include "inverse/simulated_record.hpp"
#include "core/hdf5_file.hpp"

#include "core/input_file.hpp"
#include "io/inverse_signals.hpp"
#include "pipeline/study.hpp"
#include "support/cli_runner.hpp"
#include "support/inverse_device.hpp"
#include "support/table1_study.hpp"

namespace stengmc {
namespace {

using testing::run_cli;
using testing::ScratchDir;

// The known device (tests/support/known_device.toml) with 20 us records and the quick prior
// (known_device_quick_prior.toml: 1-3 asperities, 50 records, a bank in seconds).
std::string device_study(const std::string& replace_from = "", const std::string& replace_to = "") {
  std::string text = testing::known_device_study("20e-6", testing::quick_prior());
  if (!replace_from.empty()) {
    const auto at = text.find(replace_from);
    EXPECT_NE(at, std::string::npos) << replace_from;
    text.replace(at, replace_from.size(), replace_to);
  }
  return text;
}

//! A CSV `t,V` of `samples` samples: times from `time(m)`, values from `value(m)`.
template <typename T, typename F>
std::string csv_with(std::size_t samples, T time, F value) {
  std::string out = "t,V\n";
  char line[96];
  for (std::size_t m = 0; m < samples; ++m) {
    std::snprintf(line, sizeof line, "%.17g,%.17g\n", time(m), value(m));
    out += line;
  }
  return out;
}

//! The same on the uniform grid m / rate.
template <typename F>
std::string csv(std::size_t samples, double rate, F value) {
  return csv_with(samples, [rate](std::size_t m) { return static_cast<double>(m) / rate; }, value);
}

//! A record of the small device with asperities of stiffness `k`, white noise of
//! `noise_v` [V] added, then scaled by `scale` (a record in other units).
std::string simulated_csv(const std::vector<double>& k, double noise_v = 1e-4, double scale = 1.0) {
  const Study study = parse_study(device_study(), "device.toml", std::nullopt);
  const InverseSetup setup = inverse_setup(study);
  std::vector<double> v = simulate_record(setup.device, k, setup.grid);
  RandomEngine engine = random_stream(3, 0, StreamKind::noise);
  boost::random::normal_distribution<double> noise(0.0, noise_v);
  for (double& x : v) x = scale * (x + (noise_v > 0.0 ? noise(engine) : 0.0));
  return csv(v.size(), 100e6, [&](std::size_t m) { return v[m]; });
}

//! The same for asperities of their own loads and onsets (SimulatedAsperity).
std::string simulated_csv(const std::vector<SimulatedAsperity>& asperities, double noise_v) {
  const Study study = parse_study(device_study(), "device.toml", std::nullopt);
  const InverseSetup setup = inverse_setup(study);
  std::vector<double> v = simulate_record(setup.device, asperities, setup.grid);
  RandomEngine engine = random_stream(3, 0, StreamKind::noise);
  boost::random::normal_distribution<double> noise(0.0, noise_v);
  for (double& x : v) x += noise(engine);
  return csv(v.size(), 100e6, [&](std::size_t m) { return v[m]; });
}

//! The suite's device with a prior of 1-8 asperities (no bank: the atoms build in a second).
std::string device_study_up_to_eight() { return device_study("count = [1, 3]", "count = [1, 8]"); }

//! Runs invert on `signal_text` without a bank; returns the result and the output's path.
std::pair<testing::CliResult, std::string> invert_unbanked(const ScratchDir& scratch, const std::string& signal_text,
                                                           const std::string& study = device_study_up_to_eight()) {
  const std::string signal = scratch.write("signal.csv", signal_text);
  const std::string known = scratch.write("known.toml", study);
  const std::string out = scratch.file("out.h5");
  return {run_cli("invert " + signal + " --known " + known + " --out " + out + " -j 1", scratch), out};
}

class InvertCommand : public ::testing::Test {
 protected:
  // One bank for the suite (it takes a few seconds).
  static void SetUpTestSuite() {
    scratch_ = new ScratchDir("invert-suite");
    scratch_->write("device.toml", device_study());
    const auto r = run_cli("calibrate " + scratch_->file("device.toml") + " -o " + scratch_->file("bank.h5") + " -j 2", *scratch_);
    ASSERT_EQ(r.exit_code, 0) << r.output;
  }
  static void TearDownTestSuite() {
    delete scratch_;
    scratch_ = nullptr;
  }
  static ScratchDir* scratch_;

  //! Runs invert on `signal_text` (a CSV) with the suite's device; expects a refusal with
  //! exit code 2 whose message holds `expected`, and no output file.
  void expect_refused(const std::string& signal_text, const std::string& expected, const std::string& study = device_study()) {
    ScratchDir scratch("invert-bad");
    const std::string signal = scratch.write("signal.csv", signal_text);
    const std::string known = scratch.write("known.toml", study);
    const std::string out = scratch.file("out.h5");
    const auto r = run_cli("invert " + signal + " --known " + known + " --out " + out, scratch);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find(expected), std::string::npos) << "expected '" << expected << "' in:\n" << r.output;
    EXPECT_FALSE(std::filesystem::exists(out));
  }
};
ScratchDir* InvertCommand::scratch_ = nullptr;

const double RATE = 100e6;
double zero(std::size_t) { return 0.0; }

TEST_F(InvertCommand, RejectsNonUniformTimes) {
  // Sample 101 moved by 0.3 steps.
  auto time = [](std::size_t m) { return (static_cast<double>(m) + (m == 100 ? 0.3 : 0.0)) / RATE; };
  expect_refused(csv_with(2001, time, zero), "not uniform");
}

TEST_F(InvertCommand, RejectsDuplicatedTimes) {
  // Sample 101 repeats sample 100's time.
  auto time = [](std::size_t m) { return static_cast<double>(m == 100 ? 99 : m) / RATE; };
  expect_refused(csv_with(2001, time, zero), "repeats the time of sample 100");
}

TEST_F(InvertCommand, RejectsNanAndInf) {
  expect_refused(csv(2001, RATE, [](std::size_t m) { return m == 77 ? std::nan("") : 0.0; }), "is not two finite numbers");
  expect_refused(csv(2001, RATE, [](std::size_t m) { return m == 77 ? INFINITY : 0.0; }), "is not two finite numbers");
}

TEST_F(InvertCommand, RejectsAConstantRecordNamingIt) {
  // It used to stop with exit 1 and "count_posterior: the noise level must be > 0".
  expect_refused(csv(2001, RATE, zero), "signal.csv: the voltage is 0 V at every sample");
  expect_refused(csv(2001, RATE, [](std::size_t) { return 0.25; }), "signal.csv: the voltage is 0.25 V at every sample");
}

TEST_F(InvertCommand, RejectsTooFewSamples) { expect_refused(csv(63, RATE, zero), "at least 64"); }

TEST_F(InvertCommand, RejectsASampleRateTooLowForThePriorsHighestLine) {
  // The prior's highest line is ~1.9 MHz (k ~ 140 N/m); 3 MHz sampling has its Nyquist
  // frequency below 1.25 x that.
  expect_refused(csv(200, 3e6, zero), "too low for the prior's highest line");
}

TEST_F(InvertCommand, RejectsAStudyMissingAKnownParameter) {
  expect_refused(csv(2001, RATE, zero), "missing model.belt_velocity_m_per_s", device_study("belt_velocity_m_per_s = 10\n", ""));
  expect_refused(csv(2001, RATE, zero), "surface.defaults.normal_load_n", device_study("normal_load_n = 1e-3\n", ""));
}

TEST_F(InvertCommand, RefusesABankMadeForOtherKnownParameters) {
  ScratchDir scratch("invert-other-bank");
  const std::string signal = scratch.write("signal.csv", simulated_csv({70.0}));
  const std::string known = scratch.write("known.toml", device_study("normal_load_n = 1e-3", "normal_load_n = 1.1e-3"));
  const std::string out = scratch.file("out.h5");
  const auto r = run_cli("invert " + signal + " --known " + known + " --bank " + scratch_->file("bank.h5") + " --out " + out, scratch);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("was made for other known parameters"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("normal_load_n = 0.001"), std::string::npos) << "the message should say what differs:\n" << r.output;
  EXPECT_FALSE(std::filesystem::exists(out));
}

TEST_F(InvertCommand, CalibrationIsTheSameOnOneAndTwoThreads) {
  ScratchDir scratch("invert-threads");
  const auto r = run_cli("calibrate " + scratch_->file("device.toml") + " -o " + scratch.file("bank1.h5") + " -j 1", scratch);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  Hdf5Reader one(scratch.file("bank1.h5")), two(scratch_->file("bank.h5"));
  // Everything but the estimator's CPU times, bitwise.
  for (const char* name : {"/records/count", "/records/true_count", "/records/stiffness", "/records/log_stiffness_se",
                           "/records/log_evidence", "/records/median", "/records/sd_log", "/records/naive_counts",
                           "/records/noise_sigma", "/maps/fits/confusion", "/maps/fits/median_score_quantile",
                           "/maps/fits/sd_score_quantile", "/maps/misfits/confusion", "/atoms/onset_values", "/atoms/breakaway_values", "/atoms/tail_phase",
                           "/atoms/tail_log_amplitude"}) {
    const std::string path = name;
    if (path == "/records/naive_counts" || path == "/maps/fits/confusion" || path == "/maps/misfits/confusion" || path == "/atoms/onset_values" ||
        path == "/atoms/breakaway_values")
      EXPECT_EQ(one.matrix(path), two.matrix(path)) << path;
    else
      EXPECT_EQ(one.vector(path), two.vector(path)) << path;
  }
}

TEST_F(InvertCommand, InvertsARecordAndDrawsItsFigure) {
  ScratchDir scratch("invert-roundtrip");
  const std::string signal = scratch.write("signal.csv", simulated_csv({55.0, 85.0}));
  const std::string out = scratch.file("out.h5");
  const auto r = run_cli("invert " + signal + " --known " + scratch_->file("device.toml") + " --bank " + scratch_->file("bank.h5") +
                             " --out " + out + " --figures",
                         scratch);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  Hdf5Reader file(out);
  EXPECT_EQ(file.vector("/inverse/count/estimate"), std::vector<double>{2.0});
  const std::vector<double> k = file.vector("/inverse/lines/stiffness_n_per_m");
  ASSERT_EQ(k.size(), 2u);
  // 1e-4 V of noise on ~8 mV lines (~40 dB): the lines to well under 1 %.
  EXPECT_NEAR(k[0] / 55.0, 1.0, 1e-2);
  EXPECT_NEAR(k[1] / 85.0, 1.0, 1e-2);
  EXPECT_EQ(file.string_attribute("/", "file_type"), "stengmc-inverse");
  EXPECT_TRUE(std::filesystem::exists(scratch.file("out.png"))) << r.output;
  // A record of the ideal device the atoms fit: no warning on the fit.
  EXPECT_EQ(r.output.find("does not fit to the noise"), std::string::npos) << r.output;
}

// A record the ideal device's atoms cannot fit (loads 0.5 and 1.8 x the device's, one onset at
// 6 us) inverted with the ideal prior's bank: the one warning on the fit, which says that the
// bank holds too few such records for its intervals, and the verdict's pointer to what the
// residual says (the old warnings fired on right and wrong answers alike; docs/inverse.md).
TEST_F(InvertCommand, ARecordTheAtomsCannotFitIsWarnedAboutWithWhatItPointsTo) {
  ScratchDir scratch("invert-misfit");
  const Study study = parse_study(device_study(), "device.toml", std::nullopt);
  const double n0 = inverse_setup(study).device.asperity.normal_load_n;
  const std::string signal = scratch.write("signal.csv", simulated_csv({{55.0, 0.5 * n0, 0.0}, {85.0, 1.8 * n0, 6e-6}}, 1e-4));
  const auto r = run_cli("invert " + signal + " --known " + scratch_->file("device.toml") + " --bank " + scratch_->file("bank.h5") +
                             " --out " + scratch.file("out.h5"),
                         scratch);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("the model does not fit to the noise"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("the bank holds too few such records"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("The residual is largest"), std::string::npos) << r.output;
}

// Four asperities of equal stiffness (a noise-free record, as `stengmc run` gives it) give
// four lines that merge to ~1e-4 in ln k. The stiffness-law fit stopped the command with
// Boost's "toms748_solve ... do not bracket the root" or an infinite Weibull scale (exit 1).
// It is a physical case: four asperities, one stiffness, no law.
TEST(InvertEqualStiffnesses, FourAsperitiesOfEqualStiffnessAreCounted) {
  ScratchDir scratch("invert-equal");
  const auto [r, out] = invert_unbanked(scratch, simulated_csv({75.0, 75.0, 75.0, 75.0}, 0.0));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("The 4 lines share one stiffness, 75"), std::string::npos) << r.output;
  Hdf5Reader file(out);
  EXPECT_EQ(file.vector("/inverse/count/estimate"), std::vector<double>{4.0});
  for (double k : file.vector("/inverse/lines/stiffness_n_per_m")) EXPECT_NEAR(k / 75.0, 1.0, 1e-3);
}

// A record in mV (x 1e3) or scaled far below the device (x 1e-200) stopped with Boost's
// bracket error, or "count_posterior: the noise level must be > 0" (exit 1). An amplitude no
// count of the device's asperities gives is the verdict's to say.
TEST(InvertOtherUnits, ARecordFarFromTheDevicesAmplitudeIsAnsweredWithAWarning) {
  for (const auto& [scale, expected] : std::vector<std::pair<double, std::string>>{
           {1e3, "more than the prior's 8 asperities could give: is the record in other units"},
           {1e-200, "nothing of this device slides in it"}}) {
    ScratchDir scratch("invert-units");
    const auto [r, out] = invert_unbanked(scratch, simulated_csv({55.0, 85.0}, 1e-4, scale));
    EXPECT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find(expected), std::string::npos) << "expected '" << expected << "' in:\n" << r.output;
    EXPECT_TRUE(std::filesystem::exists(out)) << r.output;
  }
}

// A prior whose smallest count lies beyond where the greedy search stops: the search used to
// end short of it ("the search stopped early", exit 1; a calibration's journal never finished).
TEST(InvertCountRange, APriorOfOneLargeCountIsAnswered) {
  ScratchDir scratch("invert-count");
  const auto [r, out] = invert_unbanked(scratch, simulated_csv({55.0, 85.0}), device_study("count = [1, 3]", "count = [12, 12]"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(Hdf5Reader(out).vector("/inverse/count/estimate"), std::vector<double>{12.0});
}

//! Writes a record file as another program would: /time as doubles, /circuit/voltage as
//! `type` (int64 or float32) holding `voltage` converted to it.
void write_typed_record(const std::string& path, const std::vector<double>& voltage, const H5::PredType& type) {
  H5::H5File file(path, H5F_ACC_TRUNC);
  const hsize_t n = voltage.size();
  const H5::DataSpace space(1, &n);
  std::vector<double> t(voltage.size());
  for (std::size_t m = 0; m < t.size(); ++m) t[m] = static_cast<double>(m) / RATE;
  file.createDataSet("/time", H5::PredType::NATIVE_DOUBLE, space).write(t.data(), H5::PredType::NATIVE_DOUBLE);
  file.createGroup("/circuit");
  // HDF5 converts the doubles to the dataset's type (rounding to integers for int64).
  file.createDataSet("/circuit/voltage", type, space).write(voltage.data(), H5::PredType::NATIVE_DOUBLE);
}

//! The voltages of simulated_csv({55, 85}) (its second column).
std::vector<double> simulated_voltages() {
  const std::string text = simulated_csv({55.0, 85.0});
  std::vector<double> v;
  for (std::size_t at = text.find('\n'); at != std::string::npos && at + 1 < text.size(); at = text.find('\n', at + 1))
    v.push_back(std::stod(text.substr(text.find(',', at) + 1)));
  return v;
}

// An int64 voltage dataset (the record in uV) stopped with Boost's "tgamma ... Series
// evaluation exceeded 1000000 iterations" or its bracket error (exit 1). It is read as the
// numbers it holds, as is a float32 one, and answered.
TEST(InvertRecordTypes, IntegerAndFloat32VoltagesAreReadAsNumbers) {
  const std::vector<double> volts = simulated_voltages();
  std::vector<double> microvolts(volts.size());
  for (std::size_t m = 0; m < volts.size(); ++m) microvolts[m] = std::round(volts[m] * 1e6);
  ScratchDir scratch("invert-types");
  const std::string known = scratch.write("known.toml", device_study_up_to_eight());
  const std::string integers = scratch.file("int64.h5"), singles = scratch.file("float32.h5");
  write_typed_record(integers, microvolts, H5::PredType::STD_I64LE);
  write_typed_record(singles, volts, H5::PredType::IEEE_F32LE);

  const auto r = run_cli("invert " + integers + " --known " + known + " --out " + scratch.file("int.h5") + " -j 1", scratch);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(Hdf5Reader(scratch.file("int.h5")).vector("/inverse/traces/record_0/voltage"), microvolts);
  EXPECT_NE(r.output.find("is the record in other units"), std::string::npos) << r.output;

  const auto f = run_cli("invert " + singles + " --known " + known + " --out " + scratch.file("f32.h5") + " -j 1", scratch);
  ASSERT_EQ(f.exit_code, 0) << f.output;
  const Hdf5Reader out(scratch.file("f32.h5"));
  EXPECT_EQ(out.vector("/inverse/count/estimate"), std::vector<double>{2.0});
  const std::vector<double> read = out.vector("/inverse/traces/record_0/voltage");
  ASSERT_EQ(read.size(), volts.size());
  for (std::size_t m = 0; m < volts.size(); ++m) ASSERT_EQ(read[m], static_cast<double>(static_cast<float>(volts[m]))) << m;
}

// An ensemble of the known device's grid in which some realisations are invalid (an
// asperity of k < mu_s N / l = 5.6 N/m reaches l: [domain] policy "flag" keeps its trace up
// to there, shorter than the others). invert stopped on that trace's grid; it must skip the
// invalid realisations, say so, and invert the valid ones (checked against the file's own
// /realisations/valid, not against numbers this code produced).
TEST(InvertEnsembleFile, InvalidRealisationsAreSkippedAndNamed) {
  ScratchDir scratch("invert-invalid");
  const std::string study =
      scratch.write("ensemble.toml", "seed = 5\nduration_s = 20e-6\nsample_rate_hz = 100e6\n" +
                                         testing::table1_model_and_circuit({.belt_velocity_m_per_s = "10"}) +
                                         testing::table1_random_surface(3, "40", "1.5") + R"(
[surface.mass]
rule = "fixed"
mass_kg = 1e-12
[noise]
snr_db = 30
[ensemble]
realisations = 8
trace_all = true
)");
  const std::string ensemble = scratch.file("ensemble.h5");
  const auto ran = run_cli("run " + study + " -j 1 -o " + ensemble, scratch);
  ASSERT_EQ(ran.exit_code, 0) << ran.output;
  const std::vector<double> valid = Hdf5Reader(ensemble).vector("/realisations/valid");
  const auto n_valid = static_cast<std::size_t>(std::count(valid.begin(), valid.end(), 1.0));
  ASSERT_GT(n_valid, 0u) << "the fixture needs valid realisations";
  ASSERT_LT(n_valid, valid.size()) << "the fixture needs an invalid realisation (another seed or sigma_log)";

  std::vector<std::string> notes;
  const std::vector<NamedRecord> records = read_inverse_records(ensemble, {}, &notes);
  EXPECT_EQ(records.size(), n_valid);
  for (std::size_t r = 0; r < valid.size(); ++r) {
    const std::string name = ensemble + "#realisation_" + std::to_string(r);
    const bool read = std::any_of(records.begin(), records.end(), [&](const NamedRecord& x) { return x.name == name; });
    EXPECT_EQ(read, valid[r] == 1.0) << name;
  }
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_NE(notes.front().find(std::to_string(valid.size() - n_valid) + " invalid realisation"), std::string::npos) << notes.front();

  const std::string known = scratch.write("known.toml", device_study_up_to_eight());
  const auto inverted = run_cli("invert " + ensemble + " --known " + known + " --out " + scratch.file("out.h5") + " -j 1", scratch);
  ASSERT_EQ(inverted.exit_code, 0) << inverted.output;
  EXPECT_NE(inverted.output.find("invalid realisation(s) skipped"), std::string::npos) << inverted.output;
  EXPECT_EQ(Hdf5Reader(scratch.file("out.h5")).vector("/inverse/count/estimate").size(), n_valid);
}

// [inverse] snr_db = [-1e9, 1e9] was accepted by invert, and calibrate reported it at line 61
// of a 40-line file under a [noise] table it does not have; [300, 400] failed mid-run naming
// [[ensemble.draw]]. Both are refused at the key's own line with the range [noise] accepts.
TEST_F(InvertCommand, RejectsAnSnrRangeBeyondWhatNoiseAcceptsAtItsLine) {
  for (const std::string range : {"[-1e9, 1e9]", "[300, 400]"}) {
    const std::string study = device_study("snr_db = [25, 35]", "snr_db = " + range);
    std::size_t line = 1;
    for (std::size_t at = 0; at < study.find("snr_db"); ++at) line += study[at] == '\n';
    const std::string expected = "known.toml:" + std::to_string(line) + ": [inverse] snr_db = ";
    expect_refused(simulated_csv({55.0}), expected, study);
    ScratchDir scratch("invert-snr");
    const auto c = run_cli("calibrate " + scratch.write("known.toml", study) + " -o " + scratch.file("bank.h5"), scratch);
    EXPECT_EQ(c.exit_code, 2) << c.output;
    EXPECT_NE(c.output.find(expected), std::string::npos) << c.output;
    EXPECT_NE(c.output.find("must lie in [-300, 300] dB"), std::string::npos) << c.output;
    EXPECT_FALSE(std::filesystem::exists(scratch.file("bank.h5.journal")));
  }
}

//! Copies `from` to `to` and sets the integer root attribute `name` to `value`.
void copy_with_attribute(const std::string& from, const std::string& to, const std::string& name, std::int64_t value) {
  std::filesystem::copy_file(from, to, std::filesystem::copy_options::overwrite_existing);
  H5::H5File file(to, H5F_ACC_RDWR);
  H5::Group root = file.openGroup("/");
  if (root.attrExists(name)) root.removeAttr(name);
  root.createAttribute(name, H5::PredType::NATIVE_INT64, H5::DataSpace(H5S_SCALAR)).write(H5::PredType::NATIVE_INT64, &value);
}

// format_version = -1 on a record file, and format_version or bank_format_version = -1 on a
// bank, were accepted by invert: refused naming the file and the attribute.
TEST_F(InvertCommand, RejectsNegativeFormatVersionsOfRecordsAndBanks) {
  ScratchDir scratch("invert-versions");
  const std::string known = scratch.write("known.toml", device_study());
  const std::string csv_record = scratch.write("signal.csv", simulated_csv({55.0}));
  const std::string run_record = scratch.file("run.h5");
  {
    Hdf5Writer file(run_record);
    file.attribute("/", "file_type", std::string("stengmc-run"));
    file.attribute("/", "format_version", std::int64_t{-1});
    const std::vector<double> v = simulated_voltages();
    std::vector<double> t(v.size());
    for (std::size_t m = 0; m < t.size(); ++m) t[m] = static_cast<double>(m) / RATE;
    file.write("/time", t, "s");
    file.write("/circuit/voltage", v, "V");
    file.commit();
  }
  auto refused = [&](const std::string& arguments, const std::vector<std::string>& expected) {
    const auto r = run_cli("invert " + arguments + " --known " + known + " --out " + scratch.file("out.h5"), scratch);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    for (const std::string& e : expected) EXPECT_NE(r.output.find(e), std::string::npos) << "expected '" << e << "' in:\n" << r.output;
    EXPECT_FALSE(std::filesystem::exists(scratch.file("out.h5")));
  };
  refused(run_record, {"run.h5", "format_version -1"});
  copy_with_attribute(scratch_->file("bank.h5"), scratch.file("bank1.h5"), "format_version", -1);
  refused(csv_record + " --bank " + scratch.file("bank1.h5"), {"bank1.h5", "format_version -1"});
  copy_with_attribute(scratch_->file("bank.h5"), scratch.file("bank2.h5"), "bank_format_version", -1);
  refused(csv_record + " --bank " + scratch.file("bank2.h5"), {"bank2.h5", "bank_format_version -1"});
}

// A CSV line of 10 MB was echoed whole in the error message.
TEST_F(InvertCommand, QuotesALongBadLineShort) {
  const std::string line = "1e-08," + std::string(10'000'000, 'x');
  ScratchDir scratch("invert-long-line");
  const std::string signal = scratch.write("signal.csv", "t,V\n0,0\n" + line + "\n");
  const auto r = run_cli("invert " + signal + " --known " + scratch_->file("device.toml") + " --out " + scratch.file("o.h5"), scratch);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("signal.csv:3: '1e-08,xxxx"), std::string::npos) << r.output.substr(0, 400);
  EXPECT_NE(r.output.find("... (10000006 characters)' is not two finite numbers"), std::string::npos) << r.output.substr(0, 400);
  EXPECT_LT(r.output.size(), 1000u);
}

// ---------------------------------------------------------------- journals and banks (issue 22)

//! A copy of the suite's bank in `scratch`, to damage.
std::string bank_copy(const ScratchDir& scratch, const std::string& source) {
  const std::string copy = scratch.file("bank.h5");
  std::filesystem::copy_file(source, copy, std::filesystem::copy_options::overwrite_existing);
  return copy;
}

void xor_byte(const std::string& path, std::uint64_t offset, unsigned char mask) {
  std::fstream file(path, std::ios::in | std::ios::out | std::ios::binary);
  file.seekg(static_cast<std::streamoff>(offset));
  const char byte = static_cast<char>(file.get() ^ mask);
  file.seekp(static_cast<std::streamoff>(offset));
  file.put(byte);
}

//! Where the values of a contiguous dataset lie in the file [bytes].
std::uint64_t data_offset(const std::string& path, const std::string& dataset) {
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t data = H5Dopen2(file, dataset.c_str(), H5P_DEFAULT);
  const haddr_t offset = H5Dget_offset(data);
  H5Dclose(data);
  H5Fclose(file);
  EXPECT_NE(offset, HADDR_UNDEF) << dataset;
  return offset;
}

//! Rewrites the numeric attribute object@name in place, as a stray write or an edit would.
template <typename T>
void rewrite_attribute(const std::string& path, const std::string& object, const std::string& name, T value) {
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  const hid_t holder = H5Oopen(file, object.c_str(), H5P_DEFAULT);
  const hid_t attribute = H5Aopen(holder, name.c_str(), H5P_DEFAULT);
  EXPECT_GE(H5Awrite(attribute, std::is_same_v<T, double> ? H5T_NATIVE_DOUBLE : H5T_NATIVE_INT64, &value), 0) << name;
  H5Aclose(attribute);
  H5Oclose(holder);
  H5Fclose(file);
}

//! Runs invert with `bank`; expects exit 2, a message naming the bank with each fragment and
//! no word of the HDF5 library, and no output file.
void expect_bank_refused(const std::string& known, const std::string& bank, const std::vector<std::string>& fragments) {
  ScratchDir scratch("invert-damaged-bank-run");
  const std::string signal = scratch.write("signal.csv", simulated_csv({70.0}));
  const std::string out = scratch.file("out.h5");
  const auto r = run_cli("invert " + signal + " --known " + known + " --bank " + bank + " --out " + out, scratch, "timeout 60");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find(bank + ": "), std::string::npos) << r.output;
  for (const std::string& fragment : fragments)
    EXPECT_NE(r.output.find(fragment), std::string::npos) << "expected '" << fragment << "' in:\n" << r.output;
  for (const char* raw : {"H5A", "H5G", "H5D", "H5O", "failed"})
    EXPECT_EQ(r.output.find(raw), std::string::npos) << "raw HDF5 text '" << raw << "' in:\n" << r.output;
  EXPECT_FALSE(std::filesystem::exists(out));
}

//! A bank was used silently when damaged: one flipped byte in /atoms/heads (the old atom
//! table; its shapes' /atoms/onset_values now) moved two estimated lines (exit 0). Every table carries its checksum now; a damaged one is refused
//! naming it, in the tables invert uses and in those it does not (the records), and so is a
//! changed numeric attribute and one HDF5 cannot read ("H5Aexists failed" came out raw).
TEST_F(InvertCommand, ADamagedBankIsRefusedNamingTheTable) {
  ScratchDir scratch("invert-damaged-bank");
  const std::string known = scratch_->file("device.toml"), source = scratch_->file("bank.h5");
  const std::string remake = "make the bank again with stengmc calibrate";
  // The suite's device reaches Pi ~6 only: its shapes are all onset-aligned (no breakaway rows).
  for (const char* table : {"/atoms/onset_values", "/atoms/tail_phase", "/records/count"}) {
    SCOPED_TRACE(table);
    const std::string bank = bank_copy(scratch, source);
    xor_byte(bank, data_offset(bank, table) + 133, 0x08);
    expect_bank_refused(known, bank, {"table " + std::string(table) + " is damaged (checksum ", remake});
  }
  {
    const std::string bank = bank_copy(scratch, source);
    rewrite_attribute(bank, "/maps", "misfit_ratio", 0.5);
    expect_bank_refused(known, bank, {"the attributes of /maps are damaged", remake});
  }
  {
    const std::string bank = bank_copy(scratch, source);
    rewrite_attribute(bank, "/maps/misfits", "line_error_scale", 0.5);
    expect_bank_refused(known, bank, {"the attributes of /maps/misfits are damaged", remake});
  }
  {
    const std::string bank = bank_copy(scratch, source);
    rewrite_attribute(bank, "/atoms", "split_pi", 11.0);
    expect_bank_refused(known, bank, {"the attributes of /atoms are damaged", remake});
  }
  {
    // The attribute's name length in its header message, made impossible: HDF5 cannot decode it.
    const std::string bank = bank_copy(scratch, source);
    const std::string bytes = read_text_file(bank, "the bank", 1ull << 30);
    const auto name = bytes.find(std::string("bank_format_version") + '\0');
    ASSERT_NE(name, std::string::npos);
    xor_byte(bank, name - 6, 0xff);
    xor_byte(bank, name - 5, 0xff);
    expect_bank_refused(known, bank, {"the calibration bank is damaged (its attribute /@bank_format_version cannot be read)", remake});
  }
}

//! Format 1 banks carry no checksums, format 2 ones the old atom table, format 3 ones one set
//! of maps for both fit classes and format 4 ones no line_se_bound: refused with what
//! to do, as are format versions that are no versions (bank_format_version = -1 and
//! format_version = -1 were accepted).
TEST_F(InvertCommand, ABankOfAnOldOrInvalidFormatIsRefused) {
  ScratchDir scratch("invert-bank-format");
  const std::string known = scratch_->file("device.toml"), source = scratch_->file("bank.h5");
  std::string bank = bank_copy(scratch, source);
  rewrite_attribute(bank, "/", "bank_format_version", std::int64_t{1});
  expect_bank_refused(known, bank, {"calibration bank format 1 carries no checksums", "make the bank again with stengmc calibrate"});
  bank = bank_copy(scratch, source);
  rewrite_attribute(bank, "/", "bank_format_version", std::int64_t{2});
  expect_bank_refused(known, bank, {"calibration bank format 2 holds the atoms as a table", "reads format 5",
                                    "make the bank again with stengmc calibrate"});
  bank = bank_copy(scratch, source);
  rewrite_attribute(bank, "/", "bank_format_version", std::int64_t{3});
  expect_bank_refused(known, bank, {"calibration bank format 3 holds one set of maps", "reads format 5",
                                    "make the bank again with stengmc calibrate"});
  bank = bank_copy(scratch, source);
  rewrite_attribute(bank, "/", "bank_format_version", std::int64_t{4});
  expect_bank_refused(known, bank, {"calibration bank format 4 sorts records into fit classes by their residual alone",
                                    "reads format 5", "make the bank again with stengmc calibrate"});
  bank = bank_copy(scratch, source);
  rewrite_attribute(bank, "/", "bank_format_version", std::int64_t{-1});
  expect_bank_refused(known, bank, {"bank_format_version -1 is not a valid version"});
  bank = bank_copy(scratch, source);
  rewrite_attribute(bank, "/", "format_version", std::int64_t{-1});
  expect_bank_refused(known, bank, {"format_version -1 is not a valid version"});
}

//! calibrate --restart deleted whatever sat at <bank>.journal (a FIFO, a folder); --refit,
//! which runs no journal, deleted it too. Both leave it now, and --restart refuses it.
TEST_F(InvertCommand, CalibrateRemovesOnlyItsOwnJournal) {
  ScratchDir scratch("calibrate-journal-path");
  const std::string bank = bank_copy(scratch, scratch_->file("bank.h5")), journal = bank + ".journal";
  ASSERT_EQ(::mkfifo(journal.c_str(), 0666), 0);
  const auto refused =
      run_cli("calibrate " + scratch_->file("device.toml") + " --restart -o " + bank + " -j 2", scratch, "timeout 60");
  EXPECT_EQ(refused.exit_code, 2) << refused.output;
  EXPECT_NE(refused.output.find(journal + " is a FIFO"), std::string::npos) << refused.output;
  EXPECT_TRUE(std::filesystem::is_fifo(journal));
  std::filesystem::remove(journal);
  std::filesystem::create_directory(journal);
  const auto refit = run_cli("calibrate " + scratch_->file("device.toml") + " --refit -o " + bank, scratch, "timeout 60");
  EXPECT_EQ(refit.exit_code, 0) << refit.output;
  EXPECT_TRUE(std::filesystem::is_directory(journal));
}

}  // namespace
}  // namespace stengmc
