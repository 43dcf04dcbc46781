#pragma once
// A large float buffer that the kernel may back with transparent huge pages (2 MiB). A fresh
// 4 KiB page costs a page fault when first touched, and on a virtual machine a fault costs about
// 10 us: the SIFT scale space's thousands of small pages are a dozen huge ones
// (docs/decisions/0045-page-faults-and-huge-pages.md). The advice is only advice:
// where the kernel offers no huge pages (THP disabled, another OS) the buffer is an ordinary one.

#include <cstddef>
#include <memory>
#include <utility>

namespace rgbdvo {

class HugePageBuffer {
 public:
  HugePageBuffer() = default;
  // Room for `floats` floats, not initialised; throws std::bad_alloc.
  explicit HugePageBuffer(size_t floats);
  // Moved from, a buffer is empty (size 0), as a default one.
  HugePageBuffer(HugePageBuffer&& other) noexcept
      : data_(std::move(other.data_)), size_(std::exchange(other.size_, 0)) {}
  HugePageBuffer& operator=(HugePageBuffer&& other) noexcept {
    data_ = std::move(other.data_);
    size_ = std::exchange(other.size_, 0);
    return *this;
  }
  float* data() const { return data_.get(); }
  size_t size() const { return size_; }

 private:
  struct Free {
    void operator()(float* p) const;
  };
  std::unique_ptr<float[], Free> data_;
  size_t size_ = 0;
};

}  // namespace rgbdvo
