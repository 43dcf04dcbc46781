#pragma once
// The process's heap set up for images. Every frame allocates and frees images of about a
// megabyte (the decoded colour and depth, the depth the odometry keeps, the scale space); glibc's
// defaults map such blocks afresh and hand them back on free, so every frame pays its page faults
// again, and a fresh 4 KiB page costs about 10 us on a virtual machine
// (docs/decisions/0027-memory-kept-by-the-allocator.md, 0045-page-faults-and-huge-pages.md).
// A process-wide policy: the program's main calls it first, libraries leave the heap alone.

#include <cstddef>

namespace rgbdvo {

// Large blocks are taken from and kept in glibc's one heap (not mapped and unmapped), and the
// heap's next `huge_page_bytes` are advised to transparent huge pages, so that the images'
// memory is faulted in 2 MiB at a time. Call before any thread starts (mallopt is not
// thread-safe). Returns the bytes advised: 0 where there is no glibc, no transparent huge
// pages, or the heap could not grow (the heap then works as before, page by page). At most
// 512 MiB; the heap is not trimmed below twice huge_page_bytes (or 256 MiB).
size_t SetUpImageHeap(size_t huge_page_bytes);

}  // namespace rgbdvo
