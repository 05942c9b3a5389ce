// Unfinished ensembles made readable (issue 25, item 5): `stengmc status` reports which
// realisations a shard file or journal holds and which are missing, and `merge --partial`
// writes the finished part as an ordinary ensemble file marked partial. The ids expected
// here are the ones the test ran or journalled itself; the rows are compared with a whole
// run's and the statistics recomputed from the rows.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <thread>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <set>

#include "core/hdf5_file.hpp"
#include "ensemble/journal.hpp"
#include "ensemble/realisation_record.hpp"
#include "ensemble/shard.hpp"
#include "support/cli_runner.hpp"
#include "support/distributed_runs.hpp"

extern char** environ;

namespace stengmc {
namespace {

using testing::distributed_study;
using testing::run_cli;
using testing::ScratchDir;

constexpr int REALISATIONS = 11;

//! Runs shard `i` of 3 of `study` into <scratch>/shard<i>; returns its path.
std::string run_shard(const std::string& study, int i, const ScratchDir& scratch) {
  const std::string path = scratch.file("shard" + std::to_string(i));
  const auto run = run_cli("run " + study + " --shard " + std::to_string(i) + "/3 -o " + path, scratch);
  EXPECT_EQ(run.exit_code, 0) << run.output;
  return path;
}

//! The journal a run of `study` (one grid point) killed after finishing realisations `ids`
//! leaves: those records, taken from shard files of the same study. Its identity is the one
//! the stengmc under test gives it: a single point's study hash is the study's, which the
//! shard files carry (this test's own build may differ from that program's, e.g. in its
//! git revision, so it does not hash the study itself); the description names the study
//! file as the runner's does.
void write_killed_journal(const std::string& path, const std::string& study_path, const std::vector<std::string>& shards,
                          const std::vector<std::uint64_t>& ids) {
  Journal journal(path, {read_shard_file(shards.front()).study_identity, "stengmc (the test's), study " + study_path});
  for (const std::string& s : shards)
    for (const RealisationRecord& r : read_shard_file(s).records)
      if (std::find(ids.begin(), ids.end(), r.realisation) != ids.end()) journal.append(r);
}

TEST(PartialResults, StatusOfAShardSaysWhichShardAndThatNoneOfItsShareIsMissing) {
  ScratchDir scratch("partial-status-shard");
  const std::string study = scratch.write("study.toml", distributed_study(REALISATIONS));
  const std::string shard = run_shard(study, 1, scratch);  // ids 1, 4, 7, 10
  const auto status = run_cli("status " + shard, scratch);
  ASSERT_EQ(status.exit_code, 0) << status.output;
  EXPECT_NE(status.output.find("a finished shard file, shard 1/3"), std::string::npos) << status.output;
  EXPECT_NE(status.output.find("study: " + study), std::string::npos) << status.output;
  EXPECT_NE(status.output.find("4 of 4 realisations finished"), std::string::npos) << status.output;
  EXPECT_NE(status.output.find("missing: none"), std::string::npos) << status.output;
}

TEST(PartialResults, StatusOfAKilledRunsJournalListsTheMissingIdsAndTheTornTail) {
  ScratchDir scratch("partial-status-journal");
  const std::string study = scratch.write("study.toml", distributed_study(REALISATIONS));
  const std::vector<std::string> shards = {run_shard(study, 0, scratch), run_shard(study, 2, scratch)};
  const std::string journal = scratch.file("killed.h5.journal");
  write_killed_journal(journal, study, shards, {0, 2, 3, 5, 9});
  const auto bytes = std::filesystem::file_size(journal);

  const auto status = run_cli("status " + journal, scratch);
  ASSERT_EQ(status.exit_code, 0) << status.output;
  EXPECT_NE(status.output.find("a journal of a run in progress or interrupted"), std::string::npos) << status.output;
  EXPECT_NE(status.output.find("5 of 11 realisations finished"), std::string::npos) << status.output;
  EXPECT_NE(status.output.find("missing: 1, 4, 6-8, 10\n"), std::string::npos) << status.output;
  EXPECT_EQ(status.output.find("torn"), std::string::npos) << status.output;

  // A kill mid-append leaves part of a record: reported, and the file is left as it was.
  std::ofstream(journal, std::ios::app | std::ios::binary) << std::string(37, '\x01');
  const auto torn = run_cli("status " + journal, scratch);
  ASSERT_EQ(torn.exit_code, 0) << torn.output;
  EXPECT_NE(torn.output.find("torn: the last 37 bytes"), std::string::npos) << torn.output;
  EXPECT_NE(torn.output.find("missing: 1, 4, 6-8, 10\n"), std::string::npos) << torn.output;
  EXPECT_EQ(std::filesystem::file_size(journal), bytes + 37) << "status changed the journal";

  // The study moved: the file is still readable (exit 0), the finished ids are listed, and
  // --study gives the count again.
  const std::string moved = scratch.file("moved.toml");
  std::filesystem::rename(study, moved);
  const auto unknown = run_cli("status " + journal, scratch);
  ASSERT_EQ(unknown.exit_code, 0) << unknown.output;
  EXPECT_NE(unknown.output.find("how many are expected is not known"), std::string::npos) << unknown.output;
  EXPECT_NE(unknown.output.find("finished ids: 0, 2-3, 5, 9\n"), std::string::npos) << unknown.output;
  const auto told = run_cli("status " + journal + " --study " + moved, scratch);
  ASSERT_EQ(told.exit_code, 0) << told.output;
  EXPECT_NE(told.output.find("missing: 1, 4, 6-8, 10\n"), std::string::npos) << told.output;
}

TEST(PartialResults, StatusOfSomethingElseIsAnInputErrorNamingTheFile) {
  ScratchDir scratch("partial-status-refused");
  const std::string study = scratch.write("study.toml", distributed_study(REALISATIONS));
  const auto refused = run_cli("status " + study, scratch);
  EXPECT_EQ(refused.exit_code, 2) << refused.output;
  EXPECT_NE(refused.output.find(study + ": not a stengmc journal"), std::string::npos) << refused.output;
}

//! "a-b, c": the ids of 0..count-1 not in `present`, written out here rather than by the
//! code under test.
std::string missing_text(const std::set<std::uint64_t>& present, std::uint64_t count) {
  std::string out;
  for (std::uint64_t id = 0; id < count;) {
    if (present.count(id)) {
      ++id;
      continue;
    }
    std::uint64_t last = id;
    while (last + 1 < count && !present.count(last + 1)) ++last;
    if (!out.empty()) out += ", ";
    out += std::to_string(id);
    if (last > id) out.append("-").append(std::to_string(last));
    id = last + 1;
  }
  return out;
}

//! The ids in the journal at `path` (every intact record), or none while it is not there.
std::set<std::uint64_t> journal_ids(const std::string& path) {
  std::set<std::uint64_t> ids;
  try {
    for (const RealisationRecord& r : scan_journal_file(path, "the journal", "").contents.records) ids.insert(r.realisation);
  } catch (const std::exception&) {
    // not there yet
  }
  return ids;
}

//! Starts stengmc with `args` (after the binary), SIGKILLs it once `journal` holds at least
//! `records` records (or after a minute), and returns the ids the journal holds then; fails
//! the test if the run ended by itself.
std::set<std::uint64_t> run_and_kill(std::vector<std::string> args, const std::string& out, const std::string& journal,
                                     std::size_t records) {
  args.insert(args.begin(), STENGMC_BINARY);
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, (out + ".log").c_str(), O_WRONLY | O_CREAT, 0644);
  posix_spawn_file_actions_addopen(&actions, 2, (out + ".err").c_str(), O_WRONLY | O_CREAT, 0644);
  pid_t pid = 0;
  EXPECT_EQ(posix_spawn(&pid, STENGMC_BINARY, &actions, nullptr, argv.data(), environ), 0);
  posix_spawn_file_actions_destroy(&actions);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (std::chrono::steady_clock::now() < deadline && journal_ids(journal).size() < records)
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  ::kill(pid, SIGKILL);
  int wait_status = 0;
  ::waitpid(pid, &wait_status, 0);
  EXPECT_TRUE(WIFSIGNALED(wait_status)) << "the run ended before it was killed";
  return journal_ids(journal);
}

//! A sweep run SIGKILLed by the test once its first point's journal holds a few records:
//! status finds the point by the journal's hash (the runner's own, not made by the test)
//! and lists exactly the ids the journal does not hold.
TEST(PartialResults, StatusOfARealKilledSweepFindsItsGridPointAndMissingIds) {
  ScratchDir scratch("partial-status-killed");
  constexpr int MANY = 3000;  // far more than run before the kill
  const std::string study = scratch.write("study.toml", distributed_study(MANY, testing::TWO_POINT_SWEEP));
  const std::string out = scratch.file("killed.h5"), journal = out + ".point0.journal";
  const std::set<std::uint64_t> ids = run_and_kill({"run", study, "-j", "1", "-o", out}, out, journal, 5);
  ASSERT_GE(ids.size(), 5u);
  const auto status = run_cli("status " + journal, scratch);
  ASSERT_EQ(status.exit_code, 0) << status.output;
  EXPECT_NE(status.output.find("grid point 1 of 2 (count = 2): " + std::to_string(ids.size()) + " of " +
                               std::to_string(MANY) + " realisations finished"),
            std::string::npos)
      << status.output;
  EXPECT_NE(status.output.find("missing: " + missing_text(ids, MANY) + "\n"), std::string::npos) << status.output;

  // Grid point 2 has nothing yet: an ensemble file needs every point, so --partial refuses,
  // naming that point (and only that one) and writing nothing.
  const auto refused = run_cli("merge --partial " + journal + " -o " + scratch.file("p.h5"), scratch);
  EXPECT_EQ(refused.exit_code, 2) << refused.output;
  EXPECT_NE(refused.output.find("grid point 2 (count = 5) of 2 in " + study), std::string::npos) << refused.output;
  EXPECT_EQ(refused.output.find("grid points"), std::string::npos) << refused.output;
  EXPECT_NE(refused.output.find("nothing was written"), std::string::npos) << refused.output;
  EXPECT_FALSE(std::filesystem::exists(scratch.file("p.h5")));
}

//! The journal of a `--shard 1/3` run killed part-way: status counts it against that
//! shard's share (the ids r with r mod 3 = 1), not every id of the study, and lists as
//! missing only the share's ids the journal lacks. The expected ids are computed here from
//! r mod 3 and the records the journal holds.
TEST(PartialResults, StatusOfAKilledShardRunsJournalCountsOnlyItsShare) {
  ScratchDir scratch("partial-status-shard-journal");
  constexpr std::uint64_t MANY = 3000;
  const std::string study = scratch.write("study.toml", distributed_study(MANY));
  const std::string out = scratch.file("s1.h5"), journal = out + ".journal";
  const std::set<std::uint64_t> ids =
      run_and_kill({"run", study, "--shard", "1/3", "-j", "1", "-o", out}, out, journal, 5);
  ASSERT_GE(ids.size(), 5u);
  std::vector<std::uint64_t> missing;
  std::uint64_t share = 0;
  for (std::uint64_t id = 0; id < MANY; ++id) {
    if (id % 3 != 1) continue;
    ++share;
    if (!ids.count(id)) missing.push_back(id);
  }
  ASSERT_EQ(share, 1000u);
  for (const std::uint64_t id : ids) ASSERT_EQ(id % 3, 1u) << "shard 1/3 ran realisation " << id;

  const auto status = run_cli("status " + journal, scratch);
  ASSERT_EQ(status.exit_code, 0) << status.output;
  EXPECT_NE(status.output.find("a journal of shard 1/3's run"), std::string::npos) << status.output;
  EXPECT_NE(status.output.find(std::to_string(ids.size()) + " of 1000 realisations finished (shard 1/3's share)"),
            std::string::npos)
      << status.output;
  // The missing ids are every third, so each is a range of one: the first 40, then the count left.
  std::string listed;
  for (std::size_t k = 0; k < 40; ++k) listed += (k ? ", " : "") + std::to_string(missing[k]);
  listed += ", ... (" + std::to_string(missing.size() - 40) + " more)\n";
  EXPECT_NE(status.output.find("missing: " + listed), std::string::npos) << status.output;

  // merge --partial takes the shard run's journal as it is: its realisations, nothing else.
  const auto merged = run_cli("merge --partial " + journal + " -o " + scratch.file("p.h5"), scratch);
  ASSERT_EQ(merged.exit_code, 0) << merged.output;
  const Hdf5Reader partial(scratch.file("p.h5"));
  EXPECT_EQ(partial.vector("/realisations/realisation"), std::vector<double>(ids.begin(), ids.end()));
}

//! The rows of `name` in `path`, by realisation id.
std::map<double, double> rows_by_id(const Hdf5Reader& file, const std::string& name) {
  const std::vector<double> ids = file.vector("/realisations/realisation"), values = file.vector(name);
  std::map<double, double> rows;
  for (std::size_t i = 0; i < ids.size(); ++i) rows[ids[i]] = values[i];
  return rows;
}

TEST(PartialResults, MergePartialOfTwoOfThreeShardsHoldsTheirRealisationsAsTheWholeRunDoes) {
  ScratchDir scratch("partial-merge");
  const std::string study = scratch.write("study.toml", distributed_study(REALISATIONS));
  const auto whole = run_cli("run " + study + " -o " + scratch.file("whole.h5"), scratch);
  ASSERT_EQ(whole.exit_code, 0) << whole.output;
  const std::string s0 = run_shard(study, 0, scratch), s2 = run_shard(study, 2, scratch);
  const std::vector<double> ran = {0, 2, 3, 5, 6, 8, 9};  // r mod 3 = 0 or 2

  // Without --partial the merge still wants every shard.
  const auto refused = run_cli("merge " + s0 + " " + s2 + " -o " + scratch.file("refused.h5"), scratch);
  EXPECT_EQ(refused.exit_code, 2) << refused.output;
  EXPECT_FALSE(std::filesystem::exists(scratch.file("refused.h5")));

  const std::string out = scratch.file("partial.h5");
  const auto merged = run_cli("merge --partial " + s2 + " " + s0 + " -o " + out, scratch);
  ASSERT_EQ(merged.exit_code, 0) << merged.output;
  EXPECT_NE(merged.output.find("PARTIAL: 7 of the 11 realisations"), std::string::npos) << merged.output;

  const Hdf5Reader partial(out), full(scratch.file("whole.h5"));
  EXPECT_EQ(partial.vector("/realisations/realisation"), ran);
  EXPECT_EQ(partial.integer_attribute("/", "partial"), 1);
  EXPECT_EQ(partial.integer_attribute("/", "realisations_expected"), REALISATIONS);
  EXPECT_EQ(partial.integer_attribute("/", "realisations_present"), 7);
  EXPECT_FALSE(full.integer_attribute("/", "partial").has_value()) << "a whole run's file is not marked partial";

  const std::map<double, double> valid = rows_by_id(partial, "/realisations/valid");
  for (std::size_t k = 0; k < SCALAR_COUNT; ++k) {
    const std::string name(scalar_info(static_cast<Scalar>(k)).name);
    const std::map<double, double> mine = rows_by_id(partial, "/realisations/" + name),
                                   whole_rows = rows_by_id(full, "/realisations/" + name);
    std::vector<double> kept;  // the valid rows, which the statistics are over
    for (const auto& [id, value] : mine) {
      ASSERT_TRUE(whole_rows.count(id)) << name << " " << id;
      if (std::isnan(value)) EXPECT_TRUE(std::isnan(whole_rows.at(id))) << name << " " << id;
      else EXPECT_EQ(value, whole_rows.at(id)) << name << " realisation " << id;
      if (valid.at(id) == 1.0) kept.push_back(value);
    }
    const std::string summary = "/summary/" + name + "/";
    ASSERT_FALSE(kept.empty());
    EXPECT_EQ(partial.vector(summary + "count")[0], static_cast<double>(kept.size())) << name;
    const double mean = std::accumulate(kept.begin(), kept.end(), 0.0) / static_cast<double>(kept.size());
    if (std::isfinite(mean)) {
      EXPECT_NEAR(partial.vector(summary + "mean")[0], mean, 1e-12 * std::max(1.0, std::abs(mean)) + 1e-300) << name;
    }
    EXPECT_EQ(partial.vector(summary + "min")[0], *std::min_element(kept.begin(), kept.end())) << name;
    EXPECT_EQ(partial.vector(summary + "max")[0], *std::max_element(kept.begin(), kept.end())) << name;
  }
}

TEST(PartialResults, MergePartialTakesAKilledRunsJournalToo) {
  ScratchDir scratch("partial-merge-journal");
  const std::string study = scratch.write("study.toml", distributed_study(REALISATIONS));
  const std::vector<std::string> shards = {run_shard(study, 0, scratch), run_shard(study, 1, scratch)};
  const std::string journal = scratch.file("killed.h5.journal");
  write_killed_journal(journal, study, shards, {1, 3, 4});
  // Shard 0 (0, 3, 6, 9) and the journal (1, 3, 4): 3 is in both, and counted once.
  const auto merged = run_cli("merge --partial " + shards[0] + " " + journal + " -o " + scratch.file("p.h5"), scratch);
  ASSERT_EQ(merged.exit_code, 0) << merged.output;
  const Hdf5Reader partial(scratch.file("p.h5"));
  EXPECT_EQ(partial.vector("/realisations/realisation"), (std::vector<double>{0, 1, 3, 4, 6, 9}));
  EXPECT_EQ(partial.integer_attribute("/", "realisations_present"), 6);
}

}  // namespace
}  // namespace stengmc
