#pragma once
//! The command line's heap in transparent huge pages.
//!
//! A single run touches a few MiB of fresh memory (HDF5's file image and metadata cache, the
//! traces, the circuit's per-sample sums), and on Linux every 4 KiB page of it costs a page
//! fault when first written: ~1 000 faults, ~1.3 µs each on this project's machines, about
//! 15 % of the paper case's CPU time. One 2 MiB transparent huge page replaces 512 of them.
//! glibc does this itself with the tunable `glibc.malloc.hugetlb=1`, but only when it is set
//! in the environment before the process starts; this does it from inside.
//!
//! Only the executable calls it, first thing in main, while one thread runs: it changes how
//! glibc's malloc grows the main heap for the rest of the process (docs/performance.md).

namespace stengmc {

//! Reserves address space at the top of the main heap (no memory: pages are only allocated
//! when touched), asks the kernel to back it with transparent huge pages
//! (madvise(MADV_HUGEPAGE)), and keeps glibc from returning it to the system between
//! allocations or serving large blocks from separate mappings. Returns whether it did: false
//! where it cannot (not glibc on Linux, a sanitizer's allocator, a heap that does not look
//! as expected); nothing changes then, and nothing is ever wrong, only slower.
bool back_the_heap_with_huge_pages();

}  // namespace stengmc
