#include "rgbdvo/util/image_heap.hpp"

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#if defined(__GLIBC__)
#include <malloc.h>
#include <sys/mman.h>
#include <unistd.h>
#endif

namespace rgbdvo {

size_t SetUpImageHeap(size_t huge_page_bytes) {
#if defined(__GLIBC__)
  // NOLINTBEGIN(concurrency-mt-unsafe): this runs first in main, before any thread is started.
  constexpr int kMiB = 1 << 20;
  // Freed images stay in the heap, so a frame does not fault their pages in again
  // (docs/decisions/0027-memory-kept-by-the-allocator.md). 32 MiB is the largest mmap threshold
  // glibc accepts on 64-bit systems.
  mallopt(M_MMAP_THRESHOLD, 32 * kMiB);
  // Above the advised room too: trimmed, the heap would grow back without the advice.
  const size_t trim = std::max(size_t{256} * kMiB, 2 * huge_page_bytes);
  mallopt(M_TRIM_THRESHOLD, static_cast<int>(std::min(trim, size_t{1} << 30)));
  // One heap for all threads: each thread's own arena (glibc's default for a second thread) is
  // trimmed by its own rules, and the feature workers' decoded images faulted in again
  // (fast90, 2 workers: 20900 -> 18500 page faults, system time 218 -> 171 ms a run). The
  // threads allocate a few large images per frame, so they hardly wait on the shared heap's lock.
  mallopt(M_ARENA_MAX, 1);
#if defined(MADV_HUGEPAGE)
  // The heap grows by brk, and a region's advice does not pass to what brk adds later: so the
  // heap is made to grow by huge_page_bytes now (a block larger than its free top, with that
  // much padding), and the new region is advised. The block itself is freed at once, and the
  // heap's end read after that (the free may trim a little of it).
  constexpr size_t kHugePage = size_t{2} << 20;
  constexpr int kDefaultTopPad = 128 * 1024;  // glibc's (mallopt(3))
  if (huge_page_bytes < kHugePage || huge_page_bytes > (size_t{512} << 20)) return 0;
  mallopt(M_TOP_PAD, static_cast<int>(huge_page_bytes));
  const size_t free_top = mallinfo2().keepcost;
  void* probe = std::malloc(free_top + kMiB);
  const auto begin = reinterpret_cast<std::uintptr_t>(probe);
  std::free(probe);
  const auto top = reinterpret_cast<std::uintptr_t>(sbrk(0));
  mallopt(M_TOP_PAD, kDefaultTopPad);
  // A block glibc mapped by itself (the heap could not grow) lies elsewhere: nothing to advise.
  if (probe == nullptr || begin >= top) return 0;
  const std::uintptr_t first = (begin + kHugePage - 1) / kHugePage * kHugePage;
  const std::uintptr_t last = top / kHugePage * kHugePage;
  if (last <= first) return 0;
  // NOLINTNEXTLINE(performance-no-int-to-ptr): the heap's own addresses
  if (madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE) != 0) return 0;
  return last - first;
#endif
  // NOLINTEND(concurrency-mt-unsafe)
#endif
  return 0;
}

}  // namespace rgbdvo
