// `stengmc spectrum` on a CSV signal and on a run file, and its rejected inputs.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

#include "core/constants.hpp"
#include "core/hdf5_file.hpp"
#include "support/cli_runner.hpp"

namespace stengmc {
namespace {

using testing::run_cli;
using testing::ScratchDir;

//! t,V of a sine of `amplitude` at `frequency` sampled at 100 MHz; `jitter` perturbs one time.
std::string sine_csv(double amplitude, double frequency, std::size_t samples, bool jitter = false) {
  std::ostringstream out;
  out.precision(17);
  out << "t,V\n";
  for (std::size_t j = 0; j < samples; ++j) {
    double t = static_cast<double>(j) * 1e-8;
    if (jitter && j == samples / 2) t += 3e-9;
    out << t << "," << amplitude * std::sin(2 * PI * frequency * t) << "\n";
  }
  return out.str();
}

TEST(SpectrumCommand, FindsTheLineOfACsvSine) {
  // One line of 3 mV at 1.234 MHz: the FFT peak, refined on the windowed DTFT, lies within
  // a hundredth of a bin (bin = 1 / 40.96 us = 24.4 kHz) and its amplitude within 0.1 %.
  ScratchDir scratch("spectrum-csv");
  const std::string csv = scratch.write("v.csv", sine_csv(3e-3, 1.234e6, 4096));
  const auto r = run_cli("spectrum " + csv + " --out " + scratch.file("s.h5"), scratch);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  Hdf5Reader file(scratch.file("s.h5"));
  EXPECT_EQ(file.string_attribute("/", "file_type"), "stengmc-spectrum");
  const auto f = file.vector("/spectrum/peaks/frequency");
  const auto a = file.vector("/spectrum/peaks/amplitude");
  ASSERT_EQ(f.size(), 1u) << r.output;
  EXPECT_NEAR(f[0], 1.234e6, 244.0);
  EXPECT_NEAR(a[0], 3e-3, 3e-6);
  // A measured record has no asperities to compare with: the summary lists what was found
  // (the line, to the 10 Hz the table prints: 1.23400 MHz), not "FFT 0 of 0 sliding".
  EXPECT_NE(r.output.find("FFT peak [MHz]"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(" 1.23400 "), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("0 of 0 sliding"), std::string::npos) << r.output;
}

TEST(SpectrumCommand, RejectsANonUniformGrid) {
  ScratchDir scratch("spectrum-jitter");
  const std::string csv = scratch.write("v.csv", sine_csv(1.0, 1e6, 512, true));
  const auto r = run_cli("spectrum " + csv + " --out " + scratch.file("s.h5"), scratch);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("v.csv: spectrum: the time grid is not uniform"), std::string::npos) << r.output;
}

TEST(SpectrumCommand, RejectsAMalformedCsvAndAnUnknownSettingsKey) {
  ScratchDir scratch("spectrum-bad");
  const std::string csv = scratch.write("v.csv", "t,V\n0,1\n1e-8,x\n");
  auto r = run_cli("spectrum " + csv + " --out " + scratch.file("s.h5"), scratch);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("v.csv:3: '1e-8,x' is not two finite numbers"), std::string::npos) << r.output;

  const std::string good = scratch.write("w.csv", sine_csv(1.0, 1e6, 512));
  const std::string settings = scratch.write("s.toml", "[spectrum]\nwindow = \"hann\"\nwindows = 3\n");
  r = run_cli("spectrum " + good + " --settings " + settings + " --out " + scratch.file("s.h5"), scratch);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("s.toml:3: unknown key 'spectrum.windows'"), std::string::npos) << r.output;
}

TEST(SpectrumCommand, ReanalysesARunFileWithItsExpectedLines) {
  // The Fig. 6 study (v_b = 10 m/s, l = 50 um) run without [spectrum], then analysed by
  // `spectrum` with the same settings: all four asperities identified, as in the run itself.
  ScratchDir scratch("spectrum-run");
  const std::string study = std::string(STENGMC_SOURCE_DIR) + "/studies/paper/fig6_vb10_l50.toml";
  ASSERT_EQ(run_cli("run " + study + " --out " + scratch.file("run.h5"), scratch).exit_code, 0);
  const auto r = run_cli("spectrum " + scratch.file("run.h5") + " --settings " + study + " --out " + scratch.file("s.h5"), scratch);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  Hdf5Reader file(scratch.file("s.h5"));
  const auto identified = file.vector("/spectrum/identifiability/fft/identified");
  EXPECT_EQ(identified, (std::vector<double>{1, 1, 1, 1})) << r.output;
  EXPECT_EQ(Hdf5Reader(scratch.file("run.h5")).vector("/spectrum/identifiability/fft/identified"), identified);
}

TEST(SpectrumCommand, AgreesWithRunOnWhichAsperitiesSlideAndRendersFigures) {
  // Fig. 6 at v_b = 1 m/s: the k = 25 N/m asperity slides 0.888 of the whole run but more
  // of the analysed interval. With min_slip_fraction = 0.9 between the two, `run` and
  // `spectrum` must still agree: both judge sliding on the same interval.
  ScratchDir scratch("spectrum-agree");
  std::ifstream in(std::string(STENGMC_SOURCE_DIR) + "/studies/paper/fig6_vb1_l50.toml");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  text.replace(text.find("[spectrum]\n"), 11, "[spectrum]\nmin_slip_fraction = 0.9\n");
  text.replace(text.find("../../surfaces/"), 15, std::string(STENGMC_SOURCE_DIR) + "/surfaces/");
  const std::string study = scratch.write("study.toml", text);
  ASSERT_EQ(run_cli("run " + study + " --out " + scratch.file("run.h5"), scratch).exit_code, 0);
  const auto r = run_cli("spectrum " + scratch.file("run.h5") + " --settings " + study + " --out " + scratch.file("s.h5") + " --figures", scratch);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(Hdf5Reader(scratch.file("run.h5")).vector("/spectrum/sliding"), Hdf5Reader(scratch.file("s.h5")).vector("/spectrum/sliding"));
  EXPECT_TRUE(std::filesystem::exists(scratch.file("s_spectrum.png"))) << r.output;
}

TEST(SpectrumCommand, RejectsAWrongHeaderAndUnitsInCsvValues) {
  ScratchDir scratch("spectrum-strict");
  auto r = run_cli("spectrum " + scratch.write("a.csv", "t,Voltage\n0,1\n") + " --out " + scratch.file("s.h5"), scratch);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("a.csv:1: header must be `t,V`"), std::string::npos) << r.output;
  r = run_cli("spectrum " + scratch.write("b.csv", "t,V\n0.0s,1\n") + " --out " + scratch.file("s.h5"), scratch);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("b.csv:2:"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace stengmc
