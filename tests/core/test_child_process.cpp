// Work run in a child process under a budget (core/child_process.hpp): its result comes
// back whole, and a crash, a loop, a block or a runaway allocation ends the child, not this
// process, each reported as what it was.
#include <gtest/gtest.h>

#include <unistd.h>

#include <csignal>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

#include "core/child_process.hpp"

namespace stengmc {
namespace {

// AddressSanitizer catches SIGSEGV, reports it and aborts (abort_on_error=1, scripts/test.sh).
#if defined(__SANITIZE_ADDRESS__)
constexpr int CRASH_SIGNAL = SIGABRT;
#else
constexpr int CRASH_SIGNAL = SIGSEGV;
#endif

TEST(ChildProcess, AResultLargerThanThePipeComesBackWhole) {
  // 8 MB: far beyond a pipe's 64 kB buffer, so parent and child must interleave.
  std::string expected(8u << 20, '\0');
  for (std::size_t k = 0; k < expected.size(); ++k) expected[k] = static_cast<char>(k * 2654435761u >> 24);
  std::size_t chunks = 0;
  const ChildOutcome outcome = run_in_child([&](int fd) { write_to_pipe(fd, expected); }, ChildBudget{},
                                            [&](std::string_view) { ++chunks; });
  EXPECT_EQ(outcome.end, ChildOutcome::End::finished);
  EXPECT_TRUE(outcome.result == expected);
  EXPECT_GT(chunks, 1u);
}

TEST(ChildProcess, AnExceptionIsAFailureAndACrashIsNamedBySignal) {
  const ChildOutcome failed = run_in_child([](int) { throw std::runtime_error("x"); }, ChildBudget{});
  EXPECT_EQ(failed.end, ChildOutcome::End::failed);
  EXPECT_EQ(failed.exit_status, 1);
  const ChildOutcome crashed = run_in_child([](int) { std::raise(SIGSEGV); }, ChildBudget{});
  EXPECT_EQ(crashed.end, ChildOutcome::End::crashed);
  EXPECT_EQ(crashed.signal_number, CRASH_SIGNAL);
  EXPECT_NE(crashed.describe(ChildBudget{}).find("crashed"), std::string::npos);
}

TEST(ChildProcess, ALoopIsStoppedAtItsCpuBudget) {
  ChildBudget budget;
  budget.cpu_seconds = 1.0;
  const ChildOutcome outcome = run_in_child(
      [](int) {
        for (;;) asm volatile("");  // busy, and not optimised away
      },
      budget);
  EXPECT_EQ(outcome.end, ChildOutcome::End::out_of_time);
}

TEST(ChildProcess, AChildThatBlocksIsStoppedAtItsWallTimeBudget) {
  ChildBudget budget;
  budget.wall_seconds = 1.0;
  const auto start = std::chrono::steady_clock::now();
  const ChildOutcome outcome = run_in_child([](int) { ::pause(); }, budget);
  EXPECT_EQ(outcome.end, ChildOutcome::End::out_of_time);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 10.0);
}

TEST(ChildProcess, ARunawayAllocationIsStoppedAtItsMemoryBudget) {
  ChildBudget budget;
  budget.memory_bytes = 64e6;
  const ChildOutcome outcome = run_in_child(
      [](int) {
        // 2 GB touched page by page, never freed: the watch (or the address-space limit,
        // whose failed allocation throws) stops it long before.
        std::vector<char*> blocks;
        for (int k = 0; k < 2048; ++k) {
          blocks.push_back(new char[1 << 20]);
          std::memset(blocks.back(), 1, 1 << 20);
          std::this_thread::sleep_for(std::chrono::microseconds(200));
        }
      },
      budget);
  // Killed by the parent's watch of the resident size, or failed inside (bad_alloc at the
  // address-space limit): never finished.
  EXPECT_TRUE(outcome.end == ChildOutcome::End::out_of_memory || outcome.end == ChildOutcome::End::failed)
      << outcome.describe(budget);
}

}  // namespace
}  // namespace stengmc
