// Ensembles over MPI ranks (docs/ensembles.md; docs/cluster.md): `mpirun -np P stengmc run`
// writes the file a single process writes, by golden_digest.py's comparison (every dataset
// and attribute but the creation time), for P = 1, 2, 3 (3 oversubscribes this 2-core
// machine) and 1 or 2 threads per rank, for an ensemble and a sweep; a job SIGKILLed
// mid-way resumes, with another number of ranks, to that same file; a calibration bank
// on 2 and 3 ranks is the one-process bank but for its timings. Every launch here opens
// the MPI module beside the binary (ensemble/mpi_module.cpp); a binary whose module is
// missing or broken says which path it tried. Built only with MPI.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <fstream>
#include <sstream>
#include <filesystem>
#include <thread>
#include <vector>

#include "support/cli_runner.hpp"
#include "support/distributed_runs.hpp"
#include "support/inverse_device.hpp"

extern char** environ;

namespace stengmc {
namespace {

using testing::distributed_study;
using testing::file_differences;
using testing::run_cli;
using testing::ScratchDir;

//! mpirun's arguments: root is allowed (CI containers), more ranks than cores are allowed,
//! and ranks are not pinned (pinned, 2 threads of a rank would share one core).
std::vector<std::string> mpirun(int ranks) {
  return {STENGMC_MPIEXEC, "--allow-run-as-root", "--oversubscribe", "--bind-to", "none", "-np", std::to_string(ranks)};
}

std::string mpirun_line(int ranks) {
  std::string line;
  for (const std::string& a : mpirun(ranks)) line += a + " ";
  return line;
}

//! `mpirun -np ranks stengmc arguments`, with output captured.
testing::CliResult run_mpi(int ranks, const std::string& arguments, const ScratchDir& scratch) {
  return testing::run_command(mpirun_line(ranks) + STENGMC_BINARY + " " + arguments, scratch);
}

void expect_every_layout_equals_one_process(const std::string& text, const std::string& name) {
  ScratchDir scratch("mpi-" + name);
  const std::string study = scratch.write("study.toml", text);
  const std::string reference = scratch.file("one_process.h5");
  const auto single = run_cli("run " + study + " -j 1 -o " + reference, scratch);
  ASSERT_EQ(single.exit_code, 0) << single.output;
  for (int ranks : {1, 2, 3})
    for (int threads : {1, 2}) {
      const std::string out = scratch.file(std::string("p") + std::to_string(ranks) + "t" + std::to_string(threads) + ".h5");
      const auto run = run_mpi(ranks, "run " + study + " -j " + std::to_string(threads) + " -o " + out, scratch);
      ASSERT_EQ(run.exit_code, 0) << ranks << " ranks x " << threads << " threads: " << run.output;
      EXPECT_EQ(file_differences(reference, out, scratch), "") << ranks << " ranks x " << threads << " threads";
      EXPECT_FALSE(std::filesystem::exists(out + ".journal"));
    }
}

TEST(Mpi, AnEnsembleIsTheOneProcessFileForOneTwoAndThreeRanksOfOneAndTwoThreads) {
  expect_every_layout_equals_one_process(distributed_study(13), "ensemble");
}

TEST(Mpi, ASweepIsTheOneProcessFileForOneTwoAndThreeRanksOfOneAndTwoThreads) {
  expect_every_layout_equals_one_process(distributed_study(7, testing::TWO_POINT_SWEEP), "sweep");
}

//! The processes descended from `root` (mpirun's ranks, whatever process group they put
//! themselves in), from /proc.
std::vector<pid_t> descendants(pid_t root) {
  std::vector<std::pair<pid_t, pid_t>> parent_of;  // (pid, ppid)
  for (const auto& entry : std::filesystem::directory_iterator("/proc")) {
    const std::string name = entry.path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::ifstream stat(entry.path() / "stat");
    std::string line;
    if (!std::getline(stat, line)) continue;
    const auto close = line.rfind(')');  // the command name may hold spaces
    if (close == std::string::npos) continue;
    std::istringstream rest(line.substr(close + 2));
    char state = 0;
    pid_t ppid = 0;
    rest >> state >> ppid;
    parent_of.emplace_back(static_cast<pid_t>(std::stol(name)), ppid);
  }
  std::vector<pid_t> found{root};
  for (std::size_t i = 0; i < found.size(); ++i)
    for (const auto& [pid, ppid] : parent_of)
      if (ppid == found[i]) found.push_back(pid);
  found.erase(found.begin());
  return found;
}

//! Starts `mpirun -np ranks stengmc run study -o out` in its own process group, waits until
//! its journal holds more than `bytes`, SIGKILLs mpirun and every process it started (as a
//! batch system ends a job) and says whether the job was still running then.
bool kill_mid_way(int ranks, const std::string& study, const std::string& out, std::uintmax_t bytes,
                  const ScratchDir& scratch) {
  std::vector<std::string> args = mpirun(ranks);
  for (const std::string& a : {std::string(STENGMC_BINARY), std::string("run"), study, std::string("-j"), std::string("1"),
                               std::string("-o"), out})
    args.push_back(a);
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETPGROUP);
  posix_spawnattr_setpgroup(&attributes, 0);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, scratch.file("killed.log").c_str(), O_WRONLY | O_CREAT, 0644);
  posix_spawn_file_actions_addopen(&actions, 2, scratch.file("killed.err").c_str(), O_WRONLY | O_CREAT, 0644);
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, args[0].c_str(), &actions, &attributes, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attributes);
  if (spawned != 0) return false;
  const std::string journal = out + ".journal";
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  std::error_code ec;
  while (std::chrono::steady_clock::now() < deadline &&
         !(std::filesystem::exists(journal) && std::filesystem::file_size(journal, ec) > bytes))
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  const std::vector<pid_t> ranks_and_helpers = descendants(pid);
  kill(-pid, SIGKILL);
  for (pid_t p : ranks_and_helpers) kill(p, SIGKILL);
  int status = 0;
  waitpid(pid, &status, 0);
  // Wait until the ranks are gone (or zombies: their files, and the journal's lock, are
  // released by then).
  const auto alive = [](pid_t p) {
    std::ifstream stat("/proc/" + std::to_string(p) + "/stat");
    std::string line;
    if (!std::getline(stat, line)) return false;
    const auto close = line.rfind(')');
    return close != std::string::npos && close + 2 < line.size() && line[close + 2] != 'Z';
  };
  for (pid_t p : ranks_and_helpers)
    for (int i = 0; i < 500 && alive(p); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  return WIFSIGNALED(status);
}

TEST(Mpi, AJobKilledMidWayResumesWithAnotherNumberOfRanksToTheOneProcessFile) {
  ScratchDir scratch("mpi-resume");
  // ~0.1 s per realisation (the shipped GW surface, ~24 asperities, 50 us): long enough to
  // be killed after a few records, well before the last.
  const std::string study = scratch.write(
      "study.toml", "seed = 3\nduration_s = 50e-6\nsample_rate_hz = 100e6\n"
                    "[model]\nkind = \"model2\"\nbelt_velocity_m_per_s = 10\n"
                    "[surface]\nfile = \"" + std::string(STENGMC_SOURCE_DIR) + "/surfaces/pet_on_steel_gw.toml\"\n"
                    "[domain]\npolicy = \"flag\"\n"
                    "[spectrum]\nwindow = \"hann\"\nstart_s = 5e-6\nprominence_over_floor = 10\n"
                    "min_frequency_hz = 100e3\nhigh_resolution = false\n"
                    "[ensemble]\nrealisations = 36\ntrace_realisations = []\n");
  const std::string reference = scratch.file("one_process.h5");
  const auto single = run_cli("run " + study + " -j 2 -o " + reference, scratch);
  ASSERT_EQ(single.exit_code, 0) << single.output;
  for (const auto& [killed_ranks, resumed_ranks] : {std::pair{2, 3}, std::pair{3, 2}}) {
    const std::string out = scratch.file("killed_at_" + std::to_string(killed_ranks) + ".h5");
    // A record of ~24 asperities is ~2.5 kB: wait for several.
    ASSERT_TRUE(kill_mid_way(killed_ranks, study, out, 15'000, scratch))
        << "the job finished before it could be killed; make it longer";
    ASSERT_FALSE(std::filesystem::exists(out)) << "a killed job left an output file";
    ASSERT_TRUE(std::filesystem::exists(out + ".journal"));
    const auto resumed = run_mpi(resumed_ranks, "run " + study + " -j 1 -o " + out, scratch);
    ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
    EXPECT_NE(resumed.output.find("resumed from an interrupted run"), std::string::npos) << resumed.output;
    EXPECT_EQ(file_differences(reference, out, scratch), "") << killed_ranks << " ranks killed, " << resumed_ranks
                                                            << " resumed";
  }
}

TEST(Mpi, ACalibrationBankIsTheOneProcessBankOnTwoAndThreeRanks) {
  // The small known device of test_invert_command (50 records of 20 us, 1-3 asperities):
  // every dataset and attribute of the bank but the wall and CPU times it records.
  ScratchDir scratch("mpi-calibrate");
  const std::string device = scratch.write("device.toml", testing::known_device_study("20e-6", testing::quick_prior()));
  const std::string reference = scratch.file("one_process.h5");
  const auto single = run_cli("calibrate " + device + " -j 1 -o " + reference, scratch);
  ASSERT_EQ(single.exit_code, 0) << single.output;
  for (int ranks : {2, 3}) {
    const std::string out = scratch.file("bank_p" + std::to_string(ranks) + ".h5");
    const auto bank = run_mpi(ranks, "calibrate " + device + " -j 1 -o " + out, scratch);
    ASSERT_EQ(bank.exit_code, 0) << ranks << " ranks: " << bank.output;
    // Timings: the estimator's time per record (and so its checksum), the bank's wall time
    // and thread count.
    const std::string differences = testing::file_differences(
        reference, out, scratch, {"/records/seconds", "/records/seconds@checksum_fnv1a64", "/@seconds", "/@threads"});
    EXPECT_EQ(differences, "") << ranks << " ranks";
  }
}

TEST(Mpi, OnlyEnsembleRunsAreDistributedAndBadInputEndsEveryRankWithExitTwo) {
  ScratchDir scratch("mpi-refused");
  const std::string study = scratch.write("study.toml", distributed_study(4));
  // Another command would run once per rank over one output.
  const auto surface = run_mpi(2, "surface " + std::string(STENGMC_SOURCE_DIR) + "/surfaces/lognormal_count.toml -o " +
                                      scratch.file("s.h5"), scratch);
  EXPECT_EQ(surface.exit_code, 2) << surface.output;
  EXPECT_NE(surface.output.find("only `stengmc run` of an [ensemble] study and `stengmc calibrate`"), std::string::npos)
      << surface.output;
  EXPECT_FALSE(std::filesystem::exists(scratch.file("s.h5")));
  // Shards and ranks are two ways of splitting one run.
  const auto shard = run_mpi(2, "run " + study + " --shard 0/2 -o " + scratch.file("x.shard"), scratch);
  EXPECT_EQ(shard.exit_code, 2) << shard.output;
  EXPECT_NE(shard.output.find("--shard 0/2"), std::string::npos) << shard.output;
  // A study error on every rank: one message, exit 2, no hang.
  const std::string broken = scratch.write("broken.toml", distributed_study(4) + "unknown_key = 1\n");
  const auto bad = run_mpi(3, "run " + broken + " -o " + scratch.file("b.h5"), scratch);
  EXPECT_EQ(bad.exit_code, 2) << bad.output;
  EXPECT_NE(bad.output.find("unknown_key"), std::string::npos) << bad.output;
}

TEST(Mpi, AMissingOrBrokenModuleIsAnErrorNamingItsPathAndTheModulePutThereRuns) {
  // A copy of the binary in a folder of its own: the module is looked for at the same path
  // relative to it as the build's module is to the build's binary (an install mirrors it).
  ScratchDir scratch("mpi-module");
  const std::filesystem::path binary = scratch.file("bin/stengmc");
  std::filesystem::create_directories(binary.parent_path());
  std::filesystem::copy_file(STENGMC_BINARY, binary);
  const std::filesystem::path built_module = STENGMC_MPI_MODULE;
  const std::filesystem::path expected =
      (binary.parent_path() / built_module.lexically_relative(std::filesystem::path(STENGMC_BINARY).parent_path()))
          .lexically_normal();
  const std::string study = scratch.write("study.toml", distributed_study(4));
  const std::string out = scratch.file("out.h5");
  const std::string launch = mpirun_line(2) + binary.string() + " run " + study + " -j 1 -o " + out;

  const auto missing = testing::run_command(launch, scratch);
  EXPECT_NE(missing.exit_code, 0) << missing.output;
  EXPECT_NE(missing.output.find("stengmc: error: an MPI launcher started stengmc, but its MPI module does not load: " +
                                expected.string() + ": cannot open shared object file"),
            std::string::npos)
      << missing.output;
  EXPECT_NE(missing.output.find("`cmake --install`"), std::string::npos) << missing.output;
  EXPECT_FALSE(std::filesystem::exists(out));

  // Not a shared object at that path: the loader's reason, same path. The launcher's
  // variable alone (no mpirun) is enough to make stengmc want the module.
  std::filesystem::create_directories(expected.parent_path());
  std::ofstream(expected) << "not an ELF file\n";
  const auto broken = testing::run_command("env OMPI_COMM_WORLD_SIZE=1 " + binary.string() + " --version", scratch);
  EXPECT_EQ(broken.exit_code, 1) << broken.output;
  EXPECT_NE(broken.output.find("its MPI module does not load: " + expected.string()), std::string::npos)
      << broken.output;

  // The module where it was looked for: the copy runs the ensemble, the one-process file.
  std::filesystem::copy_file(built_module, expected, std::filesystem::copy_options::overwrite_existing);
  const auto placed = testing::run_command(launch, scratch);
  ASSERT_EQ(placed.exit_code, 0) << placed.output;
  const std::string reference = scratch.file("one_process.h5");
  const auto single = run_cli("run " + study + " -j 1 -o " + reference, scratch);
  ASSERT_EQ(single.exit_code, 0) << single.output;
  EXPECT_EQ(file_differences(reference, out, scratch), "");
}

}  // namespace
}  // namespace stengmc
