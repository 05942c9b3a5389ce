// Every command estimates its work before it starts and refuses, naming the quantity, the
// estimate and the limit, what cannot fit or finish (docs/faults.md, "Limits"). Through the real
// command line: each refusal exits 2 within seconds (a `timeout` turns the old hang into a
// failure), writes nothing, and says by how much the limit is exceeded and how to raise it;
// an ensemble refuses up front what no realisation could do, and marks a realisation
// that exceeds the limit invalid, with the reason, while the others run.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>

#include "core/error.hpp"
#include "core/format.hpp"
#include "core/hdf5_file.hpp"
#include "pipeline/study.hpp"
#include "pipeline/work_estimate.hpp"
#include "support/cli_runner.hpp"

namespace stengmc {
namespace {

using testing::run_cli;
using testing::ScratchDir;

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

void expect_refused(const testing::CliResult& r, const ScratchDir& scratch, const std::vector<std::string>& fragments) {
  EXPECT_EQ(r.exit_code, 2) << r.output;
  for (const auto& f : fragments) EXPECT_TRUE(contains(r.output, f)) << "missing '" << f << "' in:\n" << r.output;
  EXPECT_TRUE(contains(r.output, " x the limit of ")) << r.output;
  for (const auto& entry : std::filesystem::directory_iterator(scratch.file("")))
    EXPECT_NE(entry.path().extension(), ".h5") << entry.path();
}

const char* MODEL1 = R"(duration_s = 200e-6
sample_rate_hz = 100e6
[model]
kind = "model1"
drive_frequency_hz = DRIVE
[surface]
[[surface.asperity]]
stiffness_n_per_m = 155
)";

std::string model1(const std::string& drive) {
  std::string text = MODEL1;
  return text.replace(text.find("DRIVE"), 5, drive);
}

//! drive_frequency_hz = 1e300 looped for ever in the slip-end scan (its step, 1/64 of a
//! period, no longer advanced time); 1e12 grew memory without end (an event per period).
TEST(WorkLimits, AnAbsurdDriveFrequencyIsRefusedBeforeTheSolverRuns) {
  ScratchDir scratch("limit-drive");
  const std::string out = scratch.file("out.h5");
  // Whatever the limits: the drive phase omega t keeps no digits (read-time validity).
  const auto hang = run_cli("run " + scratch.write("hang.toml", model1("1e300")) +
                                " --max-memory-gb 1e300 --max-steps 1e300 -o " + out, scratch, "timeout 60");
  EXPECT_EQ(hang.exit_code, 2) << hang.output;
  EXPECT_TRUE(contains(hang.output, "hang.toml:5: [model] drive_frequency_hz = 1e+300 Hz")) << hang.output;
  // Within that precision, the events of 2e8 periods do not fit in memory ...
  expect_refused(run_cli("run " + scratch.write("grow.toml", model1("1e12")) + " -o " + out, scratch, "timeout 60"),
                 scratch, {"grow.toml", "stick/slip events", "GB of memory", "--max-memory-gb"});
  // ... and over 100 x longer, with memory to spare, the scan's steps would take days.
  std::string slow = model1("1e12");
  slow.replace(slow.find("200e-6"), 6, "2e-2");
  expect_refused(run_cli("run " + scratch.write("slow.toml", slow) + " --max-memory-gb 1e300 -o " + out, scratch,
                         "timeout 60"),
                 scratch, {"slow.toml", "slip-end scan", "--max-steps"});
}

TEST(WorkLimits, TooManySamplesAreRefusedNamingThem) {
  ScratchDir scratch("limit-samples");
  std::string text = model1("1e4");
  text.replace(text.find("100e6"), 5, "1e15");
  expect_refused(run_cli("run " + scratch.write("rate.toml", text) + " -o " + scratch.file("out.h5"), scratch, "timeout 60"),
                 scratch, {"rate.toml", "samples", "GB of memory"});
}

//! A long run's traces are what fills memory (issue 26): every trace of 50 excited asperities
//! over 10 ms at 100 MHz (~6 GB) is refused within 2 GB before anything runs, naming
//! [output] traces, its size and how to leave it out; without traces the run fits (the
//! dense motions are dropped one by one once summed).
TEST(WorkLimits, OversizedTracesAreRefusedNamingOutputTraces) {
  ScratchDir scratch("limit-traces");
  const std::string text = "duration_s = 10e-3\nsample_rate_hz = 100e6\n[model]\nkind = \"model2\"\n"
                           "belt_velocity_m_per_s = 5\n[counterface]\nfriction_modulation_rms = 0.01\n"
                           "correlation_length_m = 0.5e-6\n[surface]\n[surface.defaults]\nlength_m = 50e-6\n"
                           "[[surface.asperity]]\nstiffness_n_per_m = 100\ncount = 50\n";
  const std::string study = scratch.write("traces.toml", text);
  const auto refused = run_cli("run " + study + " --max-memory-gb 2 -o " + scratch.file("out.h5"), scratch, "timeout 60");
  expect_refused(refused, scratch,
                 {"traces.toml", "[output] traces = [\"x\", \"v\", \"friction\", \"current\", \"charge\"]",
                  "50 asperities x 1e+06 samples", "GB of memory", "traces = [] keeps V and Q only", "--max-memory-gb"});
  const double bare = estimate_run(parse_study(text + "[output]\ntraces = []\n", study)).memory_bytes;
  EXPECT_LT(bare, 2e9);  // measured: ~0.7 GB peak (bench/bench_long_run.cpp)
}

//! Each command takes --max-memory-gb and --max-steps, and applies them.
TEST(WorkLimits, EveryCommandAppliesTheLimitsItIsGiven) {
  ScratchDir scratch("limit-commands");
  const std::string study = scratch.write("run.toml", model1("1e4"));
  std::ostringstream csv, voltage;
  csv << "t,x1\n";
  voltage << "t,V\n";
  for (int j = 0; j < 100; ++j) {
    csv << j * 1e-8 << "," << 1e-7 * std::sin(0.3 * j) << "\n";
    voltage << j * 1e-8 << "," << std::sin(0.3 * j) << "\n";
  }
  const std::string out = " -o " + scratch.file("out.h5");
  const std::string surface = std::string(STENGMC_SOURCE_DIR) + "/surfaces/pet_on_steel_gw.toml";
  for (const std::string& command :
       {"run " + study, "circuit " + scratch.write("x.csv", csv.str()) + " -R 1e6", "spectrum " + scratch.write("v.csv", voltage.str()),
        "surface " + surface + " -k 5"}) {
    SCOPED_TRACE(command);
    const auto fits = run_cli(command + out, scratch);
    ASSERT_EQ(fits.exit_code, 0) << fits.output;
    std::filesystem::remove(scratch.file("out.h5"));
    expect_refused(run_cli(command + " --max-memory-gb 0.001" + out, scratch), scratch, {"--max-memory-gb"});
    expect_refused(run_cli(command + " --max-steps 10" + out, scratch), scratch, {"--max-steps"});
  }
}

//! `surface --realisations` took 1e8 x 400 summits as far as memory would go.
TEST(WorkLimits, SurfaceRealisationsBeyondMemoryAreRefused) {
  ScratchDir scratch("limit-surface");
  const std::string surface = std::string(STENGMC_SOURCE_DIR) + "/surfaces/pet_on_steel_gw.toml";
  expect_refused(run_cli("surface " + surface + " -k 100000000 -o " + scratch.file("out.h5"), scratch, "timeout 60"),
                 scratch, {"realisations", "summits", "GB of memory"});
}

std::string ensemble(const std::string& top, const std::string& extra, const std::string& surface = "lognormal_count") {
  return top + "[model]\nkind = \"model2\"\nbelt_velocity_m_per_s = 10\n[surface]\nfile = \"" + std::string(STENGMC_SOURCE_DIR) +
         "/surfaces/" + surface + ".toml\"\n[ensemble]\nrealisations = 4\n" + extra;
}

//! An ensemble of 1 s runs reached 6.9 GB and died of bad_alloc; a swept sample_rate_hz =
//! 1e15 asked for 400 GB. What even one asperity cannot do is refused before anything
//! runs, naming the grid point.
TEST(WorkLimits, AnEnsembleRefusesUpFrontWhatNoRealisationCouldDo) {
  ScratchDir scratch("limit-ensemble");
  const std::string out = " -o " + scratch.file("out.h5");
  expect_refused(run_cli("run " + scratch.write("long.toml", ensemble("duration_s = 1\nsample_rate_hz = 100e6\n", "")) + out,
                         scratch, "timeout 60"),
                 scratch, {"long.toml", "samples"});
  const std::string sweep = "[[ensemble.sweep]]\nparameter = \"sample_rate_hz\"\nvalues = [100e6, 1e15]\n";
  expect_refused(run_cli("run " + scratch.write("sweep.toml", ensemble("duration_s = 4e-6\nsample_rate_hz = 100e6\n", sweep)) +
                             out, scratch, "timeout 60"),
                 scratch, {"grid point 2 of 2", "sample_rate_hz = 1e+15", "samples"});
  EXPECT_FALSE(std::filesystem::exists(scratch.file("out.h5.point0.journal")));  // nothing ran
}

//! A realisation that would exceed the limit (it drew more asperities) is an invalid
//! realisation with the reason; the others run. The limit is set between the estimates of
//! two realisations, so realisation r must be valid exactly when its own estimate is below.
TEST(WorkLimits, AnEnsembleMarksARealisationOverTheLimitInvalid) {
  ScratchDir scratch("limit-realisation");
  const std::string surface = scratch.write(
      "poisson.toml", "kind = \"random\"\nnominal_area_m2 = 1e-6\n[summits]\ncount_rule = \"poisson\"\ndensity_per_m2 = 2.5e6\n"
                      "[heights]\nkind = \"fixed\"\nvalues = [110e-6]\n[stiffness]\nkind = \"uniform\"\nmin = 50\nmax = 150\n"
                      "[load]\nrule = \"fixed\"\nnormal_load_n = 1e-3\n[element]\nlength_m = 50e-6\n");
  const std::string text = "seed = 2\nduration_s = 200e-6\nsample_rate_hz = 50e6\n[model]\nkind = \"model2\"\n"
                           "belt_velocity_m_per_s = 10\n[surface]\nfile = \"" + surface + "\"\n[ensemble]\nrealisations = 12\n";
  const std::string study = scratch.write("ensemble.toml", text);
  // Each realisation's own estimate, with the asperities it draws (none: no contact).
  std::vector<double> estimates;
  for (std::uint64_t r = 0; r < 12; ++r) {
    try {
      estimates.push_back(estimate_run(read_study(study, r), -1.0, false).memory_bytes);
    } catch (const ModelError&) {
      estimates.push_back(-1.0);
    }
  }
  std::vector<double> sorted;
  for (double e : estimates)
    if (e > 0.0) sorted.push_back(e);
  std::sort(sorted.begin(), sorted.end());
  sorted.erase(std::unique(sorted.begin(), sorted.end()), sorted.end());
  ASSERT_GE(sorted.size(), 2u) << "the realisations should differ in asperity count";
  const double limit = 0.5 * (sorted[sorted.size() / 2 - 1] + sorted[sorted.size() / 2]);

  const std::string out = scratch.file("out.h5");
  const auto r = run_cli("run " + study + " --max-memory-gb " + format_number(limit / 1e9) + " -o " + out, scratch);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto valid = Hdf5Reader(out).vector("/realisations/valid");
  ASSERT_EQ(valid.size(), 12u);
  std::size_t over = 0;
  for (std::size_t k = 0; k < valid.size(); ++k) {
    if (estimates[k] < 0.0) continue;  // no contact: invalid for that reason
    EXPECT_EQ(valid[k], estimates[k] <= limit ? 1.0 : 0.0) << "realisation " << k;
    if (estimates[k] > limit) {
      ++over;
      EXPECT_TRUE(contains(r.output, "realisation " + std::to_string(k) + ": work limit: with ")) << r.output;
    }
  }
  EXPECT_GT(over, 0u);
}

}  // namespace
}  // namespace stengmc
