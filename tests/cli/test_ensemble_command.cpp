// Ensembles through the command line (docs/ensembles.md): the datasets are bitwise
// identical for 1 and 2 threads and when a realisation is re-run alone (--only), and a
// run killed with SIGKILL and resumed gives the datasets of an uninterrupted run.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <thread>
#include <vector>

#include "ensemble/journal.hpp"
#include "ensemble/realisation_record.hpp"
#include "core/hdf5_file.hpp"
#include "support/cli_runner.hpp"

extern char** environ;

namespace stengmc {
namespace {

using testing::run_cli;
using testing::ScratchDir;

// ~24 asperities of the shipped GW surface, Model 2 at v_b = 10 m/s, FFT spectra; about
// 0.1 s of CPU per realisation. One realisation in ~20 flags x = l: invalid records too.
std::string study_text(int realisations, const std::string& extra = "") {
  return "seed = 3\nduration_s = 50e-6\nsample_rate_hz = 100e6\n"
         "[model]\nkind = \"model2\"\nbelt_velocity_m_per_s = 10\n"
         "[surface]\nfile = \"" + std::string(STENGMC_SOURCE_DIR) + "/surfaces/pet_on_steel_gw.toml\"\n"
         "[domain]\npolicy = \"flag\"\n"
         "[spectrum]\nwindow = \"hann\"\nstart_s = 5e-6\nprominence_over_floor = 10\nmin_frequency_hz = 100e3\n"
         "high_resolution = false\n"
         "[ensemble]\nrealisations = " + std::to_string(realisations) + "\n" + extra;
}

//! Every per-realisation and per-asperity dataset, and the summary means, of a file.
std::vector<std::pair<std::string, std::vector<double>>> datasets(const std::string& path) {
  const Hdf5Reader f(path);
  std::vector<std::pair<std::string, std::vector<double>>> out;
  for (const char* name : {"/realisations/realisation", "/realisations/valid", "/realisations/asperity_offset"})
    out.emplace_back(name, f.vector(name));
  for (std::size_t k = 0; k < SCALAR_COUNT; ++k) {
    const std::string name(scalar_info(static_cast<Scalar>(k)).name);
    out.emplace_back("/realisations/" + name, f.vector("/realisations/" + name));
    for (const char* stat : {"mean", "mean_low", "mean_high", "std", "median_low", "p95_high"})
      out.emplace_back("/summary/" + name + "/" + stat, f.vector("/summary/" + name + "/" + stat));
  }
  for (std::size_t c = 0; c < ASPERITY_COLUMN_COUNT; ++c) {
    const std::string name(column_info(static_cast<AsperityColumn>(c)).name);
    out.emplace_back("/asperities/" + name, f.vector("/asperities/" + name));
  }
  return out;
}

void expect_bitwise_equal_files(const std::string& a, const std::string& b) {
  const auto x = datasets(a), y = datasets(b);
  ASSERT_EQ(x.size(), y.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    ASSERT_EQ(x[i].second.size(), y[i].second.size()) << x[i].first;
    EXPECT_EQ(std::memcmp(x[i].second.data(), y[i].second.data(), x[i].second.size() * sizeof(double)), 0) << x[i].first;
  }
}

TEST(EnsembleCommand, BitwiseIdenticalForOneAndTwoThreadsAndForARealisationAlone) {
  ScratchDir scratch("ensemble-threads");
  const std::string study = scratch.write("study.toml", study_text(8));
  const auto one = run_cli("run " + study + " -j 1 -o " + scratch.file("one.h5"), scratch);
  ASSERT_EQ(one.exit_code, 0) << one.output;
  const auto two = run_cli("run " + study + " -j 2 -o " + scratch.file("two.h5"), scratch);
  ASSERT_EQ(two.exit_code, 0) << two.output;
  expect_bitwise_equal_files(scratch.file("one.h5"), scratch.file("two.h5"));
  EXPECT_FALSE(std::filesystem::exists(scratch.file("two.h5.journal"))) << "the journal outlives a finished run";

  // Realisation 5 alone: its row and asperity slice equal the batch's.
  const auto alone = run_cli("run " + study + " --only 5 -o " + scratch.file("alone.h5"), scratch);
  ASSERT_EQ(alone.exit_code, 0) << alone.output;
  const Hdf5Reader batch(scratch.file("two.h5")), single(scratch.file("alone.h5"));
  EXPECT_EQ(single.vector("/realisations/realisation"), std::vector<double>{5.0});
  for (std::size_t k = 0; k < SCALAR_COUNT; ++k) {
    const std::string name = "/realisations/" + std::string(scalar_info(static_cast<Scalar>(k)).name);
    const double a = batch.vector(name)[5], b = single.vector(name)[0];
    EXPECT_EQ(std::memcmp(&a, &b, sizeof a), 0) << name;
  }
  const std::vector<double> offsets = batch.vector("/realisations/asperity_offset");
  for (std::size_t c = 0; c < ASPERITY_COLUMN_COUNT; ++c) {
    const std::string name = "/asperities/" + std::string(column_info(static_cast<AsperityColumn>(c)).name);
    const std::vector<double> all = batch.vector(name), mine = single.vector(name);
    const std::vector<double> slice(all.begin() + static_cast<long>(offsets[5]), all.begin() + static_cast<long>(offsets[6]));
    ASSERT_EQ(slice.size(), mine.size()) << name;
    EXPECT_EQ(std::memcmp(slice.data(), mine.data(), mine.size() * sizeof(double)), 0) << name;
  }
}

//! Starts `stengmc run study -j 2 -o out` (its stdout and stderr to out.log, out.err), waits
//! until several realisations are in its journal, sends `signal` and returns the wait status.
int run_until_journaled(const std::string& study, const std::string& out, int signal) {
  const std::string journal = out + ".journal";
  std::vector<std::string> args{STENGMC_BINARY, "run", study, "-j", "2", "-o", out};
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, (out + ".log").c_str(), O_WRONLY | O_CREAT, 0644);
  posix_spawn_file_actions_addopen(&actions, 2, (out + ".err").c_str(), O_WRONLY | O_CREAT, 0644);
  if (posix_spawn(&pid, STENGMC_BINARY, &actions, nullptr, argv.data(), environ) != 0) return -1;
  posix_spawn_file_actions_destroy(&actions);
  // A record of ~24 asperities is ~2.5 kB: wait for several, well before the 40th.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  std::error_code ec;
  while (std::chrono::steady_clock::now() < deadline &&
         !(std::filesystem::exists(journal) && std::filesystem::file_size(journal, ec) > 15'000))
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  kill(pid, signal);
  int status = 0;
  waitpid(pid, &status, 0);
  return status;
}

TEST(EnsembleCommand, KilledRunResumesToTheUninterruptedDatasets) {
  ScratchDir scratch("ensemble-resume");
  const std::string study = scratch.write("study.toml", study_text(40, "trace_realisations = []\n"));
  const auto whole = run_cli("run " + study + " -j 2 -o " + scratch.file("whole.h5"), scratch);
  ASSERT_EQ(whole.exit_code, 0) << whole.output;

  // Start the same run, let a few realisations reach the journal, then SIGKILL it.
  const std::string out = scratch.file("killed.h5"), journal = out + ".journal";
  const int status = run_until_journaled(study, out, SIGKILL);
  ASSERT_TRUE(WIFSIGNALED(status)) << "the run finished before it could be killed; make it longer";
  ASSERT_FALSE(std::filesystem::exists(out)) << "a killed run left an output file";
  ASSERT_TRUE(std::filesystem::exists(journal));

  const auto resumed = run_cli("run " + study + " -j 2 -o " + out, scratch);
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_NE(resumed.output.find("resumed from an interrupted run"), std::string::npos) << resumed.output;
  expect_bitwise_equal_files(scratch.file("whole.h5"), out);

}

//! Ctrl-C and a batch system's SIGTERM: the run dies of the signal (the shell's 130, 143),
//! says on its way out where the finished realisations are and how to resume, and the run
//! started again says how many it took from the journal.
TEST(EnsembleCommand, AnInterruptedRunSaysHowToResumeAndTheResumeSaysWhatItTook) {
  ScratchDir scratch("ensemble-interrupt");
  const std::string study = scratch.write("study.toml", study_text(40, "trace_realisations = []\n"));
  for (const int signal : {SIGINT, SIGTERM}) {
    const std::string out = scratch.file("interrupted" + std::to_string(signal) + ".h5");
    const int status = run_until_journaled(study, out, signal);
    ASSERT_TRUE(WIFSIGNALED(status)) << "the run finished before it could be interrupted; make it longer";
    EXPECT_EQ(WTERMSIG(status), signal);
    std::ifstream err(out + ".err");
    const std::string said((std::istreambuf_iterator<char>(err)), std::istreambuf_iterator<char>());
    EXPECT_NE(said.find("interrupted by SIG"), std::string::npos) << said;
    EXPECT_NE(said.find("kept in " + out + ".journal: the same command resumes"), std::string::npos) << said;
    ASSERT_FALSE(std::filesystem::exists(out));
    const auto resumed = run_cli("run " + study + " -j 2 -o " + out, scratch);
    ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
    EXPECT_NE(resumed.output.find("realisations taken from " + out + ".journal"), std::string::npos) << resumed.output;
  }
}

TEST(EnsembleCommand, AJournalOfAnotherStudyIsRefusedUnlessRestarted) {
  // A journal left by a different study (another hash) must not be mixed into this run.
  ScratchDir scratch("ensemble-changed");
  const std::string study = scratch.write("study.toml", study_text(2, "trace_realisations = []\n"));
  const std::string out = scratch.file("out.h5");
  { Journal stale(out + ".journal", {.study_hash = 12345, .description = "an older study"}); }
  const auto refused = run_cli("run " + study + " -o " + out, scratch);
  EXPECT_EQ(refused.exit_code, 2) << refused.output;
  EXPECT_NE(refused.output.find(out + ".journal"), std::string::npos) << refused.output;
  EXPECT_NE(refused.output.find("--restart"), std::string::npos) << refused.output;
  EXPECT_FALSE(std::filesystem::exists(out));
  const auto restarted = run_cli("run " + study + " --restart -o " + out, scratch);
  EXPECT_EQ(restarted.exit_code, 0) << restarted.output;
  EXPECT_TRUE(std::filesystem::exists(out));
}

//! What sits at `path`, for checking it was left alone: its type and, for a folder, its entries.
std::string what_is_at(const std::string& path) {
  const auto status = std::filesystem::symlink_status(path);
  std::string text = std::to_string(static_cast<int>(status.type()));
  if (status.type() == std::filesystem::file_type::directory)
    for (const auto& entry : std::filesystem::directory_iterator(path)) text.append(" ").append(entry.path().filename().string());
  return text;
}

//! --restart deleted whatever sat at <out>.journal: a device node, a FIFO, an empty folder
//! (and a non-empty one gave a raw "filesystem error"). It removes only a regular file that
//! starts as a stengmc journal; anything else is refused, named with what it is, and left as
//! it was. Without --restart, a FIFO there is refused too instead of failing to be read.
TEST(EnsembleCommand, RestartRemovesOnlyAStengmcJournal) {
  ScratchDir scratch("ensemble-restart");
  const std::string study = scratch.write("study.toml", study_text(2, "trace_realisations = []\n"));
  const std::string out = scratch.file("out.h5"), journal = out + ".journal";
  struct Case {
    std::string what;                             //!< how the message names it
    std::function<bool(const std::string&)> make;  //!< makes it at the path; false: cannot here
  };
  const std::vector<Case> cases = {
      {"a FIFO", [](const std::string& p) { return ::mkfifo(p.c_str(), 0666) == 0; }},
      // A copy of /dev/null's node: only root may make one.
      {"a character device", [](const std::string& p) { return ::mknod(p.c_str(), S_IFCHR | 0666, makedev(1, 3)) == 0; }},
      {"a folder", [](const std::string& p) { return std::filesystem::create_directory(p); }},
      {"a folder", [](const std::string& p) {
         std::filesystem::create_directory(p);
         std::ofstream(p + "/results.h5") << "someone's data";
         return true;
       }},
      {"a symbolic link", [&](const std::string& p) {
         { Journal real(scratch.file("real.journal"), {.study_hash = 1, .description = "a journal elsewhere"}); }
         std::filesystem::create_symlink(scratch.file("real.journal"), p);
         return true;
       }},
      {"a file that is not a stengmc journal", [](const std::string& p) {
         std::ofstream(p) << "someone's notes";
         return true;
       }},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.what);
    std::filesystem::remove_all(journal);
    if (!c.make(journal)) continue;  // a device node without root
    const std::string before = what_is_at(journal);
    const auto refused = run_cli("run " + study + " --restart -o " + out, scratch, "timeout 60");
    EXPECT_EQ(refused.exit_code, 2) << refused.output;
    EXPECT_NE(refused.output.find(journal + " is " + c.what), std::string::npos) << refused.output;
    EXPECT_EQ(refused.output.find("filesystem error"), std::string::npos) << refused.output;
    EXPECT_EQ(what_is_at(journal), before);
    EXPECT_FALSE(std::filesystem::exists(out));
  }
  std::filesystem::remove_all(journal);
  ASSERT_EQ(::mkfifo(journal.c_str(), 0666), 0);
  const auto resumed = run_cli("run " + study + " -o " + out, scratch, "timeout 60");
  EXPECT_EQ(resumed.exit_code, 2) << resumed.output;
  EXPECT_NE(resumed.output.find(journal + " is a FIFO"), std::string::npos) << resumed.output;
  EXPECT_TRUE(std::filesystem::is_fifo(journal));
}

// Short Model 2 runs of the lognormal-count surface; `surface` names the surface file.
std::string sweep_study(const std::string& surface, const std::string& ensemble) {
  return "seed = 5\nduration_s = 10e-6\nsample_rate_hz = 100e6\n"
         "[model]\nkind = \"model2\"\nbelt_velocity_m_per_s = 10\n"
         "[surface]\nfile = \"" + surface + "\"\n[domain]\npolicy = \"flag\"\n"
         "[spectrum]\nwindow = \"hann\"\nhigh_resolution = false\nmin_frequency_hz = 100e3\n"
         "[ensemble]\nrealisations = 3\ntrace_realisations = []\n" + ensemble;
}

TEST(EnsembleCommand, ASweepPointEqualsTheStudyEditedByHand) {
  // Grid point (count = 3, v_b = 4) of a sweep against an ensemble of the same study with
  // those two values written into the files: the datasets of that point must be bitwise
  // those of the edited study (the override reaches both the study and its surface file).
  ScratchDir scratch("ensemble-sweep");
  const std::string surface = std::string(STENGMC_SOURCE_DIR) + "/surfaces/lognormal_count.toml";
  const std::string sweep = scratch.write(
      "sweep.toml", sweep_study(surface, "[[ensemble.sweep]]\nparameter = \"surface.summits.count\"\nvalues = [2, 3]\n"
                                         "[[ensemble.sweep]]\nparameter = \"model.belt_velocity_m_per_s\"\nvalues = [10, 4]\n"));
  const auto swept = run_cli("run " + sweep + " -o " + scratch.file("sweep.h5"), scratch);
  ASSERT_EQ(swept.exit_code, 0) << swept.output;

  std::ifstream in(surface);
  std::stringstream text;
  text << in.rdbuf();
  std::string edited_surface = text.str();
  edited_surface.replace(edited_surface.find("count = 4"), 9, "count = 3");
  const std::string surface_copy = scratch.write("surface.toml", edited_surface);
  std::string edited = sweep_study(surface_copy, "");
  edited.replace(edited.find("belt_velocity_m_per_s = 10"), 26, "belt_velocity_m_per_s = 4");
  const std::string single = scratch.write("single.toml", edited);
  const auto alone = run_cli("run " + single + " -o " + scratch.file("single.h5"), scratch);
  ASSERT_EQ(alone.exit_code, 0) << alone.output;

  const Hdf5Reader a(scratch.file("sweep.h5")), b(scratch.file("single.h5"));
  // Grid order: the first axis slowest -> (2,10), (2,4), (3,10), (3,4): point 3.
  EXPECT_EQ(a.matrix("/grid/values")[3], (std::vector<double>{3.0, 4.0}));
  const std::vector<double> points = a.vector("/realisations/grid_point");
  for (std::size_t k = 0; k < SCALAR_COUNT; ++k) {
    const std::string name = "/realisations/" + std::string(scalar_info(static_cast<Scalar>(k)).name);
    const std::vector<double> all = a.vector(name), mine = b.vector(name);
    std::vector<double> point3;
    for (std::size_t i = 0; i < all.size(); ++i)
      if (points[i] == 3.0) point3.push_back(all[i]);
    ASSERT_EQ(point3.size(), mine.size()) << name;
    EXPECT_EQ(std::memcmp(point3.data(), mine.data(), mine.size() * sizeof(double)), 0) << name;
  }
  // A product grid: the statistics over (count, velocity), point 3 at [1][1].
  EXPECT_EQ(a.matrix("/summary/asperity_count/mean")[1][1], 3.0);
  EXPECT_EQ(a.matrix("/summary/asperity_count/mean")[0][0], 2.0);
}

TEST(EnsembleCommand, NoiseHasTheClosedFormSigmaAndASingleRunIsTheEnsemblesRecord) {
  // [noise] snr_db: sigma^2 = P / 10^(snr/10), P the mean square of the mean-removed clean
  // voltage over the analysis interval (docs/ensembles.md), computed here from the file's
  // own clean voltage; the noise actually added has that standard deviation (within 4
  // standard errors of a sample std, sigma / sqrt(2 N)). Realisation 2 run alone as an
  // ordinary run identifies exactly what the ensemble's record 2 says.
  ScratchDir scratch("ensemble-noise");
  const std::string surface = std::string(STENGMC_SOURCE_DIR) + "/surfaces/lognormal_count.toml";
  const std::string study =
      scratch.write("noisy.toml", sweep_study(surface, "") + "[noise]\nsnr_db = 10\n");
  const auto single = run_cli("run " + study + " --realisation 2 -o " + scratch.file("r2.h5"), scratch);
  ASSERT_EQ(single.exit_code, 0) << single.output;
  const Hdf5Reader r(scratch.file("r2.h5"));
  const std::vector<double> clean = r.vector("/circuit/voltage"), noisy = r.vector("/circuit/measured_voltage");
  const auto first = static_cast<std::size_t>(*r.integer_attribute("/spectrum", "first_sample"));
  const auto count = static_cast<std::size_t>(*r.integer_attribute("/spectrum", "samples"));
  double mean = 0.0, power = 0.0;
  for (std::size_t j = first; j < first + count; ++j) mean += clean[j];
  mean /= static_cast<double>(count);
  for (std::size_t j = first; j < first + count; ++j) power += (clean[j] - mean) * (clean[j] - mean);
  power /= static_cast<double>(count);
  const double sigma = std::sqrt(power / 10.0);
  EXPECT_NEAR(*r.number_attribute("/circuit/measured_voltage", "noise_sigma_v") / sigma, 1.0, 1e-12);
  double sum2 = 0.0;
  for (std::size_t j = 0; j < clean.size(); ++j) sum2 += (noisy[j] - clean[j]) * (noisy[j] - clean[j]);
  const double n = static_cast<double>(clean.size());
  EXPECT_NEAR(std::sqrt(sum2 / n) / sigma, 1.0, 4.0 / std::sqrt(2.0 * n));

  const auto only = run_cli("run " + study + " --only 2 -o " + scratch.file("only2.h5"), scratch);
  ASSERT_EQ(only.exit_code, 0) << only.output;
  const Hdf5Reader e(scratch.file("only2.h5"));
  EXPECT_EQ(e.vector("/realisations/fft_identifiable")[0],
            static_cast<double>(*r.integer_attribute("/spectrum/identifiability/fft", "n_identifiable")));
  EXPECT_EQ(e.vector("/realisations/fft_detected")[0],
            static_cast<double>(*r.integer_attribute("/spectrum/identifiability/fft", "n_detected")));
  EXPECT_EQ(*e.integer_attribute("/", "only_realisation"), 2);
}

TEST(EnsembleCommand, TargetRuleStopsAtTheSameBatchForAnyThreadsAndNotBeforeThirty) {
  // A half-width any sample meets: the run must still draw the minimum of 30 valid
  // realisations (in batches of 8: it stops after 32 of the cap of 100), and stop there
  // with 1 and with 2 threads alike, with bitwise the same datasets.
  ScratchDir scratch("ensemble-target");
  const std::string surface = std::string(STENGMC_SOURCE_DIR) + "/surfaces/lognormal_count.toml";
  std::string text = sweep_study(surface, "target_statistic = \"final_charge_c\"\ntarget_half_width = 1\nbatch = 8\n");
  text.replace(text.find("realisations = 3"), 16, "realisations = 100");
  const std::string study = scratch.write("target.toml", text);
  for (const char* threads : {"1", "2"}) {
    const auto result = run_cli("run " + study + " -j " + threads + " -o " + scratch.file(std::string("t") + threads + ".h5"), scratch);
    ASSERT_EQ(result.exit_code, 0) << result.output;
    EXPECT_NE(result.output.find("met, stopped early"), std::string::npos) << result.output;
    const Hdf5Reader f(scratch.file(std::string("t") + threads + ".h5"));
    EXPECT_EQ(*f.integer_attribute("/", "realisations_run"), 32) << threads << " threads";
    EXPECT_EQ(f.vector("/summary/target/met"), std::vector<double>{1.0});
  }
  expect_bitwise_equal_files(scratch.file("t1.h5"), scratch.file("t2.h5"));
}

TEST(EnsembleCommand, InvalidRealisationsAreCountedNamedAndLeftOutOfTheStatistics) {
  // l = 4 um: soft asperities break away past it (mu_s N / k = 4 um at k = 70 N/m, up to
  // 14 um), hard ones do not: about 40 % of the one-asperity realisations are invalid under
  // `flag` (lognormal k, median 75 N/m, sigma_log 0.3). The run goes
  // on, names the invalid ones, and the statistics count only the valid.
  ScratchDir scratch("ensemble-invalid");
  std::ifstream in(std::string(STENGMC_SOURCE_DIR) + "/surfaces/lognormal_count.toml");
  std::stringstream original;
  original << in.rdbuf();
  std::string surface_text = original.str();
  surface_text.replace(surface_text.find("length_m = 50e-6"), 17, "length_m = 4e-6");
  surface_text.replace(surface_text.find("count = 4"), 9, "count = 1");
  const std::string surface = scratch.write("short_l.toml", surface_text);
  std::string text = sweep_study(surface, "");
  text.replace(text.find("realisations = 3"), 16, "realisations = 12");
  const std::string study = scratch.write("invalid.toml", text);
  const auto result = run_cli("run " + study + " -o " + scratch.file("inv.h5"), scratch);
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const Hdf5Reader f(scratch.file("inv.h5"));
  const std::vector<double> valid = f.vector("/realisations/valid");
  const auto n_valid = static_cast<std::int64_t>(std::count(valid.begin(), valid.end(), 1.0));
  ASSERT_GT(n_valid, 0);
  ASSERT_LT(n_valid, 12) << "the study should break some realisations";
  EXPECT_EQ(*f.integer_attribute("/", "valid_realisations"), n_valid);
  EXPECT_EQ(f.vector("/summary/voltage_rms_v/count"), std::vector<double>{static_cast<double>(n_valid)});
  EXPECT_NE(result.output.find("invalid realisation"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("x reached l"), std::string::npos) << result.output;
}

TEST(EnsembleCommand, BadEnsembleInputNamesTheKeyOrTheGridPoint) {
  ScratchDir scratch("ensemble-bad");
  const std::string surface = std::string(STENGMC_SOURCE_DIR) + "/surfaces/lognormal_count.toml";
  struct Case {
    const char* name;
    std::string ensemble;
    std::vector<std::string> message;
  };
  const std::vector<Case> cases = {
      {"unknown target statistic", "target_statistic = \"vrms\"\ntarget_half_width = 0.1\n",
       {"study.toml:", "[ensemble] target_statistic", "voltage_rms_v"}},
      {"sweep of a missing table", "[[ensemble.sweep]]\nparameter = \"model.belt.velocity\"\nvalues = [1]\n",
       {"grid point 1 of 1", "model.belt.velocity", "no table [model.belt]"}},
      {"swept value the study refuses", "[[ensemble.sweep]]\nparameter = \"surface.summits.count\"\nvalues = [2, -1]\n",
       {"grid point 2 of 2", "surface.summits.count = -1", "count", ">= 0"}},
      {"sweeping the seed", "[[ensemble.sweep]]\nparameter = \"seed\"\nvalues = [1, 2]\n", {"seed", "cannot be swept"}},
  };
  for (const Case& c : cases) {
    const std::string study = scratch.write("study.toml", sweep_study(surface, c.ensemble));
    const auto result = run_cli("run " + study + " -o " + scratch.file("out.h5"), scratch);
    EXPECT_EQ(result.exit_code, 2) << c.name << "\n" << result.output;
    for (const std::string& part : c.message)
      EXPECT_NE(result.output.find(part), std::string::npos) << c.name << ": " << part << "\n" << result.output;
    EXPECT_FALSE(std::filesystem::exists(scratch.file("out.h5"))) << c.name;
  }
  // [noise] needs [spectrum]: the noise is added to what the spectra analyse.
  std::string no_spectrum = sweep_study(surface, "") + "[noise]\nsnr_db = 20\n";
  no_spectrum.erase(no_spectrum.find("[spectrum]"), no_spectrum.find("[ensemble]") - no_spectrum.find("[spectrum]"));
  const auto noise = run_cli("run " + scratch.write("noise.toml", no_spectrum), scratch);
  EXPECT_EQ(noise.exit_code, 2) << noise.output;
  EXPECT_NE(noise.output.find("[noise] snr_db needs a [spectrum] table"), std::string::npos) << noise.output;
}

}  // namespace
}  // namespace stengmc
