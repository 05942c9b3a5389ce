#include "core/huge_page_heap.hpp"

#include <cstddef>
#include <cstdint>
#include <cstdlib>  // first: it defines __GLIBC__ under glibc

#if defined(__linux__) && defined(__GLIBC__)
#include <malloc.h>
#include <sys/mman.h>
#include <unistd.h>
#endif

namespace stengmc {

#if defined(__linux__) && defined(__GLIBC__) && !defined(__SANITIZE_ADDRESS__)

namespace {

constexpr std::uintptr_t HUGE_PAGE_BYTES = std::uintptr_t{2} << 20;  // x86-64's PMD size
// Address space only: pages are allocated when first touched, so a run that needs 6 MiB
// gets three huge pages, and one that needs more than this grows the heap as usual beyond.
constexpr std::size_t RESERVE_BYTES = std::size_t{64} << 20;

std::uintptr_t program_break() { return reinterpret_cast<std::uintptr_t>(sbrk(0)); }

// The main arena's top chunk (the free block malloc carves new memory from) ends at the
// program break: it starts `keepcost` bytes below it (mallinfo2, main arena).
std::uintptr_t top_chunk_start() { return program_break() - mallinfo2().keepcost; }

// The block that moves the top chunk up to the first huge page; never freed, never touched
// beyond its header (address space below that page, no memory).
void* skipped_below_first_huge_page = nullptr;

}  // namespace

bool back_the_heap_with_huge_pages() {
  // Blocks of up to 32 MiB (glibc's own largest dynamic threshold) come from the heap, not
  // from mappings of their own that fault afresh each time; and freeing does not hand the
  // reserve back to the system.
  if (mallopt(M_MMAP_THRESHOLD, 32 << 20) == 0 || mallopt(M_TRIM_THRESHOLD, 256 << 20) == 0) return false;

  // Grow the heap by the reserve: a block just larger than the top chunk makes malloc
  // extend the break by it plus M_TOP_PAD; freed, it merges back into the top chunk. Only
  // its header and the top chunk's, near the old break, are written.
  const std::uintptr_t old_break = program_break();
  if (mallopt(M_TOP_PAD, static_cast<int>(RESERVE_BYTES)) == 0) return false;
  void* volatile grow = std::malloc(mallinfo2().keepcost + (16 << 10));  // volatile: not elided
  std::free(grow);
  mallopt(M_TOP_PAD, 128 << 10);  // glibc's default again

  // Huge pages cover whole aligned 2 MiB ranges whose page table is still empty: from the
  // first boundary past the headers just written, to the last one below the new break.
  const std::uintptr_t first = (old_break + (64 << 10) + HUGE_PAGE_BYTES - 1) & ~(HUGE_PAGE_BYTES - 1);
  const std::uintptr_t last = program_break() & ~(HUGE_PAGE_BYTES - 1);
  if (last < first + 2 * HUGE_PAGE_BYTES) return false;
  if (madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE) != 0) return false;

  // Start carving at the first huge page: otherwise the first up to 2 MiB of the run's
  // allocations land below it, in ordinary pages.
  const std::uintptr_t top = top_chunk_start();
  if (top >= first || first - top > 2 * HUGE_PAGE_BYTES) return false;
  skipped_below_first_huge_page = std::malloc(first - top);
  return skipped_below_first_huge_page != nullptr && top_chunk_start() >= first;
}

#else

bool back_the_heap_with_huge_pages() { return false; }

#endif

}  // namespace stengmc
