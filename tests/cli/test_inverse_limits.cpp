// `invert` and `calibrate` hold the known device to the checks `run` makes and their work to
// the limits every command has (docs/faults.md, "Faults" and "Limits"), through the real
// command line. Each case used to run unbounded (minutes and gigabytes), or to stop with raw
// library text: now it is refused up front, naming the file and the key or the limit, and
// leaves no output, bank or journal. Every command runs under `timeout 60`, so a regression
// to "unbounded" fails the test instead of hanging it.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "inverse/calibration_run.hpp"
#include "inverse/inversion_work.hpp"
#include "pipeline/study.hpp"
#include "support/cli_runner.hpp"
#include "support/inverse_device.hpp"

namespace stengmc {
namespace {

using testing::CliResult;
using testing::ScratchDir;

//! The inverse tests' known device (20 us records, the quick prior of 1-3 asperities) with
//! `from` replaced by `to`.
std::string device_study(const std::string& from = "", const std::string& to = "") {
  std::string text = testing::known_device_study("20e-6", testing::quick_prior());
  if (!from.empty()) {
    const auto at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) text.replace(at, from.size(), to);
  }
  return text;
}

//! A record at 100 MHz that is no constant: a sine of 1 mV.
std::string sine_csv(std::size_t samples) {
  std::string out = "t,V\n";
  char line[64];
  for (std::size_t m = 0; m < samples; ++m) {
    std::snprintf(line, sizeof line, "%.17g,%.17g\n", static_cast<double>(m) * 1e-8, 1e-3 * std::sin(0.7 * static_cast<double>(m)));
    out += line;
  }
  return out;
}

//! `stengmc arguments`, stopped after 60 s (exit 124) if it runs that long.
CliResult run_bounded(const std::string& arguments, const ScratchDir& scratch) {
  return testing::run_command("timeout 60 " + std::string(STENGMC_BINARY) + " " + arguments, scratch);
}

struct Outcome {
  CliResult invert, calibrate;
  bool left_something = false;  //!< an output, a bank or a journal
};

//! invert (on a 2001-sample sine) and calibrate with the known device `study`.
Outcome invert_and_calibrate(const std::string& study, const std::string& extra = "") {
  ScratchDir scratch("inverse-limits");
  const std::string known = scratch.write("known.toml", study);
  const std::string record = scratch.write("record.csv", sine_csv(2001));
  Outcome o;
  o.invert = run_bounded("invert " + record + " --known " + known + " -o " + scratch.file("out.h5") + " " + extra, scratch);
  o.calibrate = run_bounded("calibrate " + known + " -o " + scratch.file("bank.h5") + " " + extra, scratch);
  for (const char* name : {"out.h5", "bank.h5", "bank.h5.journal"}) o.left_something |= std::filesystem::exists(scratch.file(name));
  return o;
}

void expect_refused(const Outcome& o, int exit_code, const std::vector<std::string>& expected) {
  for (const CliResult* r : {&o.invert, &o.calibrate}) {
    EXPECT_EQ(r->exit_code, exit_code) << r->output;
    for (const std::string& e : expected)
      EXPECT_NE(r->output.find(e), std::string::npos) << "expected '" << e << "' in:\n" << r->output;
  }
  EXPECT_FALSE(o.left_something);
}

// Each ran past 60 s and 3.5-6.2 GB (mass 1e-300: the integrator's whole step budget per
// atom), or stopped with Boost's "trunc ... -nan" (R = 1e300, c = 1), or after 18 s and
// 1.8 GB with an internal message (N = 1e300), or wrote a bank's NaN (v_b = 1e-6: a journal
// left behind). The sample-rate check is run's own, on the stiffest asperity simulated.
TEST(InverseDeviceChecks, InvertAndCalibrateRefuseUpFrontWhatCannotRunOrHasNoLine) {
  struct Case {
    std::string from, to;
    std::vector<std::string> expected;
  };
  const std::vector<Case> cases = {
      {"mass_kg = 1e-12", "mass_kg = 1e-300",
       {"known.toml", "sample_rate_hz = 1e+08 Hz is below twice the highest natural frequency"}},
      {"load_resistance_ohm = 1e6", "load_resistance_ohm = 1e300",
       {"known.toml:", "[circuit] load_resistance_ohm = 1e+300 Ohm", "beyond what inverse estimation can square and sum"}},
      {"damping_n_s_per_m = 1e-7", "damping_n_s_per_m = 1", {"known.toml:", "[model] damping_n_s_per_m = 1 N s/m over-damps"}},
      {"normal_load_n = 1e-3", "normal_load_n = 1e300",
       {"known.toml:", "[surface.defaults] normal_load_n = 1e+300 N", "no asperity of the prior slides"}},
      {"belt_velocity_m_per_s = 10", "belt_velocity_m_per_s = 1e-6",
       {"known.toml:", "[model] belt_velocity_m_per_s = 1e-06 m/s", "no line to invert"}}};
  for (const Case& c : cases) {
    SCOPED_TRACE(c.to);
    expect_refused(invert_and_calibrate(device_study(c.from, c.to)), 2, c.expected);
  }
}

// R = 1e-300 makes the circuit itself fail, which `run` reports as a model error (exit 3)
// at once. invert and calibrate searched ever stiffer asperities for one that "stays
// valid" (every run failed) for more than 60 s and GBs; now they stop with run's message.
TEST(InverseDeviceChecks, ACircuitThatFailsStopsThemWithRunsOwnMessage) {
  const std::string study = device_study("load_resistance_ohm = 1e6", "load_resistance_ohm = 1e-300");
  ScratchDir scratch("inverse-circuit");
  const CliResult run = run_bounded("run " + scratch.write("known.toml", study) + " -o " + scratch.file("run.h5"), scratch);
  const std::string message = "the circuit produced a non-finite voltage";
  ASSERT_EQ(run.exit_code, 3) << run.output;
  ASSERT_NE(run.output.find(message), std::string::npos) << run.output;
  expect_refused(invert_and_calibrate(study), 3, {message});
}

// A prior whose every stiffness is too soft for the device stopped with "atom table: the
// stiffness range [6.18812, 5.53311] N/m is empty": no file, no key.
TEST(InverseDeviceChecks, APriorTooSoftForTheDeviceIsRefusedNamingTheFileAndKeys) {
  const Outcome o = invert_and_calibrate(device_study("median_n_per_m = [60, 90]", "median_n_per_m = [0.5, 1]"));
  expect_refused(o, 2, {"known.toml:", "[surface.defaults] normal_load_n", "median_n_per_m, sigma_log"});
  EXPECT_EQ(o.invert.output.find("atom table"), std::string::npos) << o.invert.output;
}

// calibrate had no work limits: --records 1000000 started with an ETA of 15 h (at ~167 kB a
// record, ~167 GB). Now its estimate is refused before anything runs, as the other
// commands' are, naming the records, the estimate, the limit and the factor.
TEST(InverseWorkLimits, CalibrateRefusesAMillionRecordsUpFront) {
  ScratchDir scratch("inverse-records");
  const std::string known = scratch.write("known.toml", device_study());
  const CliResult r = run_bounded("calibrate " + known + " -o " + scratch.file("bank.h5") + " --records 1000000", scratch);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  for (const char* e : {"known.toml: the calibration's 1000000 records of 2001 samples", "needs ~", "x the limit of",
                        "Reduce it, or raise the limit with --max-"})
    EXPECT_NE(r.output.find(e), std::string::npos) << "expected '" << e << "' in:\n" << r.output;
  EXPECT_FALSE(std::filesystem::exists(scratch.file("bank.h5")));
  EXPECT_FALSE(std::filesystem::exists(scratch.file("bank.h5.journal")));
}

// invert had no --max-memory-gb / --max-steps: a long record ran unbounded. Both commands
// now take the limits and apply them to their estimate before anything is computed.
TEST(InverseWorkLimits, BothCommandsTakeTheLimitsOfTheOtherCommands) {
  ScratchDir scratch("inverse-options");
  const std::string known = scratch.write("known.toml", device_study());
  const std::string record = scratch.write("long.csv", sine_csv(200001));
  const std::string invert = "invert " + record + " --known " + known + " -o " + scratch.file("out.h5");
  const CliResult memory = run_bounded(invert + " --max-memory-gb 0.2", scratch);
  EXPECT_EQ(memory.exit_code, 2) << memory.output;
  for (const char* e : {"inverting 1 record(s) of 200001 samples needs ~", "GB of memory", "--max-memory-gb"})
    EXPECT_NE(memory.output.find(e), std::string::npos) << "expected '" << e << "' in:\n" << memory.output;
  const CliResult steps = run_bounded(invert + " --max-steps 1e6", scratch);
  EXPECT_EQ(steps.exit_code, 2) << steps.output;
  EXPECT_NE(steps.output.find("steps, "), std::string::npos) << steps.output;
  EXPECT_NE(steps.output.find("--max-steps"), std::string::npos) << steps.output;
  const CliResult bank = run_bounded("calibrate " + known + " -o " + scratch.file("bank.h5") + " --max-memory-gb 0.01", scratch);
  EXPECT_EQ(bank.exit_code, 2) << bank.output;
  EXPECT_NE(bank.output.find("--max-memory-gb"), std::string::npos) << bank.output;
  EXPECT_FALSE(std::filesystem::exists(scratch.file("out.h5")));
  EXPECT_FALSE(std::filesystem::exists(scratch.file("bank.h5.journal")));
}

// A record of 1e7 samples (Python's invert(np.zeros(10**8)) reached 11.5 GB) is over the
// default limits: the atoms' forward runs and the estimators alone need more than 8 GB.
TEST(InverseWorkLimits, ATenMillionSampleRecordIsOverTheDefaultLimits) {
  const Study known = parse_study(device_study(), "known.toml", std::nullopt);
  const InverseSetup setup = inverse_setup(known, RecordGrid{0.0, 1e-8, 10'000'000});
  const WorkEstimate e = estimate_inversion(known, setup, {.records = 1, .threads = 2, .builds_atoms = true});
  EXPECT_GT(e.memory_bytes, WorkLimits{}.memory_bytes);
  EXPECT_NE(exceeded_limit(e, WorkLimits{}).find("--max-memory-gb"), std::string::npos);
  // The same device on its own 2001-sample grid is well within them.
  const WorkEstimate small = estimate_inversion(known, inverse_setup(known), {.records = 1, .threads = 2, .builds_atoms = true});
  EXPECT_EQ(exceeded_limit(small, WorkLimits{}), "");
}

}  // namespace
}  // namespace stengmc
