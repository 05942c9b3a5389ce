// Shards (docs/ensembles.md; docs/cluster.md): `run --shard i/n` for i = 0..n-1 and
// `merge` give the file one run writes, by golden_digest.py's comparison (every dataset and
// attribute but the creation time); bad shard specifications and bad merges are refused
// with exit 2, naming the file, and overwrite nothing.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "ensemble/journal.hpp"
#include "support/cli_runner.hpp"
#include "support/distributed_runs.hpp"

namespace stengmc {
namespace {

using testing::distributed_study;
using testing::file_differences;
using testing::run_cli;
using testing::ScratchDir;

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

//! Runs shards 0..n-1 of `study` (shard i on 1 + i % 2 threads) into `prefix`<i>; returns the paths.
std::vector<std::string> run_shards(const std::string& study, int n, const std::string& prefix, const ScratchDir& scratch) {
  std::vector<std::string> paths;
  for (int i = 0; i < n; ++i) {
    paths.push_back(scratch.file(prefix + std::to_string(i)));
    const auto shard = run_cli("run " + study + " --shard " + std::to_string(i) + "/" + std::to_string(n) + " -j " +
                                   std::to_string(1 + i % 2) + " -o " + paths.back(),
                               scratch);
    EXPECT_EQ(shard.exit_code, 0) << shard.output;
  }
  return paths;
}

void expect_merge_equals_single_run(const std::string& text, const std::string& name) {
  ScratchDir scratch("shards-" + name);
  const std::string study = scratch.write("study.toml", text);
  const auto whole = run_cli("run " + study + " -j 2 -o " + scratch.file("whole.h5"), scratch);
  ASSERT_EQ(whole.exit_code, 0) << whole.output;
  const std::vector<std::string> shards = run_shards(study, 3, "shard", scratch);
  for (const std::string& s : shards) EXPECT_FALSE(std::filesystem::exists(s + ".journal")) << "a journal outlives its shard";
  // In another order than written: the merge orders by grid point and id itself.
  const auto merged =
      run_cli("merge " + shards[2] + " " + shards[0] + " " + shards[1] + " -o " + scratch.file("merged.h5"), scratch);
  ASSERT_EQ(merged.exit_code, 0) << merged.output;
  EXPECT_EQ(file_differences(scratch.file("whole.h5"), scratch.file("merged.h5"), scratch), "");
}

TEST(Shards, ThreeShardsMergeToTheSingleRunFileOfAnEnsemble) {
  expect_merge_equals_single_run(distributed_study(11), "ensemble");
}

TEST(Shards, ThreeShardsMergeToTheSingleRunFileOfASweep) {
  expect_merge_equals_single_run(distributed_study(7, testing::TWO_POINT_SWEEP), "sweep");
}

TEST(Shards, BadShardSpecificationsAreRefusedWithExitTwo) {
  ScratchDir scratch("shards-specs");
  const std::string study = scratch.write("study.toml", distributed_study(4));
  for (const std::string spec : {"3/2", "2/2", "0/0", "-1/2", "a/b", "1", "1/2/3", "/2", "1/"}) {
    const auto refused = run_cli("run " + study + " --shard=" + spec + " -o " + scratch.file("s.shard"), scratch);
    EXPECT_EQ(refused.exit_code, 2) << spec << ": " << refused.output;
    EXPECT_NE(refused.output.find("--shard " + spec + ":"), std::string::npos) << spec << ": " << refused.output;
    EXPECT_FALSE(std::filesystem::exists(scratch.file("s.shard"))) << spec;
  }
  // A study with a target cannot be cut: a slice cannot know where the whole would stop.
  const std::string target = scratch.write(
      "target.toml", distributed_study(40, "target_statistic = \"final_charge_c\"\ntarget_half_width = 1\nbatch = 8\n"));
  const auto refused = run_cli("run " + target + " --shard 0/2 -o " + scratch.file("t.shard"), scratch);
  EXPECT_EQ(refused.exit_code, 2) << refused.output;
  EXPECT_NE(refused.output.find("target"), std::string::npos) << refused.output;
}

TEST(Shards, BadMergesAreRefusedNamingTheFileAndOverwriteNothing) {
  ScratchDir scratch("shards-bad-merges");
  const std::string study = scratch.write("study.toml", distributed_study(6));
  const std::vector<std::string> s = run_shards(study, 3, "shard", scratch);
  // Shard 1 of another study (another seed): same n, another identity.
  std::string other_text = distributed_study(6);
  other_text.replace(other_text.find("seed = 11"), 9, "seed = 12");
  const std::string other = scratch.write("other.toml", other_text);
  const std::string foreign = scratch.file("foreign1");
  ASSERT_EQ(run_cli("run " + other + " --shard 1/3 -o " + foreign, scratch).exit_code, 0);
  // An unfinished shard: its journal, not a shard file.
  const std::string unfinished = scratch.file("unfinished");
  { Journal journal(unfinished, {.study_hash = 1, .description = "a run in progress"}); }

  const std::string out = scratch.write("merged.h5", "an earlier result that must survive");
  struct Case {
    std::string what, shards, expected;
  };
  const Case cases[] = {
      {"a shard twice", s[0] + " " + s[0] + " " + s[1] + " " + s[2], s[0]},
      {"a shard of another study", s[0] + " " + foreign + " " + s[2], foreign},
      {"a missing shard", s[0] + " " + s[2], "index 1 of 3"},
      {"an unfinished shard", s[0] + " " + s[1] + " " + unfinished, unfinished},
  };
  for (const Case& c : cases) {
    const auto refused = run_cli("merge " + c.shards + " -o " + out, scratch);
    EXPECT_EQ(refused.exit_code, 2) << c.what << ": " << refused.output;
    EXPECT_NE(refused.output.find(c.expected), std::string::npos) << c.what << ": " << refused.output;
    EXPECT_EQ(read_text(out), "an earlier result that must survive") << c.what;
  }
  // The output onto one of the shards: refused, the shard intact.
  const std::string shard0 = read_text(s[0]);
  const auto onto = run_cli("merge " + s[0] + " " + s[1] + " " + s[2] + " -o " + s[0], scratch);
  EXPECT_EQ(onto.exit_code, 2) << onto.output;
  EXPECT_NE(onto.output.find("a shard file"), std::string::npos) << onto.output;
  EXPECT_EQ(read_text(s[0]), shard0);
  // A study edited since the shards ran is not theirs.
  std::ofstream(study, std::ios::app) << "# edited\n";
  const auto edited = run_cli("merge " + s[0] + " " + s[1] + " " + s[2] + " -o " + out, scratch);
  EXPECT_EQ(edited.exit_code, 2) << edited.output;
  EXPECT_NE(edited.output.find(study), std::string::npos) << edited.output;
  EXPECT_EQ(read_text(out), "an earlier result that must survive");
}

//! What merge reads is a regular file of a size it can hold (issue 22): a FIFO among the
//! shards blocked the merge for ever, /dev/zero would be read until memory ran out. Each is
//! refused naming the file and what it is; `timeout` turns the old hang into a failure.
TEST(Shards, AShardThatIsNotARegularFileIsRefusedNamingIt) {
  ScratchDir scratch("shards-not-regular");
  const std::string study = scratch.write("study.toml", distributed_study(4));
  const std::vector<std::string> s = run_shards(study, 2, "shard", scratch);
  const std::string fifo = scratch.file("fifo.shard");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0666), 0);
  const std::string out = scratch.file("merged.h5");
  for (const auto& [file, what] : {std::pair<std::string, std::string>{fifo, "a FIFO"}, {"/dev/zero", "a character device"}}) {
    const auto refused = run_cli("merge " + s[0] + " " + file + " -o " + out, scratch, "timeout 60");
    EXPECT_EQ(refused.exit_code, 2) << file << ": " << refused.output;
    EXPECT_NE(refused.output.find(file + " is not a regular file (" + what + ")"), std::string::npos) << refused.output;
    EXPECT_FALSE(std::filesystem::exists(out));
  }
  // The shards are read whole: together they must fit the memory limit, like any work.
  const auto large = run_cli("merge " + s[0] + " " + s[1] + " --max-memory-gb 1e-6 -o " + out, scratch, "timeout 60");
  EXPECT_EQ(large.exit_code, 2) << large.output;
  EXPECT_NE(large.output.find("most of it: the shard file " + scratch.file("shard")), std::string::npos) << large.output;
  EXPECT_NE(large.output.find("--max-memory-gb"), std::string::npos) << large.output;
  EXPECT_FALSE(std::filesystem::exists(out));
}

//! merge has no --restart: a damaged shard, or one of another journal format, must say how
//! to make it again, not advise an option merge does not have (issue 22).
TEST(Shards, ADamagedShardIsRefusedWithAdviceMergeCanFollow) {
  ScratchDir scratch("shards-damaged");
  const std::string study = scratch.write("study.toml", distributed_study(4));
  const std::vector<std::string> s = run_shards(study, 2, "shard", scratch);
  const std::string bytes = read_text(s[1]);
  std::string other_version = bytes;
  other_version[8] = 1;  // the u32 journal format version after the magic
  std::string damaged_record = bytes;
  damaged_record[bytes.size() - 20] = static_cast<char>(damaged_record[bytes.size() - 20] ^ 0x10);
  for (const auto& [what, text] : std::vector<std::pair<std::string, std::string>>{
           {"a torn header", bytes.substr(0, 20)}, {"another format version", other_version},
           {"a damaged record", damaged_record}}) {
    const std::string damaged = scratch.write("damaged.shard", text);
    const auto refused = run_cli("merge " + s[0] + " " + damaged + " -o " + scratch.file("merged.h5"), scratch);
    EXPECT_EQ(refused.exit_code, 2) << what << ": " << refused.output;
    EXPECT_NE(refused.output.find(damaged), std::string::npos) << what << ": " << refused.output;
    EXPECT_NE(refused.output.find("stengmc run STUDY --shard i/n"), std::string::npos) << what << ": " << refused.output;
    EXPECT_EQ(refused.output.find("--restart"), std::string::npos) << what << ": " << refused.output;
  }
}

}  // namespace
}  // namespace stengmc
