// Byte-identical outputs (issue 25, point 5): with SOURCE_DATE_EPOCH set, one study and
// seed give the same file, byte for byte (so the same sha256), on 1 or 2 threads, on 2 MPI
// ranks and merged from shards: HDF5 objects carry no timestamps (core/hdf5_untimed.hpp)
// and created_utc is the variable's time (core/creation_time.hpp). Without the variable
// created_utc is the time of the run; a malformed one is refused before any work.
#include <gtest/gtest.h>

#include <chrono>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "core/hdf5_file.hpp"
#include "support/cli_runner.hpp"
#include "support/distributed_runs.hpp"

namespace stengmc {
namespace {

using testing::distributed_study;
using testing::run_cli;
using testing::ScratchDir;

// 2023-11-14T22:13:20Z.
const std::string FIXED_TIME = "SOURCE_DATE_EPOCH=1700000000";

std::string bytes_of(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

//! "" when the files are byte-identical, else how many bytes differ and where the first is
//! (what `cmp -l` would show), so a failure points at the object that changed.
std::string byte_differences(const std::string& a, const std::string& b) {
  const std::string x = bytes_of(a);
  const std::string y = bytes_of(b);
  if (x.size() != y.size()) return a + " has " + std::to_string(x.size()) + " bytes, " + b + " " + std::to_string(y.size());
  std::size_t count = 0;
  std::size_t first = 0;
  for (std::size_t i = 0; i < x.size(); ++i)
    if (x[i] != y[i] && count++ == 0) first = i;
  if (count == 0) return "";
  return std::to_string(count) + " bytes differ, the first at offset " + std::to_string(first);
}

std::string utc_text(std::chrono::system_clock::time_point when) {
  const std::time_t t = std::chrono::system_clock::to_time_t(when);
  std::tm parts{};
  gmtime_r(&t, &parts);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &parts);
  return text;
}

TEST(IdenticalBytes, OneAndTwoThreadsTwoRanksAndMergedShardsGiveOneSha256) {
  ScratchDir scratch("identical-bytes");
  const std::string study = scratch.write("study.toml", distributed_study(6));
  const std::string reference = scratch.file("j1.h5");
  const auto single = run_cli("run " + study + " -j 1 -o " + reference, scratch, FIXED_TIME);
  ASSERT_EQ(single.exit_code, 0) << single.output;
  // A second later: a time of making recorded anywhere in the file (HDF5 records seconds)
  // would now differ.
  std::this_thread::sleep_for(std::chrono::milliseconds(1100));
  std::vector<std::string> same;

  same.push_back(scratch.file("j2.h5"));
  const auto threads = run_cli("run " + study + " -j 2 -o " + same.back(), scratch, FIXED_TIME);
  ASSERT_EQ(threads.exit_code, 0) << threads.output;

#ifdef STENGMC_MPIEXEC
  // As test_mpi_runs launches: root allowed (CI containers), more ranks than cores, unpinned.
  same.push_back(scratch.file("p2.h5"));
  const auto ranks = testing::run_command("env " + FIXED_TIME + " " + STENGMC_MPIEXEC +
                                              " --allow-run-as-root --oversubscribe --bind-to none -np 2 " +
                                              STENGMC_BINARY + " run " + study + " -j 1 -o " + same.back(),
                                          scratch);
  ASSERT_EQ(ranks.exit_code, 0) << ranks.output;
#endif

  same.push_back(scratch.file("merged.h5"));
  for (int i = 0; i < 2; ++i) {
    const auto shard = run_cli("run " + study + " --shard " + std::to_string(i) + "/2 -j " + std::to_string(1 + i) +
                                   " -o " + scratch.file("shard" + std::to_string(i)),
                               scratch, FIXED_TIME);
    ASSERT_EQ(shard.exit_code, 0) << shard.output;
  }
  const auto merged = run_cli("merge " + scratch.file("shard1") + " " + scratch.file("shard0") + " -o " + same.back(),
                              scratch, FIXED_TIME);
  ASSERT_EQ(merged.exit_code, 0) << merged.output;

  for (const std::string& file : same) EXPECT_EQ(byte_differences(reference, file), "") << file;
  EXPECT_EQ(Hdf5Reader(reference).string_attribute("/", "created_utc"), "2023-11-14T22:13:20Z");
}

TEST(IdenticalBytes, WithoutSourceDateEpochCreatedUtcIsTheTimeOfTheRun) {
  ScratchDir scratch("identical-bytes-now");
  const std::string study = scratch.write("study.toml", distributed_study(2));
  const std::string out = scratch.file("now.h5");
  // Whole seconds: created_utc has no fraction. The text's order is the time's order.
  const std::string before = utc_text(std::chrono::floor<std::chrono::seconds>(std::chrono::system_clock::now()));
  const auto run = run_cli("run " + study + " -j 1 -o " + out, scratch, "-u SOURCE_DATE_EPOCH");
  const std::string after = utc_text(std::chrono::system_clock::now());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const std::string created = Hdf5Reader(out).string_attribute("/", "created_utc");
  EXPECT_LE(before, created);
  EXPECT_LE(created, after);
}

TEST(IdenticalBytes, AMalformedSourceDateEpochIsRefusedNamingItBeforeAnyWork) {
  ScratchDir scratch("identical-bytes-malformed");
  const std::string study = scratch.write("study.toml", distributed_study(2));
  const std::string out = scratch.file("refused.h5");
  // Not `date +%s`: text, empty, a sign, a fraction, a space, past year 9999.
  for (const std::string value : {"yesterday", "", "-1", "1.5", " 1", "253402300800"}) {
    const auto refused = run_cli("run " + study + " -o " + out, scratch, "SOURCE_DATE_EPOCH='" + value + "'");
    EXPECT_EQ(refused.exit_code, 2) << "[" << value << "] " << refused.output;
    EXPECT_NE(refused.output.find("input error: environment variable SOURCE_DATE_EPOCH = \"" + value +
                                  "\": expected a whole number of seconds since 1970-01-01T00:00:00Z"),
              std::string::npos)
        << refused.output;
    EXPECT_FALSE(std::filesystem::exists(out)) << value;
    EXPECT_FALSE(std::filesystem::exists(out + ".journal")) << value;
  }
  // Help and the version write no file: they answer whatever the variable holds.
  for (const char* asked : {"--help", "--version", "run --help"}) {
    const auto answered = run_cli(asked, scratch, "SOURCE_DATE_EPOCH=yesterday");
    EXPECT_EQ(answered.exit_code, 0) << asked << ": " << answered.output;
  }
}

}  // namespace
}  // namespace stengmc
