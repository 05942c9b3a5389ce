// `stengmc track` through the real command line (docs/tracking.md): bad input is refused with
// exit 2 and a message naming the file, and leaves no output; a good record is tracked and
// its file written.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>

#include "core/hdf5_file.hpp"
#include "support/cli_runner.hpp"

namespace stengmc {
namespace {

using testing::CliResult;
using testing::ScratchDir;

std::string source(const std::string& relative) { return std::string(STENGMC_SOURCE_DIR) + "/" + relative; }

std::string device() { return source("studies/monitoring/device_unexcited.toml"); }

//! A 200 us record at 100 MHz: one damped line at 1.2 MHz (k ~ 57 N/m) from 20 us, and noise.
std::string ringing_csv() {
  std::string out = "t,V\n";
  char line[64];
  unsigned state = 12345;
  for (std::size_t m = 0; m < 20000; ++m) {
    const double t = static_cast<double>(m) * 1e-8;
    state = state * 1103515245u + 12345u;
    const double noise = 1e-5 * (static_cast<double>(state >> 8) / 16777216.0 - 0.5);
    const double v = t < 20e-6 ? 0.0 : 1e-3 * std::exp(-5e4 * (t - 20e-6)) * std::sin(2.0 * M_PI * 1.2e6 * (t - 20e-6));
    std::snprintf(line, sizeof line, "%.17g,%.17g\n", t, v + noise);
    out += line;
  }
  return out;
}

// (d) A record that is not a record, a record that does not exist, a device that does not exist,
// a device study without a device key (mass_kg: tracking would assume a mass) and a window
// shorter than ESPRIT can use: exit 2, the message names the file (or the option), no output.
TEST(TrackCommand, BadInputIsRefusedNamingTheFile) {
  const ScratchDir scratch("track-bad");
  const std::string out = scratch.file("out.h5");
  const std::string bad = scratch.write("bad.csv", "t,V\n0,1\n1e-8,oops\n");
  CliResult r = testing::run_cli("track " + bad + " --known " + device() + " -o " + out, scratch);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("bad.csv"), std::string::npos) << r.output;

  r = testing::run_cli("track " + scratch.file("missing.csv") + " --known " + device() + " -o " + out, scratch);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("missing.csv"), std::string::npos) << r.output;

  const std::string record = scratch.write("ring.csv", ringing_csv());
  r = testing::run_cli("track " + record + " --known " + scratch.file("no_device.toml") + " -o " + out, scratch);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("no_device.toml"), std::string::npos) << r.output;

  std::string text;
  {
    std::ifstream in(device());
    text.assign(std::istreambuf_iterator<char>(in), {});
  }
  text.erase(text.find("mass_kg = 1e-12\n"), 16);
  const std::string no_mass = scratch.write("no_mass.toml", text);
  r = testing::run_cli("track " + record + " --known " + no_mass + " -o " + out, scratch);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("no_mass.toml"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("mass_kg"), std::string::npos) << r.output;

  r = testing::run_cli("track " + record + " --known " + device() + " --window-s 1e-7 -o " + out, scratch);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--window-s"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(out));
}

// A good record: tracked, one track, its onset within 10 us of 20 us, its file written.
TEST(TrackCommand, TracksARingingAndWritesItsFile) {
  const ScratchDir scratch("track-good");
  const std::string record = scratch.write("ring.csv", ringing_csv());
  const std::string out = scratch.file("ring_track.h5");
  const CliResult r = testing::run_cli("track " + record + " --known " + device() + " -o " + out, scratch);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("1 tracks; events: 1 onsets, 0 releases, 0 steps"), std::string::npos) << r.output;
  EXPECT_TRUE(std::filesystem::exists(out));
  // The record is silent until 20 us: no asperity stuck at its start (no plateau), and the
  // summary and the file say the start's count was not read (issue 26 F4).
  EXPECT_NE(r.output.find("at the start: not read"), std::string::npos) << r.output;
  const Hdf5Reader f(out);
  EXPECT_EQ(f.integer_attribute("/", "start_count"), std::optional<std::int64_t>(0));
  EXPECT_FALSE(f.number_attribute("/", "start_level").has_value());
}

}  // namespace
}  // namespace stengmc
