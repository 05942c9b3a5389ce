// Inputs that used to escape as raw errors (a Boost message, std::bad_alloc, a Python
// traceback, a hang) or be accepted when they should not, each now a named error with exit
// 2 (docs/faults.md). Run through the real command line; each test
// checks the exit code, that the message names the file (and key or line where there is
// one), and that no raw text leaks out.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/hdf5_file.hpp"
#include "support/cli_runner.hpp"
#include "support/test_surfaces.hpp"

namespace stengmc {
namespace {

using testing::run_cli;
using testing::ScratchDir;

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

void expect_named_error(const testing::CliResult& r, const std::vector<std::string>& fragments, int exit_code = 2) {
  EXPECT_EQ(r.exit_code, exit_code) << r.output;
  for (const auto& fragment : fragments) EXPECT_TRUE(contains(r.output, fragment)) << "missing '" << fragment << "' in:\n" << r.output;
  for (const char* raw : {"boost::", "toms748", "bad_alloc", "Traceback", "std::"})
    EXPECT_FALSE(contains(r.output, raw)) << "raw error text '" << raw << "' in:\n" << r.output;
}

std::string gw_surface(const std::string& from, const std::string& to) {
  std::ifstream in(std::string(STENGMC_SOURCE_DIR) + "/surfaces/pet_on_steel_gw.toml");
  std::stringstream text;
  text << in.rdbuf();
  std::string s = text.str();
  const auto at = s.find(from);
  if (at == std::string::npos) throw std::logic_error("test bug: '" + from + "' not in the surface");
  return s.replace(at, from.size(), to);
}

//! Loads and moduli whose contact no double can hold: the Hertz solve's bracket overflowed
//! (W = 1e300 N, E = 1e-300 Pa) or underflowed (W = 1e-300 N), and Boost's "do not bracket
//! the root" came out raw (or "could not bracket", exit 3).
TEST(NamedErrors, ExtremeLoadsAndModuliAreRefusedAtTheirKey) {
  ScratchDir scratch("extreme-contact");
  for (const auto& [from, to] : std::vector<std::pair<std::string, std::string>>{
           {"nominal_load_n = 0.02 ", "nominal_load_n = 1e300 "},
           {"nominal_load_n = 0.02 ", "nominal_load_n = 1e-300 "},
           {"youngs_modulus_pa = 2.8e9", "youngs_modulus_pa = 1e-300"}}) {
    SCOPED_TRACE(to);
    const std::string surface = scratch.write("surface.toml", gw_surface(from, to));
    expect_named_error(run_cli("surface " + surface + " -k 3 -o " + scratch.file("out.h5"), scratch),
                       {"surface.toml:", "nominal_load_n", "E*"});
    EXPECT_FALSE(std::filesystem::exists(scratch.file("out.h5")));
  }
}

//! A surface file that is a device or a FIFO: /dev/zero ran out of memory (bad_alloc), a
//! FIFO blocked forever. `timeout` turns a hang into exit 124, a failure here.
TEST(NamedErrors, ASurfaceOrStudyThatIsNotARegularFileIsRefused) {
  ScratchDir scratch("not-regular-input");
  const std::string fifo = scratch.file("fifo.toml");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0666), 0);
  const std::string head = "duration_s = 1e-6\nsample_rate_hz = 100e6\n[model]\nkind = \"model1\"\n[surface]\n";
  for (const std::string& file : {std::string("/dev/zero"), fifo}) {
    SCOPED_TRACE(file);
    const std::string study = scratch.write("study.toml", head + "file = \"" + file + "\"\n");
    expect_named_error(run_cli("run " + study + " -o " + scratch.file("out.h5"), scratch, "timeout 60"),
                       {file, "is not a regular file"});
  }
  expect_named_error(run_cli("run " + fifo + " -o " + scratch.file("out.h5"), scratch, "timeout 60"),
                     {fifo, "is not a regular file"});
}

TEST(NamedErrors, AnEmptyOutputFileKeyIsRefusedWithItsLine) {
  ScratchDir scratch("empty-output");
  const std::string study = scratch.write(
      "study.toml", "duration_s = 1e-6\nsample_rate_hz = 100e6\n[model]\nkind = \"model1\"\n[surface]\n"
                    "[[surface.asperity]]\nstiffness_n_per_m = 75\n[output]\nfile = \"\"\n");
  expect_named_error(run_cli("run " + study, scratch), {"study.toml:9:", "[output] file", "empty"});
}

//! `-o ""` (an unset shell variable) silently wrote the default output (results/...) of
//! run, calibrate, merge, export-netlist and surface: an empty --out is refused naming the
//! option, and nothing is written where the user did not ask.
TEST(NamedErrors, AnEmptyOutOptionIsRefused) {
  ScratchDir scratch("empty-out-option");
  const std::string study = scratch.write(
      "study.toml", "duration_s = 1e-6\nsample_rate_hz = 100e6\n[model]\nkind = \"model1\"\n[surface]\n"
                    "[[surface.asperity]]\nstiffness_n_per_m = 75\n");
  const std::string surface = std::string(STENGMC_SOURCE_DIR) + "/surfaces/pet_on_steel_gw.toml";
  for (const std::string& command : {"run " + study, "calibrate " + study, "merge " + study + " " + study,
                                     "export-netlist " + study, "surface " + surface + " -k 2"}) {
    SCOPED_TRACE(command);
    // In the scratch folder, where the default outputs (results/...) would appear.
    const auto r = testing::run_command("cd " + scratch.file("") + " && " + STENGMC_BINARY + " " + command + " -o ''", scratch);
    expect_named_error(r, {"--out", "an empty path"});
    EXPECT_FALSE(std::filesystem::exists(scratch.file("results")));
  }
}

//! 1e308 in a CSV: a histogram bin that wide overflowed the target law (exit 1, "refusing
//! to write a non-finite value"); a voltage that large overflows its own square.
TEST(NamedErrors, HugeCsvValuesAreRefusedWithTheirLine) {
  ScratchDir scratch("huge-csv");
  const std::string surface = scratch.write("surface.toml", testing::HISTOGRAM_SURFACE);
  scratch.write("h.csv", "lower,upper,weight\n-1e308,1e308,1\n");
  expect_named_error(run_cli("surface " + surface + " -k 2 -o " + scratch.file("out.h5"), scratch), {"h.csv:2:", "width"});

  std::string csv = "t,V\n";
  for (int j = 0; j < 64; ++j) csv += std::to_string(j * 1e-9) + "," + (j == 5 ? "1e308" : "0.5") + "\n";
  const std::string voltage = scratch.write("v.csv", csv);
  expect_named_error(run_cli("spectrum " + voltage + " -o " + scratch.file("out.h5"), scratch), {"v.csv:7:", "1e308"});
}

//! Subnormal numbers (below 2.2e-308, down to 4.9e-324) are finite, and were refused as
//! "not finite" by every CSV reader.
TEST(NamedErrors, SubnormalCsvValuesAreAccepted) {
  ScratchDir scratch("subnormal-csv");
  std::ostringstream x, v;
  x << "t,x1\n";
  v << "t,V\n";
  for (int j = 0; j < 64; ++j) {
    const std::string value = j == 3 ? "1e-310" : j == 4 ? "-4.9e-324" : std::to_string(1e-7 * (j % 5));
    x << j * 1e-8 << "," << value << "\n";
    v << j * 1e-8 << "," << value << "\n";
  }
  const auto circuit = run_cli("circuit " + scratch.write("x.csv", x.str()) + " -R 1e6 -o " + scratch.file("c.h5"), scratch);
  EXPECT_EQ(circuit.exit_code, 0) << circuit.output;
  const auto spectrum = run_cli("spectrum " + scratch.write("v.csv", v.str()) + " -o " + scratch.file("s.h5"), scratch);
  EXPECT_EQ(spectrum.exit_code, 0) << spectrum.output;
  scratch.write("h.csv", "100e-6,120e-6,1e-310\n120e-6,130e-6,1\n");
  const auto surface = run_cli("surface " + scratch.write("surface.toml", testing::HISTOGRAM_SURFACE) + " -k 2 -o " +
                                   scratch.file("h.h5"), scratch);
  EXPECT_EQ(surface.exit_code, 0) << surface.output;
}

//! A small valid run file to damage.
std::string run_file(const ScratchDir& scratch) {
  const std::string study = scratch.write(
      "study.toml", "duration_s = 2e-6\nsample_rate_hz = 100e6\n[model]\nkind = \"model2\"\nbelt_velocity_m_per_s = 10\n"
                    "[surface]\n[surface.defaults]\nlength_m = 50e-6\n[[surface.asperity]]\nstiffness_n_per_m = 75\n");
  const std::string out = scratch.file("run.h5");
  const auto r = run_cli("run " + study + " -o " + out, scratch);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  return out;
}

//! Copies `from` to `to` with the root attribute format_version replaced, or /asperity/v
//! cut to its first `v_samples` columns.
void rewrite(const std::string& from, const std::string& to, std::int64_t format_version, std::size_t v_samples) {
  const Hdf5Reader in(from);
  Hdf5Writer out(to);
  out.attribute("/", "file_type", in.string_attribute("/", "file_type"));
  out.attribute("/", "format_version", format_version);
  for (const char* name : {"/time", "/circuit/voltage", "/asperity/natural_frequency", "/asperity/sigma", "/asperity/d0",
                           "/asperity/w", "/asperity/l"})
    out.write(name, in.vector(name), "");
  for (const char* name : {"/asperity/x", "/asperity/current"}) out.write(name, in.matrix(name), "");
  auto v = in.matrix("/asperity/v");
  for (auto& row : v) row.resize(std::min(row.size(), v_samples));
  out.write("/asperity/v", v, "m/s");
  out.commit();
}

TEST(NamedErrors, ANegativeFormatVersionIsRefused) {
  ScratchDir scratch("format-version");
  const std::string damaged = scratch.file("damaged.h5");
  rewrite(run_file(scratch), damaged, -1, 1000);
  expect_named_error(run_cli("circuit " + damaged + " -R 1e6 -o " + scratch.file("c.h5"), scratch),
                     {"damaged.h5", "format_version -1"});
  expect_named_error(run_cli("spectrum " + damaged + " -o " + scratch.file("s.h5"), scratch),
                     {"damaged.h5", "format_version -1"});
}

//! `spectrum` judged sliding from /asperity/v over the analysis interval and read past the
//! end of a row shorter than /time.
TEST(NamedErrors, SpectrumRefusesVelocitiesShorterThanTime) {
  ScratchDir scratch("short-velocity");
  const std::string damaged = scratch.file("damaged.h5");
  rewrite(run_file(scratch), damaged, 1, 50);
  expect_named_error(run_cli("spectrum " + damaged + " -o " + scratch.file("s.h5"), scratch),
                     {"damaged.h5", "/asperity/v", "/time"});
}

//! `plot` printed a Python traceback for a file that is not a stengmc output.
TEST(NamedErrors, PlotRefusesAFileItCannotPlot) {
  ScratchDir scratch("plot-bad");
  expect_named_error(run_cli("plot " + scratch.write("bad.h5", "not HDF5 at all"), scratch),
                     {"bad.h5", "not a readable HDF5 file"});
  const std::string foreign = scratch.file("foreign.h5");
  {
    Hdf5Writer file(foreign);
    file.write("/data", std::vector<double>{1.0, 2.0}, "1");
    file.commit();
  }
  expect_named_error(run_cli("plot " + foreign, scratch), {"foreign.h5", "not a stengmc output file"});
  const std::string truncated = scratch.file("truncated.h5");
  {
    Hdf5Writer file(truncated);  // claims to be a run file, has nothing
    file.attribute("/", "file_type", std::string("stengmc-run"));
    file.attribute("/", "format_version", std::int64_t{1});
    file.commit();
  }
  expect_named_error(run_cli("plot " + truncated, scratch), {"truncated.h5"});
}

//! Values the fuzz tests (tests/fuzz) found making a run loop or grind for minutes: each
//! is refused where it is read. (Its damaged HDF5 file that made libhdf5 loop for ever is
//! the fuzz test Fuzz.hdf5 itself, seed 1.)
TEST(NamedErrors, ValuesTheFuzzerFoundHangingAreRefusedAtTheirKey) {
  ScratchDir scratch("fuzz-found");
  const std::string head = "duration_s = 50e-6\nsample_rate_hz = 100e6\n[model]\n";
  const std::string asperities = "[surface]\n[surface.defaults]\nlength_m = 50e-6\n[[surface.asperity]]\nstiffness_n_per_m = 75\n";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {head + "kind = \"model1\"\n" + asperities + "drive_phase_rad = 1e15\n", "study.toml:10: [surface.asperity[0]] drive_phase_rad"},
      {head + "kind = \"model2\"\natan_sharpness_s_per_m = 1e15\n" + asperities, "study.toml:5: [model] atan_sharpness_s_per_m"},
      {head + "kind = \"model2\"\nstatic_friction = 2147483648\n" + asperities, "study.toml:5: [model] static_friction"}};
  for (const auto& [text, where] : cases) {
    SCOPED_TRACE(where);
    expect_named_error(run_cli("run " + scratch.write("study.toml", text) + " -o " + scratch.file("out.h5"), scratch, "timeout 30"),
                       {where});
  }
}

//! `[inverse]` is read by calibrate and invert, but a study with it is also run: a misspelt
//! key there must be refused by `run` as well, at its line, not pass with exit 0.
TEST(NamedErrors, AMisspeltInverseKeyIsRefusedByRunToo) {
  ScratchDir scratch("inverse-key");
  const std::string text = "duration_s = 2e-6\nsample_rate_hz = 100e6\n[model]\nkind = \"model2\"\n"
                           "[surface]\n[[surface.asperity]]\nstiffness_n_per_m = 75\n[inverse]\ncuont = [1, 4]\n";
  const auto r = run_cli("run " + scratch.write("study.toml", text) + " -o " + scratch.file("out.h5"), scratch);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("study.toml:9"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("cuont"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(scratch.file("out.h5")));
}

//! Bare `stengmc` is a question, not a usage error: the help, exit 0 (README, "Commands").
TEST(NamedErrors, BareCommandPrintsTheHelp) {
  ScratchDir scratch("bare");
  const auto r = run_cli("", scratch);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("Subcommands:"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("calibrate"), std::string::npos) << r.output;
}

//! --figures writes the format and resolution asked (the same options as `stengmc plot`);
//! those options without --figures are a usage error, not silently ignored.
TEST(NamedErrors, FigureOptionsChooseTheFormatAndNeedFigures) {
  ScratchDir scratch("figure-options");
  const std::string study = scratch.write(
      "study.toml", "duration_s = 2e-6\nsample_rate_hz = 100e6\n[model]\nkind = \"model2\"\nbelt_velocity_m_per_s = 10\n"
                    "[surface]\n[surface.defaults]\nlength_m = 50e-6\n[[surface.asperity]]\nstiffness_n_per_m = 75\n");
  const auto svg = run_cli("run " + study + " -o " + scratch.file("out.h5") + " --figures --figure-format svg --dpi 80", scratch);
  ASSERT_EQ(svg.exit_code, 0) << svg.output;
  std::ifstream figure(scratch.file("out.svg"));
  std::string head(200, '\0');
  figure.read(head.data(), static_cast<std::streamsize>(head.size()));
  EXPECT_NE(head.find("<svg"), std::string::npos) << head;
  EXPECT_FALSE(std::filesystem::exists(scratch.file("out.png")));
  const auto alone = run_cli("run " + study + " -o " + scratch.file("other.h5") + " --figure-format pdf", scratch);
  EXPECT_EQ(alone.exit_code, 2) << alone.output;
  EXPECT_NE(alone.output.find("--figure-format requires --figures"), std::string::npos) << alone.output;
  EXPECT_FALSE(std::filesystem::exists(scratch.file("other.h5")));
}

}  // namespace
}  // namespace stengmc
