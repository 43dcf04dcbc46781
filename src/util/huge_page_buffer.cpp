#include "rgbdvo/util/huge_page_buffer.hpp"

#include <cstdlib>
#include <new>
#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace rgbdvo {

HugePageBuffer::HugePageBuffer(size_t floats) : size_(floats) {
  constexpr size_t kHugePage = size_t{2} << 20;
  // Whole huge pages, aligned to one: the kernel backs only aligned 2 MiB ranges with them.
  const size_t bytes = (floats * sizeof(float) + kHugePage - 1) / kHugePage * kHugePage;
  void* p = std::aligned_alloc(kHugePage, bytes);
  if (p == nullptr) throw std::bad_alloc();
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  madvise(p, bytes, MADV_HUGEPAGE);  // advice: where it fails the pages are ordinary ones
#endif
  data_.reset(static_cast<float*>(p));
}

void HugePageBuffer::Free::operator()(float* p) const { std::free(p); }

}  // namespace rgbdvo
