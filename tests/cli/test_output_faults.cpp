// Faults around output files, through the real command line (docs/faults.md, "Rejected inputs and
// faults"):
//  - a full disk: every command that writes a file (HDF5, or export-netlist's netlist) is run
//    with its output on a disk that is already full and on one that fills while the file is
//    written; each must exit 1 with a message naming the output file and the system's "No
//    space left on device", leave nothing in the output folder (no temporary, no partial
//    file) and leave its inputs untouched. An ensemble must keep its journal whole, so that
//    the next run, with space again, resumes it to the datasets of an uninterrupted run;
//  - an output that is one of the command's inputs (also through a link), or not a regular
//    file (a device, a FIFO, a folder): refused with exit 2 before anything runs, the input
//    byte for byte as it was;
//  - a kill while the output is written: SIGTERM removes the temporary file; after SIGKILL
//    (which nothing can catch) the next run of the same output removes it; temporaries of
//    live processes and of other hosts are never touched.
//
// The faults are tests/support/fault_shim.c, loaded with LD_PRELOAD: writes to files under
// <scratch>/disk/ fail with ENOSPC once a byte budget is spent, as on a real full
// filesystem (short write, then ENOSPC), or stall so the test can kill the process there.
// scripts/fault_table.sh repeats the full disk on a real tmpfs where it may mount one.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>
#include <vector>

#include "core/hdf5_file.hpp"
#include "support/cli_runner.hpp"
#include "support/test_surfaces.hpp"

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

//! The environment that loads the fault shim for files under `folder`.
std::string faults(const std::string& folder) {
  // ASan (the sanitizer build) wants to be first in the library list; the shim is only an
  // interposer, so the order does not matter to it.
  return "LD_PRELOAD=" + std::string(STENGMC_FAULT_SHIM) + " STENGMC_FAULT_PATH_CONTAINS=" + folder +
         "/ ASAN_OPTIONS=verify_asan_link_order=0:detect_leaks=0";
}

//! ... whose writes under `folder` see a disk with `free_bytes` left.
std::string full_disk(const std::string& folder, long long free_bytes, const std::string& exempt = "") {
  return faults(folder) + " STENGMC_FAULT_FREE_BYTES=" + std::to_string(free_bytes) +
         (exempt.empty() ? "" : " STENGMC_FAULT_EXEMPT_CONTAINS=" + exempt);
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
  std::string extension = ".h5";
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
          {"surface", "surface " + surface + " -k 20 -o OUT"},
          // Its netlist (~290 kB) was written through an ofstream, which keeps no reason.
          {"export-netlist", "export-netlist " + study + " -o OUT", ".cir"}};
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
      const std::string out = disk + "/" + command.name + command.extension;
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
      EXPECT_EQ(files_in(disk), std::vector<std::string>{command.name + command.extension});
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

//! plot's figures on a full disk: it said "cannot be plotted ... (a damaged or partial
//! file?)" with exit 2, as if the input were bad, and left a partial (or empty) PNG that
//! looks like a figure. Now the figure is written whole or not at all (the scripts write a
//! temporary and rename it), and a failed write is exit 1 with the system's reason.
TEST(FullDisk, PlotLeavesNoPartialFigureAndSaysWhy) {
  ScratchDir scratch("full-disk-plot");
  const std::string disk = scratch.file("disk");
  std::filesystem::create_directories(disk);
  const std::string run = disk + "/r.h5";
  ASSERT_EQ(run_cli("run " + scratch.write("run.toml", RUN_STUDY) + " -o " + run, scratch).exit_code, 0);
  for (const long long free_bytes : {0LL, 20000LL}) {
    SCOPED_TRACE(std::to_string(free_bytes) + " bytes free");
    const auto result = run_cli("plot " + run, scratch, full_disk(disk, free_bytes));
    EXPECT_EQ(result.exit_code, 1) << result.output;
    EXPECT_TRUE(contains(result.output, disk + "/r.png: cannot write the figure: " + std::strerror(ENOSPC))) << result.output;
    EXPECT_EQ(files_in(disk), std::vector<std::string>{"r.h5"});
  }
}

// ---------------------------------------------------------------- output = input

struct Refusal {
  std::string arguments;  //!< the command line
  std::string input;      //!< the input it would have destroyed
};

//! Every command, with its output on each of its inputs: refused before anything runs,
//! the input unchanged.
TEST(OutputPath, AnOutputThatIsAnInputIsRefusedAndTheInputKept) {
  ScratchDir scratch("output-is-input");
  const std::string surface = scratch.write("surface.toml", testing::HISTOGRAM_SURFACE);
  const std::string histogram = scratch.write("h.csv", "100e-6,120e-6,1\n");
  const std::string study = scratch.write("study.toml", std::string(RUN_STUDY).substr(0, std::string(RUN_STUDY).find("[surface]")) +
                                                            "[surface]\nfile = \"surface.toml\"\n");
  const std::string ensemble = scratch.write("ensemble.toml", "duration_s = 2e-6\nsample_rate_hz = 50e6\n[model]\nkind = \"model1\"\n"
                                                              "[surface]\nfile = \"surface.toml\"\n[ensemble]\nrealisations = 2\n");
  const std::string own_output =
      scratch.write("own.toml", std::string(RUN_STUDY) + "[output]\nfile = \"" + scratch.file("own.toml") + "\"\n");
  const std::string csv = scratch.write("x.csv", displacement_csv());
  const std::string voltage = scratch.write("v.csv", voltage_csv());
  std::filesystem::create_symlink(study, scratch.file("link.h5"));
  const std::vector<Refusal> cases = {
      {"run " + study + " -o " + study, study},
      {"run " + study + " -o " + scratch.file("link.h5"), study},  // a link to the study
      {"run " + study + " -o " + surface, surface},
      {"run " + study + " -o " + histogram, histogram},
      {"run " + own_output, own_output},  // [output] file = the study itself
      {"run " + ensemble + " -o " + ensemble, ensemble},
      {"run " + ensemble + " -o " + surface, surface},
      {"surface " + surface + " -k 2 -o " + surface, surface},
      {"surface " + surface + " -k 2 -o " + histogram, histogram},
      {"surface " + surface + " -k 2 --study " + study + " -o " + study, study},
      {"circuit " + csv + " -R 1e6 -o " + csv, csv},
      {"spectrum " + voltage + " -o " + voltage, voltage},
      {"spectrum " + voltage + " --settings " + own_output + " -o " + own_output, own_output},
  };
  for (const Refusal& c : cases) {
    SCOPED_TRACE(c.arguments);
    const std::string before = read_bytes(c.input);
    const auto result = run_cli(c.arguments, scratch);
    EXPECT_EQ(result.exit_code, 2) << result.output;
    EXPECT_TRUE(contains(result.output, "is the input file " + c.input)) << result.output;
    EXPECT_TRUE(read_bytes(c.input) == before) << c.input << " was changed";
    for (const std::string& name : files_in(scratch.file(""))) EXPECT_FALSE(contains(name, ".tmp")) << name;
  }
}

//! A device (as root, `-o /dev/null` was once renamed over the device node), a FIFO
//! (writing would block), a folder: refused, and left what they were. The device is a copy
//! of /dev/null's node made in the scratch folder (root only), so that a regression can
//! only ever replace the copy, never the machine's /dev/null.
TEST(OutputPath, AnOutputThatIsNotARegularFileIsRefused) {
  ScratchDir scratch("output-not-regular");
  const std::string study = scratch.write("study.toml", RUN_STUDY);
  std::vector<std::pair<std::string, std::string>> outputs;
  const std::string device = scratch.file("null.h5");
  if (::mknod(device.c_str(), S_IFCHR | 0666, makedev(1, 3)) == 0) outputs.push_back({device, "a character device"});
  const std::string fifo = scratch.file("fifo.h5");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0666), 0);
  outputs.push_back({fifo, "a FIFO"});
  std::filesystem::create_directories(scratch.file("folder.h5"));
  outputs.push_back({scratch.file("folder.h5"), "a folder"});
  for (const auto& [out, kind] : outputs) {
    SCOPED_TRACE(out);
    const auto result = run_cli("run " + study + " -o " + out, scratch);
    EXPECT_EQ(result.exit_code, 2) << result.output;
    EXPECT_TRUE(contains(result.output, out + " exists and is " + kind)) << result.output;
  }
  if (outputs.size() == 3) {
    EXPECT_TRUE(std::filesystem::is_character_file(device));
  }
  EXPECT_TRUE(std::filesystem::is_fifo(fifo));
  EXPECT_TRUE(std::filesystem::is_directory(scratch.file("folder.h5")));
}

//! `plot` writes <stem>.png (and <stem>_spectrum.png) beside the file: it wrote a PNG into a
//! character device there, blamed a FIFO r.png on r.h5, and would write the figure over the
//! very file plotted when that file's name ends in .png. Its figures get the output checks.
TEST(OutputPath, PlotRefusesAFigurePathThatIsNotARegularFileOrTheFilePlotted) {
  ScratchDir scratch("plot-figure-path");
  const std::string study = scratch.write("study.toml", RUN_STUDY);
  const std::string run = scratch.file("r.h5");
  ASSERT_EQ(run_cli("run " + study + " -o " + run, scratch).exit_code, 0);
  std::vector<std::pair<std::string, std::string>> figures;
  const std::string device = scratch.file("r.png");
  if (::mknod(device.c_str(), S_IFCHR | 0666, makedev(1, 3)) == 0) figures.push_back({device, "a character device"});
  const std::string fifo = scratch.file("r_spectrum.png");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0666), 0);
  figures.push_back({fifo, "a FIFO"});
  for (const auto& [figure, kind] : figures) {
    SCOPED_TRACE(figure);
    const auto result = run_cli("plot " + run, scratch, "timeout 60");
    EXPECT_EQ(result.exit_code, 2) << result.output;
    EXPECT_TRUE(contains(result.output, "the figure " + figure + " exists and is " + kind)) << result.output;
    EXPECT_FALSE(contains(result.output, run + ": cannot be plotted")) << result.output;
    EXPECT_TRUE(kind == "a FIFO" ? std::filesystem::is_fifo(figure) : std::filesystem::is_character_file(figure));
    std::filesystem::remove(figure);  // the next case's figure is the one still in the way
  }
  // A run file named like its own figure.
  const std::string named_png = scratch.file("f.png");
  std::filesystem::copy_file(run, named_png);
  const std::string before = read_bytes(named_png);
  const auto onto = run_cli("plot " + named_png, scratch, "timeout 60");
  EXPECT_EQ(onto.exit_code, 2) << onto.output;
  EXPECT_TRUE(contains(onto.output, "the figure " + named_png + " is the input file " + named_png)) << onto.output;
  EXPECT_TRUE(read_bytes(named_png) == before) << "the file plotted was overwritten";
}

// ---------------------------------------------------------------- kills and stale temporaries

//! Starts `stengmc arguments` with the fault shim stalling its first write to `folder`;
//! returns its pid once it stalls there (the marker file appears).
pid_t start_stalled(const std::string& arguments, const std::string& folder, const ScratchDir& scratch) {
  const std::string marker = scratch.file("stalled");
  std::filesystem::remove(marker);
  const pid_t pid = ::fork();
  if (pid == 0) {
    const std::string command = "exec env " + faults(folder) + " STENGMC_FAULT_STALL_MARKER=" + marker + " " +
                                std::string(STENGMC_BINARY) + " " + arguments + " > " + scratch.file("stalled.log") +
                                " 2>&1";
    ::execl("/bin/sh", "sh", "-c", command.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  for (int i = 0; i < 600 && !std::filesystem::exists(marker); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  EXPECT_TRUE(std::filesystem::exists(marker)) << "the command never wrote its output";
  return pid;
}

//! Every temporary of `out` in its folder.
std::vector<std::string> temporaries_of(const std::string& folder) {
  std::vector<std::string> found;
  for (const std::string& name : files_in(folder))
    if (name.size() > 4 && name.compare(name.size() - 4, 4, ".tmp") == 0) found.push_back(name);
  return found;
}

TEST(Temporaries, SigtermWhileWritingRemovesTheTemporaryFile) {
  ScratchDir scratch("kill-term");
  const std::string disk = scratch.file("disk");
  std::filesystem::create_directories(disk);
  const std::string study = scratch.write("run.toml", RUN_STUDY);
  const pid_t pid = start_stalled("run " + study + " -o " + disk + "/out.h5", disk, scratch);
  ASSERT_EQ(temporaries_of(disk).size(), 1u);  // caught while writing it
  ::kill(pid, SIGTERM);
  int status = 0;
  ::waitpid(pid, &status, 0);
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGTERM) << status;  // dies of the signal, as before
  EXPECT_TRUE(files_in(disk).empty()) << "left behind: " << files_in(disk).front();
}

TEST(Temporaries, AfterSigkillTheNextRunRemovesTheStaleTemporary) {
  ScratchDir scratch("kill-9");
  const std::string disk = scratch.file("disk");
  std::filesystem::create_directories(disk);
  const std::string study = scratch.write("run.toml", RUN_STUDY);
  const std::string out = disk + "/out.h5";
  const pid_t pid = start_stalled("run " + study + " -o " + out, disk, scratch);
  ::kill(pid, SIGKILL);
  ::waitpid(pid, nullptr, 0);
  const auto stale = temporaries_of(disk);
  ASSERT_EQ(stale.size(), 1u);  // nothing can catch SIGKILL
  EXPECT_FALSE(std::filesystem::exists(out));

  // Temporaries that are not stale: one of a live process (this test), one of another host.
  char host[256] = {};
  ::gethostname(host, sizeof host - 1);
  const std::string live = out + "." + host + "." + std::to_string(::getpid()) + ".tmp";
  const std::string other_host = out + ".another-host." + std::to_string(pid) + ".tmp";
  std::ofstream(live) << "a run in progress";
  std::ofstream(other_host) << "a run on another machine";

  const auto again = run_cli("run " + study + " -o " + out, scratch);
  ASSERT_EQ(again.exit_code, 0) << again.output;
  EXPECT_FALSE(std::filesystem::exists(disk + "/" + stale.front()));
  EXPECT_TRUE(std::filesystem::exists(live));
  EXPECT_TRUE(std::filesystem::exists(other_host));
  EXPECT_TRUE(std::filesystem::exists(out));
}

}  // namespace
}  // namespace stengmc
