// The executable's heap in transparent huge pages (core/huge_page_heap.hpp): measured by
// the kernel's own count of page faults (getrusage's minor faults) while 16 MiB of new
// allocations are written, in a child process (gtest's death-test fork) so the test's own
// heap is left as it was. A control child without the call sees one fault per 4 KiB page,
// which shows the count measures what it should.
#include <gtest/gtest.h>
#include <sys/resource.h>

#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "core/huge_page_heap.hpp"

namespace {

constexpr std::size_t BLOCK_BYTES = 256 << 10;  // the size of a trace or a sum array
constexpr std::size_t TOTAL_BYTES = 16 << 20;
constexpr long PAGES_4K = TOTAL_BYTES / 4096;

long minor_faults() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_minflt;
}

//! Faults taken while allocating and writing TOTAL_BYTES in blocks (kept until the end).
long faults_writing_new_blocks() {
  std::vector<char*> blocks;
  blocks.reserve(TOTAL_BYTES / BLOCK_BYTES);
  const long before = minor_faults();
  for (std::size_t i = 0; i < TOTAL_BYTES / BLOCK_BYTES; ++i) {
    blocks.push_back(static_cast<char*>(std::malloc(BLOCK_BYTES)));
    std::memset(blocks.back(), 1, BLOCK_BYTES);
  }
  const long faults = minor_faults() - before;
  for (char* b : blocks) std::free(b);
  return faults;
}

bool kernel_offers_huge_pages_on_request() {
  std::ifstream setting("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string line;
  return std::getline(setting, line) && line.find("[never]") == std::string::npos;
}

}  // namespace

TEST(HugePageHeap, NewAllocationsFaultAQuarterAsOftenOrLessThanWithOrdinaryPages) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "the sanitizer's allocator replaces glibc's malloc: nothing to back with huge pages";
#endif
  if (!kernel_offers_huge_pages_on_request()) GTEST_SKIP() << "transparent huge pages are off on this kernel";
  GTEST_FLAG_SET(death_test_style, "fast");  // fork without re-running the test binary: same heap state

  // Control: without the call every new 4 KiB page faults once (glibc serves 256 KiB blocks
  // from their own mappings by default; either way the pages are new).
  EXPECT_EXIT(std::exit(faults_writing_new_blocks() >= PAGES_4K * 9 / 10 ? 0 : 1), testing::ExitedWithCode(0), "");
  // With it: 8 huge pages hold the 16 MiB; a quarter of the 4 KiB count leaves room for
  // whatever the heap's first boundary and the kernel's page tables cost.
  EXPECT_EXIT(std::exit(stengmc::back_the_heap_with_huge_pages() && faults_writing_new_blocks() <= PAGES_4K / 4 ? 0 : 1),
              testing::ExitedWithCode(0), "");
}
