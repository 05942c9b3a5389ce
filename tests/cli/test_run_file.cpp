// The run file describes itself (README "Output files"), and one study run twice gives
// bitwise-identical datasets (results are reproducible).
#include <gtest/gtest.h>

#include <H5Cpp.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "core/hdf5_file.hpp"
#include "support/cli_runner.hpp"

namespace stengmc {
namespace {

using testing::run_cli;
using testing::ScratchDir;

const char* STUDY = R"(title = "run-file test"
seed = 42
duration_s = 3e-6
sample_rate_hz = 100e6
[model]
kind = "model2"
belt_velocity_m_per_s = 10
[surface]
file = "SURFACE"
[circuit]
load_resistance_ohm = 1e6
)";

std::string study_text() {
  std::string text = STUDY;
  text.replace(text.find("SURFACE"), 7, std::string(STENGMC_SOURCE_DIR) + "/surfaces/paper_four_stiffnesses_l50.toml");
  return text;
}

std::string int_attribute_text(const std::string& path, const std::string& name) {
  H5::H5File file(path, H5F_ACC_RDONLY);
  H5::Attribute a = file.openGroup("/").openAttribute(name);
  long long value = 0;
  a.read(H5::PredType::NATIVE_LLONG, &value);
  return std::to_string(value);
}

TEST(RunFile, RecordsStudyTextSeedVersionAndRevisionAndHasTheDocumentedLayout) {
  ScratchDir scratch("run-file");
  const std::string study = scratch.write("study.toml", study_text());
  const std::string out = scratch.file("run.h5");
  const auto r = run_cli("run " + study + " --out " + out, scratch);
  ASSERT_EQ(r.exit_code, 0) << r.output;

  Hdf5Reader file(out);
  EXPECT_EQ(file.string_attribute("/", "file_type"), "stengmc-run");
  EXPECT_EQ(file.string_attribute("/", "input_text"), study_text());  // verbatim
  EXPECT_EQ(int_attribute_text(out, "seed"), "42");
  EXPECT_EQ(int_attribute_text(out, "format_version"), "1");
  EXPECT_FALSE(file.string_attribute("/", "program_version").empty());
  EXPECT_FALSE(file.string_attribute("/", "git_revision").empty());

  const std::size_t samples = 301;  // 3 us at 100 MHz, both ends
  EXPECT_EQ(file.vector("/time").size(), samples);
  for (const char* name : {"/asperity/x", "/asperity/v", "/asperity/friction", "/asperity/current"}) {
    const auto m = file.matrix(name);
    ASSERT_EQ(m.size(), 4u) << name;
    EXPECT_EQ(m[0].size(), samples) << name;
  }
  for (const char* name : {"/asperity/k", "/asperity/m", "/asperity/N", "/asperity/sigma", "/asperity/d0",
                           "/asperity/w", "/asperity/l"})
    EXPECT_EQ(file.vector(name).size(), 4u) << name;
  EXPECT_EQ(file.vector("/asperity/k"), (std::vector<double>{25, 50, 100, 155}));
  EXPECT_EQ(file.vector("/circuit/voltage").size(), samples);
  EXPECT_EQ(file.vector("/circuit/charge").size(), samples);
  EXPECT_TRUE(file.has("/events/time"));
  EXPECT_TRUE(file.has("/events/kind"));
}

TEST(RunFile, SameStudyTwiceGivesBitwiseIdenticalDatasets) {
  ScratchDir scratch("reproducible");
  const std::string study = scratch.write("study.toml", study_text());
  ASSERT_EQ(run_cli("run " + study + " --out " + scratch.file("a.h5"), scratch).exit_code, 0);
  ASSERT_EQ(run_cli("run " + study + " --out " + scratch.file("b.h5"), scratch).exit_code, 0);
  Hdf5Reader a(scratch.file("a.h5"));
  Hdf5Reader b(scratch.file("b.h5"));
  for (const char* name : {"/asperity/x", "/asperity/v", "/asperity/friction", "/asperity/current"})
    EXPECT_EQ(a.matrix(name), b.matrix(name)) << name;  // operator== on doubles: bitwise for finite values
  for (const char* name : {"/circuit/voltage", "/circuit/charge", "/events/time"})
    EXPECT_EQ(a.vector(name), b.vector(name)) << name;
}

TEST(RunFile, CircuitCommandReadsARunFileAndReproducesItsCircuitWithTheSpline) {
  // `circuit` on a run's own x samples (spline between them) must reproduce the run's
  // voltage, which was computed from the solver's dense output. Starting from rest, each
  // asperity catches the 10 m/s belt within ~36 ns (mu_s N / m = 2.8e8 m/s^2): a kink in
  // x' that no spline through 10 ns samples can follow, so the comparison starts at
  // 0.5 us. After that the motion is smooth and the spline's error in x' is
  // ~(omega dt)^4 / 384 ~ 1e-5 relative (measured: 2.9e-6 in V); 1e-4 bounds that and
  // still catches any layout or unit mismatch, which would be O(1).
  ScratchDir scratch("roundtrip");
  const std::string study = scratch.write("study.toml", study_text());
  ASSERT_EQ(run_cli("run " + study + " --out " + scratch.file("run.h5"), scratch).exit_code, 0);
  const auto r = run_cli("circuit " + scratch.file("run.h5") + " -R 1e6 --out " + scratch.file("circuit.h5"), scratch);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto v_run = Hdf5Reader(scratch.file("run.h5")).vector("/circuit/voltage");
  const auto v_circuit = Hdf5Reader(scratch.file("circuit.h5")).vector("/circuit/voltage");
  ASSERT_EQ(v_run.size(), v_circuit.size());
  double num = 0.0, den = 0.0;
  const std::size_t start = 50;  // 0.5 us at 100 MHz
  for (std::size_t j = start; j < v_run.size(); ++j) {
    num += (v_run[j] - v_circuit[j]) * (v_run[j] - v_circuit[j]);
    den += v_run[j] * v_run[j];
  }
  EXPECT_LT(std::sqrt(num / den), 1e-4);
}

TEST(RunFile, OutputTracesSelectWhichArraysAreWritten) {
  ScratchDir scratch("traces");
  const std::string study = scratch.write("study.toml", study_text() + "[output]\ntraces = [\"x\", \"charge\"]\n");
  const auto r = run_cli("run " + study + " --out " + scratch.file("run.h5"), scratch);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  Hdf5Reader file(scratch.file("run.h5"));
  EXPECT_TRUE(file.has("/asperity/x"));
  EXPECT_TRUE(file.has("/asperity/charge"));
  for (const char* omitted : {"/asperity/v", "/asperity/friction", "/asperity/current"}) EXPECT_FALSE(file.has(omitted)) << omitted;
  for (const char* always : {"/time", "/circuit/voltage", "/circuit/charge", "/asperity/k", "/asperity/l"})
    EXPECT_TRUE(file.has(always)) << always;
}

}  // namespace
}  // namespace stengmc
