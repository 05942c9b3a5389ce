// Every rejected input of the README's "Rejected inputs" table, one test per row: the
// program exits non-zero, names the file, the line and the key, says what was expected,
// and leaves no output file behind.
#include <gtest/gtest.h>

#include <filesystem>

#include "core/hdf5_file.hpp"
#include "support/cli_runner.hpp"

namespace stengmc {
namespace {

using testing::run_cli;
using testing::ScratchDir;

// A valid Model 2 study (the paper's four asperities, l = 50 um); each test breaks one thing.
std::string valid_study(const std::string& replace_from = "", const std::string& replace_to = "") {
  std::string text = R"(title = "bad-input test"
duration_s = 2e-6
sample_rate_hz = 100e6

[model]
kind = "model2"
belt_velocity_m_per_s = 10

[surface]
[surface.defaults]
length_m = 50e-6
[[surface.asperity]]
stiffness_n_per_m = 25
mass_kg = 1e-12
[[surface.asperity]]
stiffness_n_per_m = 155

[circuit]
load_resistance_ohm = 1e6
)";
  if (!replace_from.empty()) {
    const auto at = text.find(replace_from);
    if (at == std::string::npos) throw std::logic_error("test bug: '" + replace_from + "' not in the study");
    text.replace(at, replace_from.size(), replace_to);
  }
  return text;
}

struct Rejection {
  int exit_code;
  std::string output;
  bool output_file_exists;
};

Rejection run_study_text(const std::string& text, const std::string& name) {
  ScratchDir scratch(name);
  const std::string study = scratch.write("study.toml", text);
  const std::string out = scratch.file("out.h5");
  const auto result = run_cli("run " + study + " --out " + out, scratch);
  bool written = std::filesystem::exists(out);
  for (const auto& entry : std::filesystem::directory_iterator(scratch.file("")))
    written = written || entry.path().extension() == ".tmp";
  return {result.exit_code, result.output, written};
}

//! Exit code 2 is bad input, 3 a model out of its domain (src/app/main.cpp).
void expect_rejected(const Rejection& r, const std::vector<std::string>& fragments, int exit_code = 2) {
  EXPECT_EQ(r.exit_code, exit_code) << r.output;
  EXPECT_FALSE(r.output_file_exists);
  for (const auto& fragment : fragments) EXPECT_NE(r.output.find(fragment), std::string::npos) << "missing '" << fragment << "' in:\n" << r.output;
}

//! Runs `circuit` on `input` and expects a non-zero exit, `fragment` in the message and no output.
void expect_circuit_rejected(const ScratchDir& scratch, const std::string& input, const std::string& fragment) {
  const auto r = run_cli("circuit " + input + " -R 1e6 --out " + scratch.file("out.h5"), scratch);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find(fragment), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(scratch.file("out.h5")));
  for (const auto& entry : std::filesystem::directory_iterator(scratch.file("")))
    EXPECT_NE(entry.path().extension(), ".tmp") << entry.path();
}

TEST(BadInput, TheValidStudyRuns) {
  // Guards the tests below: each breaks exactly one thing in a study that works.
  const Rejection r = run_study_text(valid_study(), "valid");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(r.output_file_exists);
}

TEST(BadInput, UnknownKey) {
  expect_rejected(run_study_text(valid_study("belt_velocity_m_per_s = 10", "belt_velocity_m_per_s = 10\nbelt_speed = 3"), "unknown"),
                  {"study.toml:8:", "unknown key 'model.belt_speed'", "allowed here:", "belt_velocity_m_per_s"});
}

TEST(BadInput, WrongType) {
  expect_rejected(run_study_text(valid_study("duration_s = 2e-6", "duration_s = \"2 us\""), "type"),
                  {"study.toml:2:", "duration_s", "is a string; expected a number"});
}

TEST(BadInput, NonPositiveMass) {
  expect_rejected(run_study_text(valid_study("mass_kg = 1e-12", "mass_kg = 0"), "mass"),
                  {"study.toml:14:", "mass_kg = 0 must be > 0"});
}

TEST(BadInput, NonPositiveStiffness) {
  expect_rejected(run_study_text(valid_study("stiffness_n_per_m = 155", "stiffness_n_per_m = -155"), "stiffness"),
                  {"study.toml:16:", "stiffness_n_per_m = -155 must be > 0"});
}

TEST(BadInput, NonPositiveLength) {
  expect_rejected(run_study_text(valid_study("length_m = 50e-6", "length_m = 0.0"), "length"),
                  {"study.toml:11:", "length_m = 0 must be > 0"});
}

TEST(BadInput, SampleRateBelowTwiceTheHighestNaturalFrequency) {
  // k = 155 N/m, m = 1e-12 kg: f = 1.98 MHz, so 3 MHz is below 2 f.
  expect_rejected(run_study_text(valid_study("sample_rate_hz = 100e6", "sample_rate_hz = 3e6"), "rate"),
                  {"study.toml:3:", "sample_rate_hz = 3e+06 Hz is below twice the highest natural frequency", "asperity 2"});
}

TEST(BadInput, DisplacementReachesLengthUnderPolicyError) {
  // The paper's l = 10 um: the k = 25 N/m asperity settles near mu N / k ~ 11 um (MODEL.md §1).
  const Rejection r = run_study_text(valid_study("length_m = 50e-6", "length_m = 10e-6"), "domain");
  expect_rejected(r, {"asperity 1 (k = 25 N/m): x reaches l = 10 um at t =", "policy = \"flag\""}, 3);
}

TEST(BadInput, UnreadableDisplacementFile) {
  ScratchDir scratch("unreadable");
  const std::string not_hdf5 = scratch.write("x.h5", "this is not HDF5");
  expect_circuit_rejected(scratch, not_hdf5, "x.h5: not a readable HDF5 file");
}

TEST(BadInput, MalformedDisplacementCsv) {
  ScratchDir scratch("malformed");
  const std::string csv = scratch.write("x.csv", "t,x1\n0,0\n1e-9,1e-7\n2e-9,abc\n3e-9,2e-7\n");
  expect_circuit_rejected(scratch, csv, "x.csv:4: column 'x1' = 'abc' is not a finite number");
}

TEST(BadInput, CsvRowWithAMissingField) {
  ScratchDir scratch("short-row");
  const std::string csv = scratch.write("x.csv", "t,x1\n0,0\n1e-9\n");
  expect_circuit_rejected(scratch, csv, "x.csv:3: 1 fields; the header has 2");
}

TEST(BadInput, DisplacementHdf5MissingADataset) {
  // A valid HDF5 file that lacks /asperity/x.
  ScratchDir scratch("missing-dataset");
  const std::string input = scratch.file("in.h5");
  {
    Hdf5Writer file(input);
    const std::vector<double> t{0.0, 1e-9, 2e-9, 3e-9};
    file.write("/time", t, "s");
    file.commit();
  }
  expect_circuit_rejected(scratch, input, "in.h5: dataset /asperity/x is missing");
}

TEST(BadInput, CommandLineValuesAreCheckedWithPlainMessages) {
  ScratchDir scratch("cli-values");
  const std::string csv = scratch.write("x.csv", "t,x1\n0,0\n1e-9,1e-7\n2e-9,2e-7\n3e-9,1e-7\n");
  const auto r = run_cli("circuit " + csv + " -R inf --out " + scratch.file("out.h5"), scratch);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("'inf' is not a finite number"), std::string::npos) << r.output;
}

TEST(BadInput, OutputThatWouldOverwriteTheInput) {
  ScratchDir scratch("overwrite");
  const std::string csv = scratch.write("x.csv", "t,x1\n0,0\n1e-9,1e-7\n2e-9,2e-7\n3e-9,1e-7\n");
  const auto r = run_cli("circuit " + csv + " -R 1e6 --out " + csv, scratch);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("is the input file"), std::string::npos) << r.output;
  EXPECT_EQ(std::filesystem::file_size(csv), std::string("t,x1\n0,0\n1e-9,1e-7\n2e-9,2e-7\n3e-9,1e-7\n").size());  // untouched
}

}  // namespace
}  // namespace stengmc
