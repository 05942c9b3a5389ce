// A full disk, through the real command line (README: "Rejected inputs and faults"). Every
// command that writes HDF5 is run with its output on a disk that is already full and on
// one that fills while the file is written; each must exit 1 with a message naming the
// output file and the system's "No space left on device", leave nothing in the output
// folder (no temporary, no partial file) and leave its inputs untouched. An ensemble must
// keep its journal whole, so that the next run, with space again, resumes it to the
// datasets of an uninterrupted run.
//
// The full disk is tests/support/full_disk_shim.c, loaded with LD_PRELOAD: writes to files
// under <scratch>/disk/ fail with ENOSPC once a byte budget is spent, as on a real full
// filesystem (short write, then ENOSPC). scripts/fault_table.sh repeats this on a real
// tmpfs where it may mount one.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "io/hdf5_file.hpp"
#include "support/cli_runner.hpp"

namespace stengmc {
namespace {

using testing::run_cli;
using testing::ScratchDir;

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

std::string read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

//! The environment of a process whose writes under `folder` see a disk with `free_bytes` left.
std::string full_disk(const std::string& folder, long long free_bytes, const std::string& exempt = "") {
  // ASan (the sanitizer build) wants to be first in the library list; the shim is only an
  // interposer, so the order does not matter to it.
  return "LD_PRELOAD=" + std::string(STENGMC_FULL_DISK_SHIM) + " STENGMC_FULL_DISK_PATH_CONTAINS=" + folder +
         "/ STENGMC_FULL_DISK_FREE_BYTES=" + std::to_string(free_bytes) +
         (exempt.empty() ? "" : " STENGMC_FULL_DISK_EXEMPT_CONTAINS=" + exempt) +
         " ASAN_OPTIONS=verify_asan_link_order=0:detect_leaks=0";
}

std::vector<std::string> files_in(const std::string& folder) {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) names.push_back(entry.path().filename().string());
  return names;
}

// A small Model 1 run (fast) whose run file is ~100 kB: enough to fill a disk mid-file.
const char* RUN_STUDY = R"(duration_s = 200e-6
sample_rate_hz = 20e6
[model]
kind = "model1"
[surface]
[[surface.asperity]]
stiffness_n_per_m = 155
[[surface.asperity]]
stiffness_n_per_m = 75
[spectrum]
high_resolution = false
)";

std::string displacement_csv() {
  std::ostringstream csv;
  csv << "t,x1,x2\n";
  for (int j = 0; j <= 2000; ++j) {
    const double t = j * 1e-8;
    csv << t << "," << 1e-6 * std::sin(2e6 * t) << "," << 2e-6 * std::sin(3e6 * t) << "\n";
  }
  return csv.str();
}

std::string voltage_csv() {
  std::ostringstream csv;
  csv << "t,V\n";
  csv.precision(17);
  for (int j = 0; j < 4096; ++j) csv << j * 1e-7 << "," << std::sin(2.0 * 3.141592653589793 * 1e5 * j * 1e-7) << "\n";
  return csv.str();
}

struct Command {
  std::string name;
  std::string arguments;  //!< with OUT standing for the output path
};

//! Inputs of every command, written into `scratch` (never onto the full disk).
std::vector<Command> commands(const ScratchDir& scratch) {
  const std::string study = scratch.write("run.toml", RUN_STUDY);
  const std::string csv = scratch.write("x.csv", displacement_csv());
  const std::string voltage = scratch.write("v.csv", voltage_csv());
  const std::string surface = std::string(STENGMC_SOURCE_DIR) + "/surfaces/pet_on_steel_gw.toml";
  return {{"run", "run " + study + " -o OUT"},
          {"circuit", "circuit " + csv + " -R 1e6 -o OUT"},
          {"spectrum", "spectrum " + voltage + " -o OUT"},
          {"surface", "surface " + surface + " -k 20 -o OUT"}};
}

std::string with_output(std::string arguments, const std::string& out) {
  arguments.replace(arguments.find("OUT"), 3, out);
  return arguments;
}

//! Each command with the disk full from the start (0 bytes) and filling part-way (4 kB
//! fits HDF5's superblock and some metadata, not the datasets).
TEST(FullDisk, EveryCommandFailsCleanlyNamingTheFileAndTheReason) {
  for (const long long free_bytes : {0LL, 4096LL}) {
    ScratchDir scratch("full-disk-" + std::to_string(free_bytes));
    const std::string disk = scratch.file("disk");
    std::filesystem::create_directories(disk);
    for (const Command& command : commands(scratch)) {
      SCOPED_TRACE(command.name + " with " + std::to_string(free_bytes) + " bytes free");
      const std::string out = disk + "/" + command.name + ".h5";
      const std::vector<std::string> inputs_before = files_in(scratch.file(""));
      const auto result = run_cli(with_output(command.arguments, out), scratch, full_disk(disk, free_bytes));
      EXPECT_EQ(result.exit_code, 1) << result.output;
      EXPECT_TRUE(contains(result.output, out)) << result.output;
      EXPECT_TRUE(contains(result.output, std::strerror(ENOSPC))) << result.output;
      EXPECT_FALSE(contains(result.output, "does the folder exist")) << result.output;
      EXPECT_TRUE(files_in(disk).empty()) << "left behind: " << files_in(disk).front();

      // With space again the same command succeeds: nothing stale is in the way.
      const auto again = run_cli(with_output(command.arguments, out), scratch);
      EXPECT_EQ(again.exit_code, 0) << again.output;
      EXPECT_EQ(files_in(disk), std::vector<std::string>{command.name + ".h5"});
      std::filesystem::remove(out);
    }
  }
}

std::string ensemble_study() {
  return "seed = 5\nduration_s = 20e-6\nsample_rate_hz = 50e6\n"
         "[model]\nkind = \"model2\"\nbelt_velocity_m_per_s = 10\n"
         "[surface]\nfile = \"" + std::string(STENGMC_SOURCE_DIR) + "/surfaces/lognormal_count.toml\"\n"
         "[ensemble]\nrealisations = 6\n";
}

//! The journal is the ensemble's only copy of its finished realisations: a disk that fills
//! while the output is written must leave it whole, and the next run resumes from it.
TEST(FullDisk, AnEnsembleKeepsItsJournalWholeAndResumesFromIt) {
  ScratchDir scratch("full-disk-ensemble");
  const std::string disk = scratch.file("disk");
  std::filesystem::create_directories(disk);
  const std::string study = scratch.write("ensemble.toml", ensemble_study());
  const std::string out = disk + "/ensemble.h5";

  // The output's temporary file is on a disk with 2 kB left; the journal has room.
  const auto failed = run_cli("run " + study + " -j 2 -o " + out, scratch, full_disk(disk, 2048, "journal"));
  EXPECT_EQ(failed.exit_code, 1) << failed.output;
  EXPECT_TRUE(contains(failed.output, out)) << failed.output;
  EXPECT_TRUE(contains(failed.output, std::strerror(ENOSPC))) << failed.output;
  EXPECT_EQ(files_in(disk), std::vector<std::string>{"ensemble.h5.journal"});
  const std::string journal = read_bytes(out + ".journal");

  const auto resumed = run_cli("run " + study + " -j 2 -o " + out, scratch);
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_TRUE(contains(resumed.output, "6 resumed")) << resumed.output;
  const std::string reference = scratch.file("reference.h5");
  ASSERT_EQ(run_cli("run " + study + " -j 1 -o " + reference, scratch).exit_code, 0);
  const Hdf5Reader a(out), b(reference);
  for (const char* name : {"/realisations/voltage_rms_v", "/realisations/final_charge_c", "/asperities/stiffness_n_per_m"})
    EXPECT_EQ(a.vector(name), b.vector(name)) << name;
  EXPECT_FALSE(journal.empty());
}

//! A disk already full when the ensemble starts: the journal cannot even be created.
TEST(FullDisk, AnEnsembleOnAFullDiskSaysSoAndLeavesNothing) {
  ScratchDir scratch("full-disk-ensemble-start");
  const std::string disk = scratch.file("disk");
  std::filesystem::create_directories(disk);
  const std::string study = scratch.write("ensemble.toml", ensemble_study());
  const std::string out = disk + "/ensemble.h5";
  const auto result = run_cli("run " + study + " -o " + out, scratch, full_disk(disk, 0));
  EXPECT_EQ(result.exit_code, 1) << result.output;
  EXPECT_TRUE(contains(result.output, out + ".journal")) << result.output;
  EXPECT_TRUE(contains(result.output, std::strerror(ENOSPC))) << result.output;
  EXPECT_TRUE(files_in(disk).empty()) << "left behind: " << files_in(disk).front();
}

}  // namespace
}  // namespace stengmc
